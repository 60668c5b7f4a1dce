// Internal: not part of the public API.
// Plots of `deb sweep`: per output, RMS against the first swept parameter,
// one colour per contributor (the total in black) and one dash pattern per
// combination of the other parameters' values.
#pragma once

#include <vector>

#include "deb/budget/engine.h"
#include "deb/budget/sweep.h"
#include "deb/report/plot.h"

namespace deb::report {

// One plot per output. DEB_DEMANDs one result per variant of spec.
std::vector<Plot> SweepPlots(const SweepSpec& spec, const std::vector<BudgetResult>& results);

}  // namespace deb::report
