// What a report contains and how it is drawn. The defaults give what most
// readers want: PNG plots for index.html and one multi-page report.pdf.
#pragma once

#include <string>
#include <vector>

#include "deb/core/enum_names.h"

namespace deb {

// File formats of the plots: kPng and kSvg write one file per plot under
// plots/ (index.html shows the PNGs, or the SVGs without PNGs); kPdf writes
// report.pdf, a typeset document holding the tables and every plot.
enum class PlotFormat { kPng, kPdf, kSvg };
inline constexpr EnumName<PlotFormat> kPlotFormatNames[] = {
    {PlotFormat::kPng, "png"}, {PlotFormat::kPdf, "pdf"}, {PlotFormat::kSvg, "svg"}};
constexpr EnumNames<PlotFormat> NamesOf(PlotFormat) { return kPlotFormatNames; }
// @throws InputError quoting the text and listing png, pdf, svg.
inline PlotFormat ParsePlotFormat(const std::string& text) { return ParseEnum<PlotFormat>(text, "plot format"); }

struct ReportOptions {
  std::vector<PlotFormat> formats = {PlotFormat::kPng, PlotFormat::kPdf};
  bool plots = true;         // false: tables, data and documents only; gnuplot is not needed
  // Without plots: still write each plot's CSV and gnuplot script under
  // plots/, to draw later (false: no plots/ directory at all).
  bool plot_scripts = true;
  bool asd = false;          // spectra as ASD (unit/sqrt(Hz)) instead of PSD
  bool reverse_cps = false;  // add a stacked reverse-CPS plot per output
  bool progress = false;     // report progress on stderr (the caller decides, e.g. isatty)
  int threads = 0;           // gnuplot processes at a time; <= 0: DefaultThreadCount()
  int digits = 4;            // significant digits of every number in tables, the console and plot labels (1..15)
  bool force = false;        // replace an output directory deb did not write (deb/core/output_dir.h)
  // gnuplot executable; empty: $DEB_GNUPLOT if set, else "gnuplot" on PATH.
  std::string gnuplot;

  bool Has(PlotFormat format) const;
  // False, with the reason in *error, for an empty or repeated format list.
  bool IsValid(std::string* error) const;
};

}  // namespace deb
