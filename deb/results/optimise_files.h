// The files of a design optimisation (deb optimise): summary.json for
// scripts (the variables and their bounds, the objective, the nominal and
// the optimal design, every requirement at the optimum with whether it is
// active, each start), history.csv (every budget evaluated, start by
// start) and optimum.yaml (the optimum as a budget: `extends:` the
// original, only the variables changed, each `name: value unit`).
#pragma once

#include <string>
#include <vector>

#include "deb/optimise/optimiser.h"

namespace deb {

std::string OptimiseSummaryJson(const std::string& budget_name, const OptimiseResult& result);
std::string OptimiseHistoryCsv(const OptimiseResult& result);
// `extends` is the original budget's path as optimum.yaml will reach it
// (relative to the directory it is written to); `overrides` (--set
// KEY=VALUE) are named in a comment, as the optimum assumes them.
std::string OptimumYaml(const std::string& extends, const std::string& budget_name, const OptimiseResult& result,
                        const std::vector<std::string>& overrides);
// The variables whose optimum lies on their range's bound (within 1e-6 of
// the range), by index: those of OptimiseResult::bound_probes.
std::vector<std::size_t> VariablesAtBound(const OptimiseResult& result);
// "On a bound: h at its maximum 400 mm: the range given, not the budget,
// limits the optimum there (widen it to see further)."; "" when none is.
// With how the objective differs a quarter of the range in (the bound
// probes, the other variables at the optimum); where that is within
// kFlatObjective and meets every requirement for each such variable:
// "On a bound: h at its maximum 400 mm (at 225 mm, the others as they are,
// the objective is 0.22 % worse): nearly flat there; the bound, not a clear
// optimum, decides the value."
inline constexpr double kFlatObjective = 0.01;
std::string BoundsText(const OptimiseResult& result);
// "Kv = 61.3, h = 182 mm": the optimum's values in their units.
std::string OptimumText(const OptimiseResult& result);
// The optimum's description, for optimum.yaml and its report: "The optimum
// of deb optimise: Kv = 61.3, h = 182 mm (z_velocity RMS minimised: 11.2,
// nominal 12.1); every requirement met." then "The budget it varies, as written (its nominal values): " and
// `budget_description` (which speaks of the nominal design), if any.
std::string OptimumDescription(const OptimiseResult& result, const std::string& budget_description);

}  // namespace deb
