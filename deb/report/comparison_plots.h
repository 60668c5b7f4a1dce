// Internal: not part of the public API.
// Plots that compare contributors at a glance: per output, the RMS of every
// contributor in every frequency band (which contributor dominates which
// band), and an overview of the RMS of every output and contributor against
// the requirements (one panel per output, in the output's own unit; at most
// eight panels per page).
#pragma once

#include <cstddef>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/report/plot.h"

namespace deb::report {

// Grouped bars, one group per band of output `output`: the band's total RMS,
// then each contributor's, on a logarithmic axis.
Plot BandPlot(const BudgetResult& result, std::size_t output);

// The overview page(s).
std::vector<Plot> OverviewPlots(const BudgetResult& result);

// "0.1–1 Hz"
std::string BandText(double lo_hz, double hi_hz);

}  // namespace deb::report
