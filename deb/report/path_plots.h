// Magnitude plots of each contributor's transfer to each output (the thesis'
// transmissibility and sensor-sensitivity plots), one line per source
// channel, in output unit per source unit, with exactly the unit factors and
// weighting the engine applies (ComputePathResponse).
#pragma once

#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/engine.h"
#include "deb/report/plot.h"

namespace deb::report {

// One plot per (contributor, output), contributors outer.
// @throws InputError as ComputePathResponse.
std::vector<Plot> PathPlots(const Budget& budget, const BudgetResult& result, int threads = 0);

}  // namespace deb::report
