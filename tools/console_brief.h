// What `deb run` prints of a result, and `deb report` of a stored one: per
// output the RMS and requirement, the contributors largest first (with exact
// RMS, top modes and channel parts), the groups, the measured references,
// the band requirements, for an output that fails the one line that says
// what would fix it, and the correlation of the budget's `covariance:`
// outputs. Printed before the report is drawn (gnuplot takes most of a run).
#pragma once

#include <optional>

#include "deb/budget/result.h"

namespace deb::tools {

// `seconds`: the evaluation's wall time, if known. `digits`: significant
// digits of every figure (ReportOptions::digits).
void PrintBrief(const BudgetResult& result, std::optional<double> seconds, int digits);

}  // namespace deb::tools
