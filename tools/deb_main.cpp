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
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/parallel.h"
#include "deb/core/process_heap.h"
#include "deb/core/suggest.h"
#include "deb/io/budget_yaml.h"
#include "deb/io/result_exports.h"
#include "deb/io/result_writer.h"
#include "deb/io/sweep_yaml.h"
#include "deb/report/budget/report_writer.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/units/unit.h"
#include "deb/version.h"
#include "tools/budget_overrides_option.h"
#include "tools/compare_command.h"
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

// A group path as part of a directory name: "stage/amplifier" -> "stage_amplifier".
std::string DirectoryWord(const std::string& text) {
  std::string word = text;
  for (char& c : word)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
          c == '.'))
      c = '_';
  return word;
}

// Each group's RMS and share, indented by depth, after the contributors.
void PrintGroups(const deb::OutputResult& o) {
  const std::vector<deb::GroupResult> groups = deb::ComputeGroups(o);
  if (groups.empty()) return;
  std::printf("  %-24s %14s %8s\n", "group", "rms", "share");
  for (const deb::GroupResult& g : groups) {
    const std::string label = std::string(2 * static_cast<std::size_t>(g.depth), ' ') + g.name;
    std::printf("  %-24s %14.6g %7.2f%%\n", label.c_str(), std::sqrt(g.variance), 100.0 * g.share);
  }
}

