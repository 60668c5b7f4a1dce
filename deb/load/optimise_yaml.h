// Budgets whose parameters are design variables (their `min` and `max`,
// deb/load/design_bounds_yaml.h; docs/budget_reference.md, "Design
// variables"), for a design optimisation (deb/optimise/optimiser.h): the
// variables `--vary` names, and the budget at any of their values, loaded as
// any budget is.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "deb/load/budget_yaml.h"
#include "deb/optimise/optimiser.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb {

struct OptimiseBudget {
  std::string name;  // the budget's name as written
  std::vector<DesignVariable> variables;  // in the order named
  // With `robust`: the budget's uncertain parameters other than the
  // variables (their distributions and correlations), whose values the
  // loader takes after the variables'.
  UncertaintySpec uncertain;
  DesignLoader loader;

  // What the loader takes for `design` (the variables' values, SI): those,
  // then the uncertain parameters' nominal values.
  std::vector<double> Point(const std::vector<double>& design) const;
  // The objective `text` names: an output, a weighted sum of outputs
  // ("z + 0.5*x"), "max-ratio", or "" for the
  // budget's only output (max-ratio when it has several); robust
  // (`percentile` in (0, 100)) over `samples` Latin-hypercube samples of
  // the tolerances drawn from `seed`.
  // @throws InputError for a term that is not OUTPUT or WEIGHT*OUTPUT with a
  //   finite weight > 0, or an output named twice.
  OptimiseObjective Objective(const std::string& text, std::optional<double> percentile = std::nullopt,
                              std::size_t samples = 64, std::uint64_t seed = 1) const;
};

// @throws InputError "<file>: --vary NAME: ..." for a name that is no
//   parameter (the nearest suggested), a parameter without bounds, a name
//   given twice or none at all; with `robust`, a budget with no uncertain
//   parameter besides the variables; and the budget's own errors.
OptimiseBudget LoadOptimiseFile(const std::string& path, const std::vector<std::string>& vary,
                                const std::vector<BudgetOverride>& overrides = {}, bool robust = false);

}  // namespace deb
