// Internal: not part of the public API.
// report.pdf as a document: page 1 names the budget, its file and digest
// and gives the verdict (one row per output: requirements, values,
// PASS/FAIL and, when failing, what would fix it); then the contents, an
// overview, one section per output (verdict line, tables, its plots grouped
// by kind, then its paths) and the warnings and conventions. This layer
// decides what goes where; pdf_document.h typesets and draws it.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/document/pdf_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

struct ReportPdfInputs {
  const BudgetResult* result = nullptr;
  ReportFacts facts;
  std::string sha256;                  // of the budget file; "" when unknown
  std::string create_date;             // ISO 8601, the report's date
  const std::vector<Plot>* plots = nullptr;
  std::string figure_dir;              // holds <plot name>.svg drawn with PdfFigureTerminal
  int digits = 4;                      // significant digits of the tables (deb run --digits)
};

// The document: its blocks, metadata and page footer.
PdfDocumentSpec ReportPdfSpec(const ReportPdfInputs& in);

// Whether report.pdf draws plot `p` (only these need a figure SVG): every
// plot but an output's path Bode figures, which the section Paths lists.
bool DrawnInPdf(const Plot& p);

// gnuplot's terminal for a figure of report.pdf: an SVG that, placed across
// the text width, sets a line of width 1 in a plot script at >= 1.5 pt on
// paper and the plots' base font at 8 pt.
std::string PdfFigureTerminal(const Plot& p);

// The width of a figure's canvas in report.pdf and the study PDFs: set
// across the text width (PdfFigureTerminal).
inline constexpr int kPdfFigureWidthPx = 662;
// The height of plot `p`'s figure canvas in px: its pdf_height_px, else by
// its kind.
int PdfFigureHeightPx(const Plot& p);
// Plot `p` as a figure block of a PDF, its SVG <name>.svg in `figure_dir`,
// with its canvas (so that its layout can be planned before it is drawn).
PdfBlock FigureOfPlot(const Plot& p, const std::string& figure_dir);
// The layout of `spec` (its figures made by FigureOfPlot) with every
// figure free to be drawn down to 2/3 of its height, across the text
// width, rather than leave the rest of a page empty: the height in px each
// is to be drawn at, by its SVG's file stem (the plot's name). Draw the
// plots at these heights, then typeset.
std::map<std::string, int> FittedFigureHeights(PdfDocumentSpec spec);

// The folder, inside a report's or study's plots/, where its PDF's figures
// are drawn (and removed once the PDF is written).
inline constexpr const char* kPdfFigureDir = ".pdf_figures";
// The commands that draw plot `p`'s figure, kPdfFigureDir/<name>.svg, from
// its script in the plots' folder (DrawCommands, PdfFigureTerminal).
std::string PdfFigureCommands(const Plot& p);

// A report table for typesetting: "FAIL" in red, emphasis in bold; a long
// note (at least `min_note_chars` characters) that several rows share, or
// any long note of the column headed "note", is printed once below the table
// and each row carries its mark ("¹").
PdfTable TypesetTable(const Table& table, std::size_t min_note_chars = 24);

// The verdict box of page 1: one row per output with its requirement(s),
// value(s), PASS/FAIL and, for a failing output, GuidanceText.
PdfTable VerdictTable(const BudgetResult& result);

}  // namespace deb::report
