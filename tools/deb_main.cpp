// deb: the command-line front end. Thin: parses arguments, calls the library,
// maps failures to documented exit codes, for every subcommand in one place
// (RunMapped below):
//
//   code  meaning                                   raised as
//   0     success
//   2     usage: unknown command or option, a      CLI11's ParseError, an
//         missing or malformed argument            unknown subcommand
//   3     invalid input: budget, data file, model,  deb::InputError, printed
//         parameters                                 "file:line:col: key.path: rule"
//   4     cannot write the output (report, CSV,     deb::WriteError
//         plots), gnuplot missing or failing
//   5     a requirement failed (run --strict; the   a subcommand's return value
//         report is written)
//   6     compared figures moved beyond            deb::tools::FiguresMoved
//         compare --tolerance (reports written)
//   70    internal error (a bug)                    any other exception
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>

#include "deb/core/file_name.h"
#include "deb/budget/engine.h"
#include "deb/budget/groups.h"
#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/parallel.h"
#include "deb/core/process_heap.h"
#include "deb/core/suggest.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/result_exports.h"
#include "deb/results/result_writer.h"
#include "deb/load/sweep_yaml.h"
#include "deb/units/unit.h"
#include "deb/version.h"
#include "tools/budget_overrides_option.h"
#include "tools/compare_command.h"
#include "tools/console_brief.h"
#include "tools/report_command.h"
#include "tools/report_flags.h"
#include "tools/sensitivity_command.h"
#include "tools/spectrum_command.h"
#include "tools/sweep_command.h"

namespace {

constexpr int kExitUsage = 2;
constexpr int kExitInput = 3;
constexpr int kExitWrite = 4;
constexpr int kExitRequirement = 5;
constexpr int kExitMoved = 6;
constexpr int kExitInternal = 70;

// A command line that names no command deb has (CLI11 reports the rest).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Parses the command line and runs the subcommand: its return value, or the
// exit code of what was thrown (the table above), the error printed as
// "deb: error: ..." (CLI11 prints its own usage errors, and --help).
template <typename F>
int RunMapped(CLI::App& app, F&& parse_and_run) {
  try {
    return parse_and_run();
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "deb: %s\n", e.what());
    return kExitUsage;
  } catch (const deb::InputError& e) {
    std::fprintf(stderr, "deb: error: %s\n", e.what());
    return kExitInput;
  } catch (const deb::WriteError& e) {
    std::fprintf(stderr, "deb: error: %s\n", e.what());
    return kExitWrite;
  } catch (const deb::tools::FiguresMoved& e) {
    std::fprintf(stderr, "deb: %s\n", e.what());
    return kExitMoved;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deb: internal error: %s\n", e.what());
    return kExitInternal;
  } catch (...) {
    std::fprintf(stderr, "deb: internal error: an unknown exception\n");
    return kExitInternal;
  }
}

int Run(const std::string& budget_file, const std::vector<deb::BudgetOverride>& overrides, const std::string& group,
        std::string out_dir, int threads, bool quiet, bool strict, deb::ReportOptions report,
        const std::vector<deb::ExportFormat>& exports) {
  deb::Budget budget = deb::LoadBudgetFile(budget_file, overrides);
  if (!group.empty()) budget = deb::SelectGroup(budget, group);
  if (out_dir.empty())
    out_dir = (std::filesystem::path("reports") /
               (group.empty() ? budget.name : budget.name + "_" + deb::FileNameWord(group)))
                  .string();
  deb::EngineOptions options;
  options.threads = threads;
  const auto t0 = std::chrono::steady_clock::now();
  const deb::BudgetResult result = deb::Evaluate(budget, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& w : result.warnings) std::fprintf(stderr, "deb: warning: %s\n", w.c_str());
  if (!quiet) deb::tools::PrintBrief(result, seconds, report.digits);
  // A reproducible report (SOURCE_DATE_EPOCH set) records no wall time.
  deb::RunInfo info;
  info.budget_file = budget_file;
  info.threads = threads;
  if (!deb::Reproducible()) info.seconds = seconds;
  deb::tools::WriteCommandReport(result, info, report, threads, quiet, out_dir, exports);
  if (!quiet) std::printf("\nreport: %s\n", out_dir.c_str());
  int failed = 0;
  for (const auto& o : result.outputs) failed += o.AllPass() ? 0 : 1;
  if (strict && failed > 0) {
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
    std::fprintf(stderr, "deb: %d output(s) fail their requirement (--strict): %s\n", failed, which.c_str());
    return kExitRequirement;
  }
  return 0;
}

