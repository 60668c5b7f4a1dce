// Internal: not part of the public API.
// The budget report's RMS-per-band figure of one output: a group of bars per
// band of the output (the budget's bands, or the grid's decades) and one per
// band requirement whose range is not already a band, each group the band's
// total then every contributor, largest (over the whole output) first. A
// band requirement is a limit segment across its group's bars; the total bar
// of a failing group has a red outline and is labelled FAIL.
#pragma once

#include <cstddef>

#include "deb/budget/result.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// @pre output < result.outputs.size().
Plot BandsPlot(const BudgetResult& result, std::size_t output, int digits = 4);

}  // namespace deb::report
