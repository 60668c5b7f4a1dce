#include "tools/run_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/budget/groups.h"
#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/file_name.h"
#include "deb/load/budget_yaml.h"
#include "tools/budget_overrides_option.h"
#include "tools/report_flags.h"

namespace deb::tools {

struct RunCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
  std::string group;                      // --group
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool strict = false;
  ReportFlags flags;
};

namespace {

// "x, y (band 1-10 Hz)": the outputs and bands that fail their requirement.
std::string FailingText(const BudgetResult& result) {
  std::string which;
  for (const auto& o : result.outputs) {
    if (!o.pass()) which += (which.empty() ? "" : ", ") + o.name;
    for (const auto& b : o.band_requirements) {
      if (b.pass()) continue;
      char band[96];
      std::snprintf(band, sizeof band, " (band %g-%g Hz)", b.requirement.lo_hz, b.requirement.hi_hz);
      which += (which.empty() ? "" : ", ") + o.name + band;
    }
  }
  return which;
}

}  // namespace

RunCommand::RunCommand() : options_(std::make_unique<Options>()) {}
RunCommand::~RunCommand() = default;

CLI::App* RunCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* run = app.add_subcommand("run", "Evaluate a budget and write its report directory");
  run->add_option("budget", s.budget_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  AddOverridesOption(run, &s.overrides);
  run->add_option("--group", s.group,
                  "Report one sub-tree: only the contributors in this group or below it (e.g. stage/amplifier); "
                  "default directory reports/<budget-name>_<group>");
  run->add_option("--out,-o", s.out_dir, "Report directory (default: reports/<budget-name>)");
  run->add_option("--threads,-j", s.threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet,-q", s.quiet, "Print nothing but warnings and errors");
  run->add_flag("--strict", s.strict, "Exit with code 5 when an output fails its requirement (report still written)");
  AddReportFlags(run, &s.flags);
  return run;
}

int RunCommand::Run() const {
  const Options& s = *options_;
  const ReportOptions report = s.flags.Options();
  Budget budget = LoadBudgetFile(s.budget_file, s.overrides);
  if (!s.group.empty()) budget = SelectGroup(budget, s.group);
  // reports/<budget-name>, or reports/<budget-name>_<group>.
  const std::string default_name = s.group.empty() ? budget.name : budget.name + "_" + FileNameWord(s.group);
  const std::string out_dir =
      s.out_dir.empty() ? (std::filesystem::path("reports") / default_name).string() : s.out_dir;
  EngineOptions options;
  options.threads = s.threads;
  const auto t0 = std::chrono::steady_clock::now();
  const BudgetResult result = Evaluate(budget, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& w : result.warnings) std::fprintf(stderr, "deb: warning: %s\n", w.c_str());
  if (!s.quiet) PrintConsoleSummary(result, seconds, report.digits);
  // A reproducible report (SOURCE_DATE_EPOCH set) records no wall time.
  RunInfo info;
  info.budget_file = s.budget_file;
  info.threads = s.threads;
  if (!Reproducible()) info.seconds = seconds;
  WriteCommandReport(result, info, report, s.threads, s.quiet, out_dir, s.flags.exports);
  if (!s.quiet) std::printf("\nreport: %s\n", out_dir.c_str());
  int failed = 0;
  for (const auto& o : result.outputs) failed += o.AllPass() ? 0 : 1;
  if (!s.strict || failed == 0) return 0;
  std::fprintf(stderr, "deb: %d output(s) fail their requirement (--strict): %s\n", failed,
               FailingText(result).c_str());
  return kExitRequirement;
}

}  // namespace deb::tools
