// Internal: not part of the public API.
// Plots of one output over frequency: the stacked cumulative power spectrum
// (the budget's central figure: which contributor adds how much variance
// where), optionally the stacked reverse CPS, and the PSD (or ASD) of every
// contributor beside the total. Layers are stacked by share, largest at the
// bottom; the key lists them top to bottom as they are drawn, with each RMS.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/report/plot.h"
#include "deb/report/report_options.h"

namespace deb::report {

// Frequencies shown in an output's plots. A budget's grid may reach far
// beyond where anything happens (the thesis budgets run 1e-4..1e8 Hz for
// accurate integrals); plots show the smallest range of whole decades that
// holds all but kDisplayTail of every contributor's variance at either end
// (less than a CPS plot can show).
// The CSVs always cover the whole grid.
inline constexpr double kDisplayTail = 1e-3;
struct FrequencyRange {
  double lo_hz = 0.0, hi_hz = 0.0;
  bool trimmed = false;  // narrower than the grid
};
FrequencyRange DisplayRange(const OutputResult& output, const FrequencyGrid& grid);

// " Shown: 0.001–100 Hz; the CSV covers the whole grid." when trimmed, else "".
std::string RangeCaption(const FrequencyRange& range);

// Logarithmic frequency axis over `range`. When trimmed, the x label gets a
// second line naming the grid and what the range shows (`shown`, enhanced text).
inline constexpr const char* kDisplayTailNote = "the decades holding all but 10^{-3} of every contributor's variance";
std::string FrequencyAxis(const FrequencyRange& range, const FrequencyGrid& grid,
                          const std::string& shown = kDisplayTailNote);

// Contributor indices of an output by decreasing variance (ties: budget order).
std::vector<std::size_t> ShareOrder(const OutputResult& output);

// CPS, [reverse CPS,] PSD or ASD of output `output`, in that order.
std::vector<Plot> SpectrumPlots(const BudgetResult& result, std::size_t output, const ReportOptions& options);

// Tics for an RMS axis drawn beside a linear variance axis [0, variance_max]
// plotted in units of `scale`: "set y2tics (...)" with labels r at positions
// r^2/scale, r on a 1-2-2.5-5 step, thinned near zero where the squares
// crowd together, plus a labelled tic at each marked RMS (the total, the
// requirement) that is > 0, the earlier winning where two crowd.
std::string RmsTics(double variance_max, double scale = 1.0,
                    const std::vector<std::pair<double, std::string>>& marked_rms = {});

}  // namespace deb::report
