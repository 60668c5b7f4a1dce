// Writes the report of an evaluated budget: plots (stacked CPS, PSD or ASD,
// optional reverse CPS, frequency bands, path magnitudes, an overview), the
// CSV and gnuplot script behind every plot, report.pdf (a typeset document:
// verdict, contents, tables and every plot; report_pdf.h), index.html and
// report.md. This is what `deb run` leaves in its
// report directory beside summary.json and the per-output CSVs.
//
// Layout of a report directory:
//   summary.json, <output>.csv           (WriteReportDirectory, deb/results)
//   result.h5                            (the result store: deb/results/result_store.h;
//                                         `deb report` redraws the report from it)
//   result.mat, result.xlsx              (with exports; deb/results/result_exports.h)
//   index.html, report.md, report.pdf
//   plots/<name>.png|.svg, plots/<name>.csv, plots/<name>.gp, plots/colours.csv
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/results/result_exports.h"
#include "deb/results/result_writer.h"
#include "deb/report/figure/report_options.h"

namespace deb {

// What WriteReport wrote.
struct ReportManifest {
  std::vector<std::string> plots;  // plot names (file stems under plots/), in report order
  std::vector<std::string> files;  // every file written, relative to the report directory
  int title_pages = 0;             // report.pdf's title page (with the verdict): 1, or 0 without report.pdf
  int pdf_pages = 0;               // pages of report.pdf, or 0 without it
};

// Writes the report into `dir`, an existing directory (normally the
// temporary directory of WriteDirectoryAtomically). Links summary.json, the
// output CSVs, result.mat and result.xlsx from index.html if they are
// already in `dir`.
// @throws InputError if the options are invalid, gnuplot is missing or fails
//         (naming the plot and quoting gnuplot), or a file cannot be written.
ReportManifest WriteReport(const BudgetResult& result, const RunInfo& info, const ReportOptions& options,
                           const std::string& dir);

// summary.json, the output CSVs, the files of `exports` (result.mat,
// result.xlsx; listed in the manifest) and WriteReport, atomically into
// out_dir: on any failure out_dir is left as it was.
// @throws InputError if the options are invalid (before anything is
//         written); WriteError for anything else that stops the report
//         (gnuplot missing or failing, a file that cannot be written or
//         read again, what WriteReport finds wrong while writing).
ReportManifest WriteReportDirectory(const BudgetResult& result, const RunInfo& info, const ReportOptions& options,
                                    const std::string& out_dir, const std::vector<ExportFormat>& exports = {});

}  // namespace deb
