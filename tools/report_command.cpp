#include "tools/report_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "deb/core/error.h"
#include "deb/results/result_store.h"
#include "tools/report_flags.h"

namespace deb::tools {

struct ReportCommand::Options {
  std::string input;  // a result directory, or its result.h5
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  ReportFlags flags;
};

ReportCommand::ReportCommand() : options_(std::make_unique<Options>()) {}
ReportCommand::~ReportCommand() = default;

CLI::App* ReportCommand::Register(CLI::App& app) {
  Options& o = *options_;
  CLI::App* cmd = app.add_subcommand(
      "report", "Redraw a report directory from its result store (result.h5), without evaluating anything");
  cmd->add_option("result", o.input, "Result directory written by deb run (or its result.h5)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--out,-o", o.out_dir, "Report directory (default: the result directory itself)");
  cmd->add_option("--threads,-j", o.threads, "gnuplot processes at a time (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet,-q", o.quiet, "Print nothing but warnings and errors");
  AddReportFlags(cmd, &o.flags);
  return cmd;
}

int ReportCommand::Run() const {
  namespace fs = std::filesystem;
  const Options& o = *options_;
  const fs::path input(o.input);
  const bool is_dir = fs::is_directory(input);
  const fs::path store = is_dir ? input / kResultStoreFile : input;
  if (!fs::is_regular_file(store))
    throw InputError(o.input + ": holds no result store (" + kResultStoreFile +
                     "); deb run writes one into every report directory");
  const fs::path result_dir = is_dir ? input : store.parent_path().empty() ? fs::path(".") : store.parent_path();
  RunInfo info;
  const BudgetResult result = ReadResultStore(store.string(), &info);

  const ReportOptions report = o.flags.Options();
  std::vector<ExportFormat> exports = o.flags.exports;
  const std::string out = o.out_dir.empty() ? result_dir.string() : o.out_dir;
  // Redrawn in place, the directory keeps the exports it had.
  std::error_code ec;
  if (fs::equivalent(out, result_dir, ec))
    for (const EnumName<ExportFormat>& f : kExportFormatNames) {
      const std::vector<std::string> files = ExportFileNames(result, f.value);
      if (!files.empty() && fs::is_regular_file(result_dir / files.front(), ec) &&
          std::find(exports.begin(), exports.end(), f.value) == exports.end())
        exports.push_back(f.value);
    }
  info.threads = o.threads;
  if (!o.quiet) PrintConsoleSummary(result, info.seconds, report.digits);
  WriteCommandReport(result, info, report, o.threads, o.quiet, out, exports);
  if (!o.quiet)
    std::printf("\nreport: %s (redrawn from %s: budget %s%s)\n", out.c_str(), store.string().c_str(),
                result.outline.name.c_str(),
                info.budget_sha256.empty() ? "" : (", SHA-256 " + info.budget_sha256.substr(0, 12) + "...").c_str());
  return 0;
}

}  // namespace deb::tools