int Check(const std::string& budget_file, const std::vector<deb::BudgetOverride>& overrides) {
  const deb::Budget budget = deb::LoadBudgetFile(budget_file, overrides);
  // Everything run checks of its input before computing: what check accepts, run accepts.
  const deb::EvaluationPlan plan = deb::PlanEvaluation(budget);
  const deb::FrequencyGrid& grid = plan.grid;
  // Every sweep variant is loaded and validated, as deb sweep would before computing.
  std::optional<deb::SweepBudget> sweep;
  if (budget.has_sweep) {
    sweep = deb::LoadSweepFile(budget_file, overrides);
    deb::LoadSweepVariants(*sweep);
  }
  std::printf("budget %s: valid\n", budget.name.c_str());
  if (!budget.description.empty()) std::printf("  %s\n", budget.description.c_str());
  std::printf("grid: %s, %zu frequencies, %g-%g Hz\n", deb::ToString(budget.grid.kind).c_str(), grid.size(),
              grid.min_hz(), grid.max_hz());
  std::printf("sources:\n");
  for (const auto& s : budget.sources) {
    std::printf("  %-20s %d channel(s) in %s: %s\n", s.name.c_str(), s.channels(), s.unit.c_str(),
                s.spectrum->Describe().c_str());
  }
  std::printf("paths:\n");
  for (const auto& p : budget.paths) {
    if (p.HasMeasuredData()) {
      const std::vector<double> f = p.measured->DataFrequencies();
      std::printf("  %-20s %d input(s) -> %d output(s), measured frequency data (%zu points, %g-%g Hz)%s\n",
                  p.name.c_str(), p.system.inputs(), p.system.outputs(), f.size(), f.front(), f.back(),
                  p.measured->HasLoopAroundData() ? ", loop stability not verified" : "");
      continue;
    }
    if (p.IsModal()) {
      const deb::ModalModel& m = *p.modal;
      const auto [lo, hi] = std::minmax_element(m.f_hz.begin(), m.f_hz.end());
      std::printf("  %-20s %d input(s) -> %d output(s), %d mode(s), %g-%g Hz, %s\n", p.name.c_str(),
                  p.system.inputs(), p.system.outputs(), m.modes(), *lo, *hi,
                  *lo > 0.0 ? "stable" : "rigid-body mode(s) at 0 Hz");
      continue;
    }
    std::printf("  %-20s %d input(s) -> %d output(s), %d state(s), %s\n", p.name.c_str(), p.system.inputs(),
                p.system.outputs(), p.system.states(),
                p.system.IsStable() ? "stable" : "unstable: no contributor may use it");
  }
  if (!plan.loops.empty()) std::printf("feedback loops:\n");
  for (const deb::LoopResult& loop : plan.loops) {
    std::string paths;
    for (const std::string& p : loop.paths) paths += (paths.empty() ? "" : ", ") + p;
    std::printf("  %s closed by %s (%s feedback), in %s\n    %s\n", loop.plant.c_str(), loop.controller.c_str(),
                loop.sign < 0 ? "negative" : "positive", paths.c_str(), deb::MarginsText(loop).c_str());
  }
  std::printf("contributors:\n");
  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const deb::Contributor& c = budget.contributors[ci];
    std::printf("  %-20s source %s, path %s, exact variance: %s\n", c.name.c_str(), c.source.c_str(),
                deb::ContributorPathKey(c).c_str(), deb::ToString(c.exact).c_str());
    // Why there will be none where it was asked for, once per distinct reason (the outputs usually share it).
    std::vector<std::string> reasons;
    for (const std::string& why : plan.exact_refusal[ci])
      if (c.exact != deb::ExactVariance::kOff && !why.empty() &&
          std::find(reasons.begin(), reasons.end(), why) == reasons.end())
        reasons.push_back(why);
    for (const std::string& why : reasons) std::printf("  %-20s no exact variance: %s\n", "", why.c_str());
  }
  std::printf("outputs:\n");
  for (const auto& o : budget.outputs) {
    std::printf("  %-20s signal %s in %s", o.name.c_str(), o.signal.c_str(), o.unit.c_str());
    if (o.weighting) std::printf(", weighted (%s)", o.weighting->unit.c_str());
    if (o.metric) std::printf(", %s", o.metric->Describe().c_str());
    if (o.rms_max) std::printf(", rms_max %g", *o.rms_max);
    std::printf("\n");
  }
  if (!budget.covariance.empty()) {  // validated with the budget: outputs that exist, once each, without a metric
    std::string names;
    for (const std::string& name : budget.covariance) names += (names.empty() ? "" : ", ") + name;
    std::printf("covariance of %zu outputs: %s (deb run: summary.json and the reports)\n", budget.covariance.size(),
                names.c_str());
  }
  std::fflush(stdout);  // the warnings after the description, also when both go to one file
  for (const auto& w : plan.warnings) std::fprintf(stderr, "deb: warning: %s\n", w.c_str());
  if (sweep) {
    std::printf("sweep: %s of %zu parameter(s), %zu variants, each valid:\n", deb::ToString(sweep->spec.mode).c_str(),
                sweep->spec.parameters.size(), sweep->variant_count);
    for (const deb::SweepParameter& p : sweep->spec.parameters) {
      std::printf("  %-40s %zu value(s): %s", p.key_path.c_str(), p.values.size(), p.Text(p.values.front()).c_str());
      if (p.values.size() > 1) std::printf(" ... %s", p.Text(p.values.back()).c_str());
      if (!p.label.empty() || !p.unit.empty()) std::printf(" (%s)", p.AxisTitle().c_str());
      std::printf("\n");
    }
  }
  return 0;
}

