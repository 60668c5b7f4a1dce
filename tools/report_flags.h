// The options of a report directory, shared by `deb run` (which evaluates a
// budget and writes one) and `deb report` (which redraws one from its result
// store): --force, --format, --digits, --asd, --reverse-cps, --no-plots,
// --plot-scripts and --export, with the same meaning and checks in both; and
// how both print the result and write the directory.
#pragma once

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cstdio>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/results/result_exports.h"
#include "deb/report/budget/console_summary.h"
#include "deb/report/budget/report_writer.h"
#include "deb/report/figure/report_options.h"

namespace deb::tools {

struct ReportFlags {
  ReportOptions report;
  bool plot_scripts = false;  // --plot-scripts (with --no-plots)
  std::vector<ExportFormat> exports;

  // The options as parsed: plot scripts are written with the plots, or when
  // asked for without them.
  ReportOptions Options() const {
    ReportOptions r = report;
    r.plot_scripts = report.plots || plot_scripts;
    return r;
  }
};

// Adds the options to `app`, bound to *flags (which must outlive the parse).
inline void AddReportFlags(CLI::App* app, ReportFlags* flags) {
  ReportOptions& report = flags->report;
  app->add_flag("--force", report.force, "Replace --out even if it is not a directory deb wrote");
  app->add_option_function<std::vector<std::string>>(
         "--format",
         [&report](const std::vector<std::string>& names) {
           if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
             throw CLI::ValidationError("--format", "a format is given twice");
           report.formats.clear();
           for (const auto& n : names) report.formats.push_back(ParsePlotFormat(n));
         },
         "Plot formats, comma-separated: png (plots/*.png), pdf (report.pdf), svg; default png,pdf")
      ->delimiter(',')
      ->check(CLI::IsMember({"png", "pdf", "svg"}));
  app->add_option("--digits", report.digits,
                  "Significant digits of the numbers in the console table, the report's tables and plot labels "
                  "(default 4)")
      ->check(CLI::Range(1, 15));
  app->add_flag("--asd", report.asd, "Plot amplitude spectral densities (unit/sqrt(Hz)) instead of PSDs");
  app->add_flag("--reverse-cps", report.reverse_cps, "Add a stacked reverse-CPS plot (variance above f) per output");
  app->add_flag_callback("--no-plots", [&report] { report.plots = false; },
                         "Write tables, data and documents only, no plots/ directory; gnuplot is not needed");
  app->add_flag("--plot-scripts", flags->plot_scripts,
                "With --no-plots: still write each plot's CSV and gnuplot script under plots/, to draw later");
  std::vector<ExportFormat>& exports = flags->exports;
  app->add_option_function<std::vector<std::string>>(
         "--export",
         [&exports](const std::vector<std::string>& names) {
           for (const auto& n : names) {
             try {
               exports.push_back(ParseExportFormat(n));
             } catch (const InputError& e) {
               throw CLI::ValidationError("--export", e.what());
             }
           }
         },
         "Also write a CSV table per output (csv: <output>.csv), the result for MATLAB (mat: result.mat) or Excel "
         "(xlsx: result.xlsx) into the report "
         "directory; repeatable or comma-separated")
      ->delimiter(',');
}

// The console summary (deb/report/budget/console_summary.h), flushed before
// the report's progress and gnuplot's time.
inline void PrintConsoleSummary(const BudgetResult& result, std::optional<double> evaluation_seconds, int digits) {
  std::fputs(report::ConsoleSummary(result, evaluation_seconds, digits).c_str(), stdout);
  std::fflush(stdout);
}

// WriteReportDirectory for a command: gnuplot and the result files on
// `threads`, progress on stderr when it is a terminal and not `quiet`.
inline void WriteCommandReport(const BudgetResult& result, const RunInfo& info, ReportOptions report, int threads,
                               bool quiet, const std::string& out_dir, const std::vector<ExportFormat>& exports) {
  report.threads = threads;
  report.progress = !quiet && ::isatty(STDERR_FILENO);
  WriteReportDirectory(result, info, report, out_dir, exports);
}

}  // namespace deb::tools
