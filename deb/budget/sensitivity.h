// Sensitivity of a budget's variances to one parameter: d var / d ln p of
// every output and contributor on the nominal frequency grid, exact where
// the parameter acts only through rational paths' realisations
// (realisation_gradient.h: the derivative of H propagated through the grid's
// integral), else by central differences in the parameter's logarithm: the
// parameter is multiplied by (1 + h) and by (1 - h), both perturbed budgets
// are evaluated on the nominal grid (a grid refined around moving poles
// would add discretisation noise to the difference), and
//   d var / d ln p ~ (var(p (1 + h)) - var(p (1 - h))) / (ln(1 + h) - ln(1 - h)),
// with an O(h^2) truncation error. The elasticity (d var / var) / (dp / p)
// says how many percent the variance moves per percent of the parameter;
// divided by p it is the plain derivative d var / dp.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "deb/budget/engine.h"

namespace deb {

struct Sensitivity {
  std::string parameter;
  std::string output;
  std::string unit;         // of the output; the variance is in unit^2
  std::string contributor;  // "total" for the output's total
  double variance = 0.0;    // nominal
  double d_variance_d_log_p = 0.0;
  double elasticity = 0.0;  // d ln var / d ln p; 0 where the variance is 0
  bool exact = false;       // from the realisation's derivative, not central differences
};

// How one parameter's derivatives were computed.
struct SensitivityMethod {
  std::string parameter;
  bool exact = false;
  std::string note;  // the method, and for central differences why not exact
};

// One entry per output and per contributor (and the total), in the order of
// the nominal result. DEB_DEMANDs results of the same budget structure.
std::vector<Sensitivity> Sensitivities(const std::string& parameter, double relative_step, const BudgetResult& nominal,
                                       const BudgetResult& up, const BudgetResult& down);

// The budget with `parameter` multiplied by `factor` (deb/load's
// LoadBudgetWithScaledParameter for a key path of the budget file).
using ScaledBudget = std::function<Budget(const std::string& parameter, double factor)>;

struct SensitivityStudy {
  BudgetResult nominal;
  std::vector<Sensitivity> sensitivities;  // parameter after parameter, each as Sensitivities()
  std::vector<SensitivityMethod> methods;  // per parameter, in order
};

// How ComputeSensitivities differentiates.
enum class SensitivityMode {
  kExactWherePossible,  // the realisation's derivative where it applies, else central differences
  kCentralDifferences,  // central differences for every parameter
};

// Evaluates `budget`, then for each parameter loads scaled(parameter, f) for
// f = 1 + h, 1 - h, 1 + h/2, 1 - h/2 on the nominal grid (and with the
// nominal bands when they have none) and differentiates exactly where it can
// (ComputeRealisationGradient), else evaluates the first two and differences
// them. Each parameter is one job of ParallelForEach on options.threads
// threads, so `scaled` is called from several threads at once; the result is
// the same for any thread count.
// @throws InputError as scaled() and Evaluate() (a serial loop's first).
SensitivityStudy ComputeSensitivities(const Budget& budget, const std::vector<std::string>& parameters,
                                      double relative_step, const ScaledBudget& scaled,
                                      const EngineOptions& options = {},
                                      SensitivityMode mode = SensitivityMode::kExactWherePossible);

// Entries of one output: the total's (one per parameter) first, then the
// contributors'; each part ranked by |d variance / d ln p|, largest first.
std::vector<Sensitivity> RankedForOutput(const std::vector<Sensitivity>& all, const std::string& output);

}  // namespace deb
