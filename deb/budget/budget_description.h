// Internal: not part of the public API.
// What `deb check` says of a valid budget, without computing it: the grid,
// each source, path (states and stability, modes, or measured points),
// feedback loop with its margins, contributor (and why it will have no exact
// variance where one was asked for), output and the covariance it asks
// for; and, for a budget with a `sweep:` section, the sweep's parameters.
#pragma once

#include <cstddef>
#include <string>

#include "deb/budget/budget.h"
#include "deb/budget/engine.h"
#include "deb/budget/sweep.h"

namespace deb {

// The description as console text, each line ending in a newline; `plan` is
// PlanEvaluation(budget).
std::string DescribeBudget(const Budget& budget, const EvaluationPlan& plan);

// "sweep: grid of 2 parameter(s), 12 variants, each valid:" and a line per
// parameter: its key path, number of values, first and last value, and its
// label and unit. `variant_count` is the number of variants checked.
std::string DescribeSweep(const SweepSpec& spec, std::size_t variant_count);

}  // namespace deb
