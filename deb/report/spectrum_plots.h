// Plots of one output over frequency: the stacked cumulative power spectrum
// (the budget's central figure: which contributor adds how much variance
// where), optionally the stacked reverse CPS, and the PSD (or ASD) of every
// contributor beside the total. Layers are stacked by share, largest at the
// bottom; the key lists them top to bottom as they are drawn, with each RMS.
#pragma once

#include <cstddef>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/report/plot.h"
#include "deb/report/report_options.h"

namespace deb::report {

// Contributor indices of an output by decreasing variance (ties: budget order).
std::vector<std::size_t> ShareOrder(const OutputResult& output);

// CPS, [reverse CPS,] PSD or ASD of output `output`, in that order.
std::vector<Plot> SpectrumPlots(const BudgetResult& result, std::size_t output, const ReportOptions& options);

// Tics for an RMS axis drawn beside a linear variance axis [0, variance_max]
// plotted in units of `scale`: "set y2tics (...)" with labels r at positions
// r^2/scale, r on a 1-2-2.5-5 step, thinned near zero where the squares
// crowd together.
std::string RmsTics(double variance_max, double scale = 1.0);

}  // namespace deb::report