// The correlation matrix of the budget's `covariance:` outputs (the
// covariance itself is in summary.json).
void PrintCorrelation(const deb::CovarianceResult& cov) {
  std::printf("\ncorrelation of outputs (covariance matrices in summary.json)\n  %-16s", "");
  for (const std::string& name : cov.outputs) std::printf(" %12.12s", name.c_str());
  for (std::size_t a = 0; a < cov.outputs.size(); ++a) {
    std::printf("\n  %-16.16s", cov.outputs[a].c_str());
    for (std::size_t b = 0; b < cov.outputs.size(); ++b) {
      const double r = cov.correlation(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
      if (std::isfinite(r)) std::printf(" %12.3f", r);
      else std::printf(" %12s", "-");
    }
  }
  std::printf("\n");
}

// The figures, and for each output that fails what would fix it; printed
// before the report is drawn (gnuplot takes most of a run).
void PrintBrief(const deb::Budget& budget, const deb::BudgetResult& r, double seconds, int digits) {
  std::printf("budget %s: %zu frequencies, %g-%g Hz, evaluated in %.3f s\n", budget.name.c_str(), r.grid.size(),
              r.grid.min_hz(), r.grid.max_hz(), seconds);
  for (const auto& o : r.outputs) {
    using deb::report::Sig;  // the report's number text: "0.3000", "1.234e-05"
    std::printf("\noutput %s [%s]: rms %s", o.name.c_str(), o.unit.c_str(), Sig(o.rms(), digits).c_str());
    if (o.rms_max) std::printf("  (requirement %g: %s)", *o.rms_max, o.pass() ? "PASS" : "FAIL");
    std::printf("\n  %-24s %14s %8s %14s\n", "contributor", "rms", "share", "exact rms");
    for (std::size_t index : deb::report::ShareOrder(o)) {  // largest first, as in the report
      const auto& c = o.contributors[index];
      const double share = o.variance > 0 ? 100.0 * c.variance / o.variance : 0.0;
      if (c.exact_variance)
        std::printf("  %-24s %14s %7.2f%% %14s\n", c.name.c_str(), Sig(std::sqrt(c.variance), digits).c_str(), share,
                    Sig(std::sqrt(*c.exact_variance), digits).c_str());
      else
        std::printf("  %-24s %14s %7.2f%% %14s\n", c.name.c_str(), Sig(std::sqrt(c.variance), digits).c_str(), share, "-");
      if (!c.top_modes.empty()) {  // a modal path: the modes that carry its exact variance
        std::string modes;
        for (std::size_t i = 0; i < c.top_modes.size() && i < 3; ++i) {
          char one[96];
          std::snprintf(one, sizeof one, "%smode %d, %.*g Hz: %.0f%%", i ? "; " : "", c.top_modes[i].mode, digits,
                        c.top_modes[i].f_hz, 100.0 * c.top_modes[i].share);
          modes += one;
        }
        std::printf("  %-24s %s\n", "", modes.c_str());
      }
      if (!c.channels.empty()) {  // breakdown: channels, largest first
        std::vector<const deb::ContributorResult::ChannelPart*> parts;
        for (const auto& p : c.channels) parts.push_back(&p);
        std::stable_sort(parts.begin(), parts.end(), [](const auto* a, const auto* b) { return a->variance > b->variance; });
        for (const auto* p : parts) {
          const std::string label = "  channel " + p->channel;
          std::printf("  %-24s %14s %7.2f%%\n", label.c_str(), Sig(std::sqrt(std::max(p->variance, 0.0)), digits).c_str(),
                      o.variance > 0 ? 100.0 * p->variance / o.variance : 0.0);
        }
        if (c.cross_variance != 0.0)
          std::printf("  %-24s %14s %7.2f%%  (variance; correlation between channels)\n", "  cross terms",
                      Sig(c.cross_variance, digits).c_str(), o.variance > 0 ? 100.0 * c.cross_variance / o.variance : 0.0);
      }
    }
    PrintGroups(o);
    for (const deb::ReferenceResult& ref : o.references) {
      const double budget = ref.budget_variance;
      std::printf("  reference %s (%g-%g Hz): measured rms %s, budget %s, measured/budget %s, unexplained %s\n",
                  ref.name.c_str(), ref.covered_lo_hz, ref.covered_hi_hz,
                  Sig(std::sqrt(ref.variance), digits).c_str(), Sig(std::sqrt(budget), digits).c_str(),
                  budget > 0 ? Sig(std::sqrt(ref.variance / budget), digits).c_str() : "-",
                  Sig(std::sqrt(std::max(ref.variance - budget, 0.0)), digits).c_str());
    }
    for (const auto& b : o.band_requirements)
      std::printf("  band %g-%g Hz: rms %s (requirement %g: %s)\n", b.requirement.lo_hz, b.requirement.hi_hz,
                  Sig(b.rms(), digits).c_str(), b.requirement.rms_max, b.pass() ? "PASS" : "FAIL");
    if (const auto g = deb::GuideFailure(o, r.grid)) std::printf("  to fix: %s\n", g->sentence.c_str());
  }
  if (r.covariance) PrintCorrelation(*r.covariance);
  std::fflush(stdout);  // before the report's progress and gnuplot's time
}

int Run(const std::string& budget_file, const std::vector<deb::BudgetOverride>& overrides, const std::string& group,
        std::string out_dir, int threads, bool quiet, bool strict, deb::ReportOptions report,
        const std::vector<deb::ExportFormat>& exports) {
  deb::Budget budget = deb::LoadBudgetFile(budget_file, overrides);
  if (!group.empty()) budget = deb::SelectGroup(budget, group);
  if (out_dir.empty())
    out_dir = (std::filesystem::path("reports") /
               (group.empty() ? budget.name : budget.name + "_" + DirectoryWord(group)))
                  .string();
  deb::EngineOptions options;
  options.threads = threads;
  const auto t0 = std::chrono::steady_clock::now();
  const deb::BudgetResult result = deb::Evaluate(budget, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& w : result.warnings) std::fprintf(stderr, "deb: warning: %s\n", w.c_str());
  if (!quiet) PrintBrief(budget, result, seconds, report.digits);
  try {
    report.progress = !quiet && ::isatty(STDERR_FILENO);
    report.threads = threads;
    // A reproducible report (SOURCE_DATE_EPOCH set) records no wall time.
    deb::RunInfo info{budget_file, {}, threads};
    if (!std::getenv("SOURCE_DATE_EPOCH")) info.seconds = seconds;
    deb::WriteReportDirectory(budget, result, info, report, out_dir, exports);
  } catch (const deb::InputError& e) {
    throw deb::WriteError(e.what());  // found while writing: the report cannot be written
  }
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
  deb::UseHugePagesForHeap();
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
  deb::ReportOptions report;
  bool plot_scripts = false;
  run->add_flag("--force", report.force, "Replace --out even if it is not a directory deb wrote");
  run->add_option_function<std::vector<std::string>>(
         "--format",
         [&report](const std::vector<std::string>& names) {
           if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
             throw CLI::ValidationError("--format", "a format is given twice");
           report.formats.clear();
           for (const auto& n : names) report.formats.push_back(deb::ParsePlotFormat(n));
         },
         "Plot formats, comma-separated: png (plots/*.png), pdf (report.pdf), svg; default png,pdf")
      ->delimiter(',')
      ->check(CLI::IsMember({"png", "pdf", "svg"}));
  run->add_option("--digits", report.digits,
                  "Significant digits of the numbers in the console table, the report's tables and plot labels "
                  "(default 4)")
      ->check(CLI::Range(1, 15));
  run->add_flag("--asd", report.asd, "Plot amplitude spectral densities (unit/sqrt(Hz)) instead of PSDs");
  run->add_flag("--reverse-cps", report.reverse_cps, "Add a stacked reverse-CPS plot (variance above f) per output");
  run->add_flag_callback("--no-plots", [&report] { report.plots = false; },
                         "Write tables, data and documents only, no plots/ directory; gnuplot is not needed");
  run->add_flag("--plot-scripts", plot_scripts,
                "With --no-plots: still write each plot's CSV and gnuplot script under plots/, to draw later");
  std::vector<deb::ExportFormat> exports;
  run->add_option_function<std::vector<std::string>>(
         "--export",
         [&exports](const std::vector<std::string>& names) {
           for (const auto& n : names) {
             try {
               exports.push_back(deb::ParseExportFormat(n));
             } catch (const deb::InputError& e) {
               throw CLI::ValidationError("--export", e.what());
             }
           }
         },
         "Also write the result for MATLAB (mat: result.mat) or Excel (xlsx: result.xlsx) into the report "
         "directory; repeatable or comma-separated")
      ->delimiter(',');

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
    // Every command reads units: the database loads while the budget is read.
    const deb::UnitDatabasePreload units;
    if (*run) {
      report.plot_scripts = report.plots || plot_scripts;
      return Run(budget_file, run_overrides, run_group, out_dir, threads, quiet, strict, report, exports);
    }
    if (*check) return Check(check_file, check_overrides);
    if (*model) return Model(model_file, model_overrides);
    if (*spectrum) return spectrum_command.Run();
    if (*compare) return compare_command.Run();
    if (*sweep) return sweep_command.Run();
    if (*sensitivity) return sensitivity_command.Run();
    return kExitUsage;
  });
}