int Model(const std::string& budget_file, const std::vector<deb::BudgetOverride>& overrides) {
  const deb::Budget budget = deb::LoadBudgetFile(budget_file, overrides);
  if (budget.models.empty()) {
    std::printf("budget %s has no physical model (no path of type isolation_system)\n", budget.name.c_str());
    return 0;
  }
  for (const auto& m : budget.models) std::printf("%s\n", m.report.c_str());
  std::printf("paths from the model(s):\n");
  for (const auto& p : budget.paths) {
    if (p.description.empty()) continue;
    std::printf("  %-28s %s\n", p.name.c_str(), p.description.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  deb::KeepHeapForLargeBlocks();
  // A file-size limit (ulimit -f) makes a write fail (EFBIG): reported as a
  // write error, exit 4, with nothing left behind, instead of death by
  // SIGXFSZ halfway through a report.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"deb: frequency-domain dynamic error budgeting for precision machines"};
  app.set_version_flag("--version", std::string("deb ") + DEB_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 2 usage error, 3 invalid input (budget, data file, model), "
      "4 cannot write the report, 5 a requirement failed (run --strict), 6 compared figures moved "
      "(compare --tolerance), 70 internal error.");

  std::string budget_file, out_dir;
  int threads = 0;
  bool quiet = false;
  bool strict = false;
  CLI::App* run = app.add_subcommand("run", "Evaluate a budget and write its report directory");
  run->add_option("budget", budget_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  std::vector<deb::BudgetOverride> run_overrides, check_overrides, model_overrides;
  deb::tools::AddOverridesOption(run, &run_overrides);
  std::string run_group;
  run->add_option("--group", run_group,
                  "Report one sub-tree: only the contributors in this group or below it (e.g. stage/amplifier); "
                  "default directory reports/<budget-name>_<group>");
  run->add_option("--out,-o", out_dir, "Report directory (default: reports/<budget-name>)");
  run->add_option("--threads,-j", threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet,-q", quiet, "Print nothing but warnings and errors");
  run->add_flag("--strict", strict, "Exit with code 5 when an output fails its requirement (report still written)");
  deb::tools::ReportFlags run_flags;
  deb::tools::AddReportFlags(run, &run_flags);

  std::string check_file;
  CLI::App* check = app.add_subcommand("check", "Validate a budget and describe it, without computing");
  check->add_option("budget", check_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  deb::tools::AddOverridesOption(check, &check_overrides);

  std::string model_file;
  CLI::App* model = app.add_subcommand(
      "model", "Describe the physical models of a budget: natural frequencies, mode shapes, static pre-stress");
  model->add_option("budget", model_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  deb::tools::AddOverridesOption(model, &model_overrides);

  deb::tools::SpectrumCommand spectrum_command;
  CLI::App* spectrum = spectrum_command.Register(app);
  deb::tools::CompareCommand compare_command;
  CLI::App* compare = compare_command.Register(app);
  deb::tools::ReportCommand report_command;
  CLI::App* redraw = report_command.Register(app);
  deb::tools::SweepCommand sweep_command;
  CLI::App* sweep = sweep_command.Register(app);
  deb::tools::SensitivityCommand sensitivity_command;
  CLI::App* sensitivity = sensitivity_command.Register(app);

  return RunMapped(app, [&] {
    // A first word that is no command: say so, and offer the nearest one
    // (CLI11 alone answers "A subcommand is required").
    if (argc > 1 && argv[1][0] != '-') {
      std::vector<std::string> names;
      std::string list;
      for (const CLI::App* sub : app.get_subcommands({})) {
        names.push_back(sub->get_name());
        list += (list.empty() ? "" : ", ") + sub->get_name();
      }
      if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
        const std::string near = deb::NearestName(argv[1], names);
        throw UsageError("unknown command '" + deb::Excerpt(argv[1]) + "'" +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; the commands are " + list +
                         " (deb --help)");
      }
    }
    app.parse(argc, argv);
    if (*run)
      return Run(budget_file, run_overrides, run_group, out_dir, threads, quiet, strict, run_flags.Options(),
                 run_flags.exports);
    if (*check) return Check(check_file, check_overrides);
    if (*model) return Model(model_file, model_overrides);
    if (*spectrum) return spectrum_command.Run();
    if (*redraw) return report_command.Run();
    if (*compare) return compare_command.Run();
    if (*sweep) return sweep_command.Run();
    if (*sensitivity) return sensitivity_command.Run();
    return kExitUsage;
  });
}
