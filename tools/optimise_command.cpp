#include "tools/optimise_command.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/output_dir.h"
#include "deb/load/optimise_yaml.h"
#include "deb/report/budget/report_writer.h"
#include "deb/report/compare/optimise_plots.h"
#include "deb/report/compare/overlay_plots.h"
#include "deb/results/optimise_files.h"
#include "tools/budget_overrides_option.h"
#include "tools/mpi_timeout_option.h"
#include "tools/run_command.h"

#ifdef DEB_MPI
#include "deb/distributed/mpi_queue.h"
#endif

namespace deb::tools {

namespace fs = std::filesystem;

struct OptimiseCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
  std::vector<std::string> vary;
  std::string objective;  // an output, or max-ratio; "" : the only output, else max-ratio
  std::string method = "auto";
  int starts = 1;
  int max_evaluations = 200;
  double tolerance = 1e-8;
  unsigned long long seed = 1;
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;
  bool plots = true;
  std::string robust;  // "P95": the percentile under the tolerances
  int robust_samples = 64;
  double timeout_s = 0.0;  // --timeout, under mpirun
};

namespace {

// "P95" -> 95; NaN unless it is P (or p) and a number in (0, 100).
double PercentileOf(const std::string& text) {
  if (text.size() < 2 || (text[0] != 'P' && text[0] != 'p')) return std::nan("");
  char* end = nullptr;
  const double p = std::strtod(text.c_str() + 1, &end);
  return end != nullptr && *end == '\0' && p > 0.0 && p < 100.0 ? p : std::nan("");
}

}  // namespace

OptimiseCommand::OptimiseCommand() : options_(std::make_unique<Options>()) {}
OptimiseCommand::~OptimiseCommand() = default;

CLI::App* OptimiseCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand("optimise", "Choose parameters within their bounds: minimise an RMS, meet every requirement");
  c->add_option("budget", s.budget_file, "Budget YAML file whose parameters have min and max")
      ->required()
      ->check(CLI::ExistingFile);
  c->add_option("--vary", s.vary, "The parameters to choose, comma-separated (each with min and max in the budget)")
      ->required()
      ->delimiter(',');
  c->add_option("--objective", s.objective,
                "An output whose RMS is minimised, a weighted sum of outputs' RMS ('z + 0.5*x', each RMS in its "
                "output's unit), or max-ratio (the largest RMS / requirement); default: the only output, else max-ratio");
  c->add_option("--method", s.method, "auto (default: bobyqa without requirements, else slsqp), cobyla, bobyqa (bounds only), slsqp or mma (with gradients)")
      ->check(CLI::IsMember({"auto", "cobyla", "bobyqa", "slsqp", "mma"}));
  c->add_option("--starts", s.starts, "Starts: the nominal design, then Sobol points of the bounds (default 1)")
      ->check(CLI::Range(1, kMaxOptimiseStarts));
  c->add_option("--max-evaluations", s.max_evaluations, "Budgets evaluated per start, at most (default 200)")
      ->check(CLI::Range(1, kMaxEvaluationsPerStart));
  c->add_option("--tolerance", s.tolerance, "Of each variable, relative to its range (default 1e-8)")
      ->check(CLI::Range(1e-12, 0.1));
  c->add_option("--seed", s.seed, "Seed of the starts' Sobol points and the robust samples (default 1)");
  c->add_option("--robust", s.robust,
                "Pxx: minimise the xx-th percentile under the tolerances of the other parameters (their "
                "distributions), each requirement's Pxx within its limit (e.g. P95)")
      ->check([](const std::string& v) {
        return std::isnan(PercentileOf(v)) ? "give a percentile as Pxx, 0 < xx < 100 (e.g. P95), not '" + v + "'"
                                           : std::string();
      });
  c->add_option("--robust-samples", s.robust_samples,
                "Latin hypercube samples of the tolerances at each design (default 64; the same at every design)")
      ->check(CLI::Range(2, kMaxRobustSamples));
  AddOverridesOption(c, &s.overrides, "--set", "the budget");
  c->add_option("--out,-o", s.out_dir, "Directory (default: reports/<budget-name>_optimum)");
  c->add_option("--threads,-j", s.threads, "Budgets evaluated at once (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; }, "The optimum's report without plots; gnuplot is not needed");
  AddMpiTimeoutOption(c, &s.timeout_s, "one start");
  return c;
}

