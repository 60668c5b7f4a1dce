#include "tools/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#include "deb/core/parallel.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/file_digest.h"
#include "deb/report/compare/comparison_directory.h"
#include "deb/report/compare/comparison_documents.h"
#include "deb/report/compare/ratio_plots.h"
#include "deb/report/figure/plot.h"
#include "tools/budget_overrides_option.h"

namespace deb::tools {
namespace {

// A budget file is evaluated (without response traces: compared, not
// drawn); a result directory or summary.json is read (its result store too
// when the overlays are drawn, `plots`).
report::ComparisonInput Load(const std::string& input, const std::vector<BudgetOverride>& overrides, int threads,
                             bool plots) {
  if (!report::IsComparisonBudgetFile(input)) return report::ReadComparisonResult(input, plots);
  const Budget budget = LoadBudgetFile(input, overrides);
  EngineOptions options;
  options.threads = threads;
  options.response_traces = false;
  BudgetResult result = Evaluate(budget, options);
  ResultFigures figures = FiguresOf(budget.name, result);
  figures.budget_sha256 = report::FileSha256(input);
  return {std::move(figures), std::move(result)};
}

}  // namespace

struct CompareCommand::Options {
  std::vector<std::string> inputs;
  std::vector<BudgetOverride> overrides;    // --set: every budget input
  std::vector<BudgetOverride> overrides_b;  // --set-b: the second input (B) only
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;  // --force: replace an output directory deb did not write
  bool plots = true;
  std::optional<double> tolerance;  // --tolerance: relative change that fails the command
};

CompareCommand::CompareCommand() : options_(std::make_unique<Options>()) {}
CompareCommand::~CompareCommand() = default;

CLI::App* CompareCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand(
      "compare", "Compare budgets or result directories: RMS per output, contributor and band, B - A and B / A");
  c->add_option("inputs", s.inputs, "Budget YAML files or result directories (summary.json); the first is A")
      ->required()
      ->expected(2, 1000)
      ->check(CLI::ExistingPath);
  AddOverridesOption(c, &s.overrides, "--set", "every budget input");
  AddOverridesOption(c, &s.overrides_b, "--set-b",
                     "the second input (B) only, after --set: compare a budget with a variant of itself");
  c->add_option("--out,-o", s.out_dir, "Report directory, for two inputs (default: reports/compare_<A>_vs_<B>)");
  c->add_option("--threads,-j", s.threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; },
                       "No overlay plots (drawn only when both inputs are budgets; need gnuplot)");
  c->add_option_function<double>(
       "--tolerance",
       [&s](double rel) {
         if (!(rel >= 0.0) || !std::isfinite(rel))
           throw CLI::ValidationError("--tolerance", "must be a finite relative change >= 0, e.g. 0.01 for 1 %");
         s.tolerance = rel;
       },
       "Regression gate: exit with code 6 when any compared RMS (total, contributor, band) changed by more than "
       "REL relative, e.g. 0.01; the figures that moved are printed, the reports written")
      ->type_name("REL");
  return c;
}

int CompareCommand::Run() const {
  const Options& s = *options_;
  if (!s.out_dir.empty() && s.inputs.size() != 2)
    throw InputError("--out names one directory: give exactly two inputs, or leave --out out");
  // All or nothing: every input is loaded (a budget evaluated) and every
  // comparison built before the first directory is written.
  // One job per input (loading and evaluating it); an error is the first
  // input's that fails, as in a serial loop.
  std::vector<report::ComparisonInput> loaded(s.inputs.size());
  const auto is_budget = report::IsComparisonBudgetFile;
  if ((!s.overrides.empty() || !s.overrides_b.empty()) &&
      std::none_of(s.inputs.begin(), s.inputs.end(), is_budget))
    throw InputError("--set and --set-b change budget files, and every input is a result directory");
  if (!s.overrides_b.empty() && (s.inputs.size() < 2 || !is_budget(s.inputs[1])))
    throw InputError("--set-b changes the second input (B), which must be a budget file");
  std::vector<std::vector<BudgetOverride>> overrides(s.inputs.size(), s.overrides);
  if (!s.overrides_b.empty())
    overrides[1].insert(overrides[1].end(), s.overrides_b.begin(), s.overrides_b.end());
  ParallelForEach(
      loaded.size(),
      [&](std::size_t i) { loaded[i] = Load(s.inputs[i], overrides[i], s.threads, s.plots); },
      s.threads);
  struct Pending {
    Comparison cmp;
    std::vector<report::Plot> plots;
    std::string dir;
    std::vector<report::StudySource> sources;  // A's and B's files as given
  };
  std::vector<Pending> reports;
  const report::ComparisonInput& la = loaded.front();
  const ResultFigures& a = la.figures;
  for (std::size_t i = 1; i < loaded.size(); ++i) {
    const report::ComparisonInput& lb = loaded[i];
    const ResultFigures& b = lb.figures;
    Pending r;
    r.cmp = Compare(a, b);
    r.cmp.tolerance = s.tolerance;
    if (s.plots && la.result && lb.result)
      r.plots = report::ComparisonPlots(a.label, *la.result, b.label, *lb.result);
    r.dir = s.out_dir.empty() ? report::DefaultComparisonDirectory(a.label, b.label) : s.out_dir;
    r.sources = {{"A", s.inputs.front(), a.budget_sha256}, {"B", s.inputs[i], b.budget_sha256}};
    reports.push_back(std::move(r));
  }
  ReplaceOptions replace;
  replace.force = s.force;
  for (const Pending& r : reports) {
    report::WriteComparisonDirectory(r.cmp, r.plots, r.dir, replace, s.threads, r.sources);
    if (s.quiet) continue;
    std::printf("%s (A) vs %s (B):\n", r.cmp.label_a.c_str(), r.cmp.label_b.c_str());
    for (const ComparedFigure& f : r.cmp.figures)
      if (f.contributor == "total" && f.band.empty())
        std::printf("  %-24s rms %12.6g -> %12.6g %s  (B/A %s, %s)\n", f.output.c_str(), f.rms_a, f.rms_b,
                    f.unit.c_str(), report::RatioText(f).c_str(), report::Verdict(f).c_str());
    for (const std::string& u : r.cmp.unmatched) std::printf("  not compared: %s\n", u.c_str());
    std::printf("report: %s\n", r.dir.c_str());
  }
  if (!s.tolerance) return 0;
  std::size_t moved = 0;
  for (const Pending& r : reports) {
    for (const ComparedFigure& f : r.cmp.Moved(*s.tolerance)) {
      if (moved++ == 0) std::fflush(stdout);
      std::fprintf(stderr, "deb: moved: %s vs %s: %s, %s%s: %.6g -> %.6g %s (B/A %s)\n", r.cmp.label_a.c_str(),
                   r.cmp.label_b.c_str(), f.output.c_str(), f.contributor.c_str(),
                   f.band.empty() ? "" : (", band " + f.band).c_str(), f.rms_a, f.rms_b, f.unit.c_str(),
                   report::RatioText(f).c_str());
    }
  }
  if (moved > 0) {
    char what[160];
    std::snprintf(what, sizeof what, "%zu figure(s) moved by more than %g relative (--tolerance)", moved,
                  *s.tolerance);
    throw FiguresMoved(what);
  }
  return 0;
}

}  // namespace deb::tools
