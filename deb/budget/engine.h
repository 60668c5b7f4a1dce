// Evaluates a budget: for every contributor (source x path) and output,
//   S_y(f) = h(f) S_u(f) h(f)^H,   h = unit/weighting factors x row of H(j 2 pi f),
// on one frequency grid; CPS(f) = integral of S_y from f_min to f; RMS and
// share of variance per contributor; RMS per band; and, where the source is
// white and the path stable, strictly proper and rational (no measured data),
// the exact variance from the Lyapunov equation beside the CPS figure
// (docs/method.md, conventions 1-3). The automatic grid refines every lightly
// damped pole, every source breakpoint (VC band edges, the bins of an
// estimate), every measured response's data point and the sinc^2 lobes of
// moving-average/std outputs.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/loop_analysis.h"
#include "deb/budget/path_analysis.h"
#include "deb/budget/result.h"
#include "deb/core/frequency_grid.h"

namespace deb {

struct EngineOptions {
  int threads = 0;  // <= 0: DefaultThreadCount()
  // Relative difference between the exact variance and (CPS + estimated
  // tails beyond the grid) above which a warning is issued.
  double exact_tolerance = 1e-3;
  // Also evaluate the transfers a report draws (BudgetResult::traces): off
  // for results that are only compared or summed (sweeps, sensitivities).
  bool response_traces = true;
  // Also evaluate the outputs' covariance the budget asks for
  // (BudgetResult::covariance): off for results whose variances alone are
  // read (an uncertainty study's samples, an optimiser's designs), where it
  // would cost as much as the rest of the evaluation.
  bool covariance = true;
  // Also break contributors down by source channel where the budget asks
  // (Contributor::breakdown_channels; ContributorResult::channels): off
  // where only the contributors' variances are read.
  bool channel_breakdown = true;

  // One thread, variances only (no traces, covariance or channel
  // breakdown): for studies that
  // evaluate many budgets in parallel and read their variances (an
  // uncertainty study's samples, an optimiser's designs).
  static EngineOptions VariancesOnly() {
    EngineOptions o;
    o.threads = 1;
    o.response_traces = false;
    o.covariance = false;
    o.channel_breakdown = false;
    return o;
  }

  // False, with the option, its value and the rule in *error, unless
  // exact_tolerance is finite and > 0. Evaluate throws an InputError with it.
  bool IsValid(std::string* error) const;
};

// The analysis of every path a contributor uses, for the output rows the
// budget reads.
std::map<std::string, std::shared_ptr<const PathAnalysis>> AnalysePaths(const Budget& budget);

// The grid the budget asks for. For the automatic grid: resonances from the
// poles of every contributor's path and every weighting, breakpoints from
// every source and band edge; the default range [0.1, 1000] Hz is narrowed to
// the data that may not be extrapolated (measured sources and responses with
// extrapolation: error), then widened to cover every band.
// @throws InputError (key "grid" or "bands[i]") if a band lies outside an
//         explicit grid range.
FrequencyGrid BuildGrid(const Budget& budget);
FrequencyGrid BuildGrid(const Budget& budget,
                        const std::map<std::string, std::shared_ptr<const PathAnalysis>>& paths);

// What Evaluate settles before it computes anything: the analysis of every
// path, the grid, the bands, the warnings, and for every contributor and
// output whether an exact variance will be attempted. Building it applies
// every check Evaluate makes of its input, so `deb check` (which prints it)
// rejects what `deb run` would, with the same message.
struct EvaluationPlan {
  std::map<std::string, std::shared_ptr<const PathAnalysis>> paths;
  FrequencyGrid grid{std::vector<double>{1.0, 2.0}};
  std::vector<Band> bands;  // the budget's, or the grid's decades
  std::vector<std::string> warnings;
  // Every distinct feedback loop of the contributors' paths, with its margins
  // over the grid (a modulus margin below kLowModulusMargin is a warning).
  std::vector<LoopResult> loops;
  // exact_refusal[contributor][output]: why no exact variance will be
  // computed; "" where one is attempted (the solve may still refuse a result
  // it cannot trust, stated in ContributorResult::exact_note).
  std::vector<std::vector<std::string>> exact_refusal;
};

// @throws InputError with a key path for anything the budget asks that cannot
//         be computed: an unstable path or weighting, exact variance required
//         but impossible, a band outside the grid, a grid beyond tabulated
//         data that may not be extrapolated.
EvaluationPlan PlanEvaluation(const Budget& budget);

// PlanEvaluation, then for every contributor the propagation, the exact
// variance and the per-mode split, then the totals and bands per output.
// @throws InputError as PlanEvaluation, and with the contributor's key path
//         where propagation meets a pole on the grid or a non-finite PSD, or
//         a required exact variance is refused.
BudgetResult Evaluate(const Budget& budget, const EngineOptions& options = {});

}  // namespace deb