int OptimiseCommand::Run() const {
  const Options& s = *options_;
  std::optional<double> percentile;
  if (!s.robust.empty()) percentile = PercentileOf(s.robust);
  const OptimiseBudget budget = LoadOptimiseFile(s.budget_file, s.vary, s.overrides, percentile.has_value());
  const OptimiseObjective objective =
      budget.Objective(s.objective, percentile, static_cast<std::size_t>(s.robust_samples), s.seed);
  OptimiseOptions options;
  options.method = ParseEnum<OptimiseMethod>(s.method, "optimisation method");
  options.starts = s.starts;
  options.max_evaluations = s.max_evaluations;
  options.tolerance = s.tolerance;
  options.seed = s.seed;
  options.threads = s.threads;
  StartRunner runner;  // on threads
#ifdef DEB_MPI
  if (MpiSession::Size() > 1) {
    // Under mpirun: the ranks run the starts, one at a time each; rank 0 alone writes.
    runner = [&s](std::size_t count, const std::function<StartOutcome(std::size_t)>& run) {
      const std::vector<std::string> bytes = DistributeBlocks(
          count,
          [&run](std::size_t begin, std::size_t end) {
            std::vector<std::string> out;
            for (std::size_t k = begin; k < end; ++k) out.push_back(StartOutcomeToBytes(run(k)));
            return out;
          },
          s.timeout_s, 1);
      std::vector<StartOutcome> outcomes;
      for (const std::string& b : bytes) outcomes.push_back(StartOutcomeFromBytes(b));
      return outcomes;
    };
  }
#endif
  const OptimiseResult result = RunOptimise(budget.variables, objective, options, budget.loader, runner);
  if (result.starts.empty()) return 0;  // a rank of mpirun other than 0: rank 0 writes

  const std::string dir =
      s.out_dir.empty() ? (fs::path("reports") / (budget.name + "_optimum")).string() : s.out_dir;
  // optimum.yaml extends the original by its path from the directory.
  const std::string extends =
      fs::absolute(s.budget_file).lexically_normal().lexically_relative(fs::absolute(dir).lexically_normal()).string();
  std::vector<std::string> overrides;
  for (const BudgetOverride& o : s.overrides) overrides.push_back(o.key_path + "=" + o.value);
  EngineOptions engine;
  engine.threads = s.threads;
  // The optimum's report: at the tolerances' nominal values. It says that it
  // is the optimum, and of what: its name and description are optimum.yaml's
  // (the budget's own description speaks of the nominal design).
  BudgetResult optimum = Evaluate(budget.loader(budget.Point(result.starts[result.best].values)), engine);
  optimum.outline.name = budget.name + "_optimum";
  optimum.outline.description = OptimumDescription(result, optimum.outline.description);
  if (const std::string bounds = BoundsText(result); !bounds.empty()) optimum.warnings.push_back(bounds);
  // The figures: the history, and for two variables the objective's map.
  std::vector<report::Plot> plots;
  if (s.plots) {
    std::optional<DesignMap> map;
    if (budget.variables.size() == 2) map = MapDesigns(budget.variables, objective, budget.loader, 21, s.threads);
    plots = report::OptimisePlots(result, map);
  }
  ReplaceOptions replace;
  replace.force = s.force;
  ReplaceDirectory(
      dir,
      [&](const std::string& tmp) {
        WriteTextFile((fs::path(tmp) / "summary.json").string(), OptimiseSummaryJson(budget.name, result));
        WriteTextFile((fs::path(tmp) / "history.csv").string(), OptimiseHistoryCsv(result));
        const std::string optimum_yaml = OptimumYaml(extends, budget.name, result, overrides);
        WriteTextFile((fs::path(tmp) / "optimum.yaml").string(), optimum_yaml);
        ReportOptions report;
        report.plots = s.plots;
        // The report is optimum.yaml's: its file (from the report's
        // directory: the same files wherever the study is written), digest
        // and text (the budget's own are another design, the nominal one).
        RunInfo info;
        info.budget_file = "../optimum.yaml";
        info.budget_text = optimum_yaml;
        info.threads = s.threads;
        WriteReportDirectory(optimum, info, report, (fs::path(tmp) / "report").string());
        if (!plots.empty()) {
          const std::string plots_dir = (fs::path(tmp) / "plots").string();
          fs::create_directories(plots_dir);
          report::WritePlotsAsPng(plots, plots_dir, s.threads);
        }
      },
      replace);

  if (!s.quiet) {
    const OptimiseStart& best = result.starts[result.best];
    const std::string what = objective.Text();
    std::printf("optimise %s: %s over %zu parameter(s), %s, %d start(s), %d designs evaluated%s\n",
                budget.name.c_str(), what.c_str(), budget.variables.size(), ToString(result.method).c_str(),
                options.starts, result.evaluations,
                objective.quantile ? (" (" + std::to_string(objective.samples.size()) + " budgets each)").c_str() : "");
    std::printf("gradients: %s\n", result.gradients.c_str());
    std::printf("nominal: %s = %s\n", what.c_str(), SignificantText(result.nominal_objective, 6).c_str());
    std::printf("optimum (start %zu, %s): %s\n", result.best + 1, best.stop.c_str(), OptimumText(result).c_str());
    std::printf("  %s = %s\n", what.c_str(), SignificantText(best.objective, 6).c_str());
    for (const RequirementRatio& q : result.requirements) {
      if (q.margin) {
        std::printf("  %s: %s, required %s%s\n", q.name.c_str(),
                    std::isinf(q.rms) ? "infinite" : SignificantText(q.rms, 5).c_str(),
                    SignificantText(q.limit, 5).c_str(), q.active ? ", active" : "");
        continue;
      }
      std::printf("  %s: %sRMS %s of %s (%s)%s\n", q.name.c_str(), objective.quantile ? ("P" + s.robust.substr(1) + " ").c_str() : "",
                  SignificantText(q.rms, 5).c_str(),
                  SignificantText(q.limit, 5).c_str(), (SignificantText(100.0 * q.ratio(), 4) + " %").c_str(),
                  q.active ? ", active" : "");
    }
    std::printf("results: %s/summary.json, optimum.yaml; the optimum's report: %s/report/\n", dir.c_str(), dir.c_str());
  }
  if (!result.feasible) {
    std::fprintf(stderr,
                 "deb: no design within the bounds meets every requirement; the least violating: %s (largest RMS / "
                 "requirement %s)\n",
                 OptimumText(result).c_str(), SignificantText(result.starts[result.best].worst_ratio, 5).c_str());
    return RunCommand::kExitRequirement;
  }
  return 0;
}

}  // namespace deb::tools
