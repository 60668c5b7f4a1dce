// Internal: not part of the public API.
// What `deb run` prints of a result, and `deb report` of a stored one: per
// output the RMS and requirement, the contributors largest first (with exact
// RMS, top modes and channel parts), the groups, the measured references,
// the band requirements, for an output that fails the one line that says
// what would fix it, and the correlation of the budget's `covariance:`
// outputs. The commands print it before the report is drawn (gnuplot takes
// most of a run), so that the figures come at once.
#pragma once

#include <optional>
#include <string>

#include "deb/budget/result.h"

namespace deb::report {

// The summary as console text, ending in a newline. `evaluation_seconds`:
// the evaluation's wall time, if known. `digits`: significant digits of
// every figure (ReportOptions::digits).
std::string ConsoleSummary(const BudgetResult& result, std::optional<double> evaluation_seconds, int digits);

}  // namespace deb::report
