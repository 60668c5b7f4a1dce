// Design optimisation of a budget (deb optimise): the parameters named as
// design variables, each within its [min, max], chosen to minimise an
// objective (an output's RMS, or the largest ratio of an RMS to its
// requirement) subject to every requirement (an output's rms_max and each
// band requirement: RMS <= limit) and to the budget evaluating at all (a
// closed loop that is unstable there is a design that fails). NLopt does
// the search: BOBYQA (derivative-free, bounds only), COBYLA
// (derivative-free, with constraints), SLSQP or MMA (with exact gradients
// where every variable acts only through rational paths' realisations and
// the objective and requirements are outputs' RMS, else by central
// differences, evaluated in parallel); several starts from Sobol
// points of the box (the first the nominal design), run in parallel, the
// best feasible one kept (OptimiseResult::method says which ran). The variables are searched scaled to [0, 1] over
// their bounds, the objective relative to its nominal value.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/core/enum_names.h"

namespace deb {

struct DesignVariable {
  std::string name;      // the budget parameter's
  std::string unit;      // the unit it is written in ("" for a plain number)
  double unit_si = 1.0;  // one `unit` in SI
  double nominal = 0.0;  // SI
  double min = 0.0, max = 0.0;  // SI
};

// kAuto: BOBYQA without requirements to meet (it converges in far fewer
// evaluations on bounds alone), SLSQP with them (on the thesis case study
// it converges in 89 evaluations where COBYLA stops at 200 short of the
// optimum: its linear models cross a flat objective slowly).
enum class OptimiseMethod { kAuto, kCobyla, kBobyqa, kSlsqp, kMma };
inline constexpr EnumName<OptimiseMethod> kOptimiseMethodNames[] = {{OptimiseMethod::kAuto, "auto"},
                                                                    {OptimiseMethod::kCobyla, "cobyla"},
                                                                    {OptimiseMethod::kBobyqa, "bobyqa"},
                                                                    {OptimiseMethod::kSlsqp, "slsqp"},
                                                                    {OptimiseMethod::kMma, "mma"}};
constexpr EnumNames<OptimiseMethod> NamesOf(OptimiseMethod) { return kOptimiseMethodNames; }

// One output's share of a weighted-sum objective: weight x its RMS, in the
// output's own unit.
struct ObjectiveTerm {
  std::string output;
  double weight = 1.0;  // > 0
};

// What is minimised: the RMS of one output, a weighted sum of outputs'
// RMS (`terms`; each RMS in its output's unit, so a weight carries the
// inverse of that unit), or (max_ratio) the largest RMS / limit over the
// requirements. Robust (`quantile` set): at each
// design, the budget is evaluated at every sample of the other uncertain
// parameters (`samples`, the same for every design: common random
// numbers), and the objective and each requirement's RMS are their
// `quantile` over the samples (P95 of the RMS <= the limit).
struct OptimiseObjective {
  bool max_ratio = false;
  std::vector<ObjectiveTerm> terms;  // {output, 1}: that output's RMS
  std::optional<double> quantile;              // in (0, 1)
  std::vector<std::vector<double>> samples;    // per sample, the uncertain parameters' values (SI)
  // "the RMS of z", "the weighted sum 2 RMS(z) + RMS(x)", "the largest RMS /
  // requirement", "the P95 of the RMS of z ..."
  std::string Text() const;
  // The objective's value for a result: NaN when an output named is not in it.
  double Of(const struct BudgetResult& result) const;
};

// The most starts, evaluations per start and robust samples a study takes.
inline constexpr int kMaxOptimiseStarts = 1000;
inline constexpr int kMaxEvaluationsPerStart = 100000;
inline constexpr int kMaxRobustSamples = 100000;
inline constexpr std::size_t kMaxObjectiveTerms = 1000;

struct OptimiseOptions {
  OptimiseMethod method = OptimiseMethod::kAuto;
  int starts = 1;                // the nominal design, then Sobol points of the box
  int max_evaluations = 200;     // per start (gradient steps included)
  double tolerance = 1e-8;       // of each variable, relative to its range
  std::uint64_t seed = 1;        // of the Sobol points' shift
  int threads = 0;
};

// A requirement at a design: "z" (rms_max), "z[10-100 Hz]" (a band's), or
// a loop's required margin ("loop G/K phase margin": `margin`, `rms` the
// loop's margin, `limit` the required one; infinite where the loop has no
// such crossover, NaN where it was not evaluated).
struct RequirementRatio {
  std::string name;
  double rms = 0.0, limit = 0.0;
  bool margin = false;
  // RMS / limit, or for a margin required / actual: at most 1 where it is met.
  double ratio() const;
  bool active = false;  // at the optimum: within 1e-3 of its limit
};

struct DesignEvaluation {
  int start = 0;
  std::vector<double> values;  // SI
  double objective = 0.0;      // unscaled (RMS or ratio); +inf when the budget failed
  double worst_ratio = 0.0;    // the largest RMS / limit (0 without requirements)
  std::string error;           // why the budget failed, or ""
};

struct OptimiseStart {
  std::vector<double> from, values;  // SI
  double objective = 0.0;
  double worst_ratio = 0.0;
  bool feasible = false;
  int evaluations = 0;
  std::string stop;  // NLopt's reason
};

// A variable whose optimum is on a bound of its range (within 1e-6 of the
// range), and the design evaluated with it a quarter of its range from the
// bound and the others at the optimum: how much the bound decides.
struct BoundProbe {
  std::size_t variable = 0;
  DesignEvaluation at;
};

struct OptimiseResult {
  std::vector<DesignVariable> variables;
  OptimiseObjective objective;
  OptimiseOptions options;
  OptimiseMethod method = OptimiseMethod::kCobyla;  // the one that ran (never kAuto)
  // How SLSQP and MMA got their gradients: "exact: ..." (the realisations'
  // derivatives, deb/budget/realisation_gradient.h) or "central
  // differences: <why not exact>"; for the derivative-free methods, none.
  std::string gradients;
  double nominal_objective = 0.0;
  std::vector<RequirementRatio> nominal_requirements;
  std::vector<OptimiseStart> starts;
  std::size_t best = 0;  // the start whose result is the optimum
  bool feasible = false;  // some start met every requirement
  std::vector<RequirementRatio> requirements;  // at the optimum
  std::vector<DesignEvaluation> history;        // start by start, in order
  int evaluations = 0;
  // One per variable on its bound, in variable order (not counted in `evaluations`).
  std::vector<BoundProbe> bound_probes;
};

// One start's outcome: the start, every design it evaluated (in order) and
// the requirement lines where it ended.
struct StartOutcome {
  OptimiseStart start;
  std::vector<DesignEvaluation> history;
  std::vector<RequirementRatio> requirements;
};

// An outcome as bytes and back, exactly (for the ranks of one run).
std::string StartOutcomeToBytes(const StartOutcome& outcome);
StartOutcome StartOutcomeFromBytes(const std::string& bytes);

// Runs starts 0..count-1, each by run(k) (which may be called from several
// threads or processes at once), and returns their outcomes in start order.
// RunOptimise's default runs them on options.threads threads; under mpirun
// the CLI passes one that spreads them over the ranks, one start per rank
// at a time, and returns them on rank 0 only: on the other ranks it returns
// none, and so does RunOptimise (a result without starts).
using StartRunner =
    std::function<std::vector<StartOutcome>(std::size_t count, const std::function<StartOutcome(std::size_t)>& run)>;

// The budget at the variables' values (SI, in order), followed (robust) by a
// sample's values of the uncertain parameters; may be called from several
// threads at once.
using DesignLoader = std::function<Budget(const std::vector<double>& values)>;

// The requirement lines of a result: every output's rms_max, then its band
// requirements; then every loop's required margins.
std::vector<RequirementRatio> RequirementRatios(const struct BudgetResult& result);

// The objective and the largest RMS / requirement over a grid of two
// variables' box (n x n designs, evaluated in parallel): the map a reader
// checks the optimum on. NaN where the budget fails.
struct DesignMap {
  std::vector<double> x, y;                    // SI, ascending
  std::vector<std::vector<double>> objective;  // [i][j] at (x[i], y[j])
  std::vector<std::vector<double>> worst_ratio;
};
// DEB_DEMANDs two variables and n >= 2.
DesignMap MapDesigns(const std::vector<DesignVariable>& variables, const OptimiseObjective& objective,
                     const DesignLoader& loader, int n, int threads);

// @throws InputError for an objective output the budget has not, max_ratio
//   or constraints with no requirement to meet, BOBYQA with requirements to
//   meet, and the nominal budget's own errors.
// The starts run through `runner` (empty: on threads); its result is the
// same, bit for bit, whichever runs them.
OptimiseResult RunOptimise(const std::vector<DesignVariable>& variables, const OptimiseObjective& objective,
                           const OptimiseOptions& options, const DesignLoader& loader,
                           const StartRunner& runner = {});

}  // namespace deb
