// Internal: not part of the public API.
// The budget report's RMS-per-band figure of one output: a group of bars per
// band of the output (the budget's bands, or the grid's decades) and one per
// band requirement whose range is not already a band, each group the band's
// total then its bars (BandBars), largest (over the whole output) first. A
// band requirement is a limit segment across its group's bars; the total bar
// of a failing group has a red outline and is labelled FAIL.
#pragma once

#include <cstddef>

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/figure/plot.h"
#include "deb/report/figure/plot_style.h"

namespace deb::report {

// A bar of every band: a contributor, a top-level group (summed from its
// members) or the rest of them.
struct BandBar {
  std::string name;
  SeriesStyle style;
  std::vector<std::size_t> members;  // the output's contributors it sums
  double variance = 0.0;             // over the whole grid: the order of the bars
  // Its part of a band: the sum of its members' (per contributor of the output).
  double Of(const std::vector<double>& contributor_variance) const {
    double sum = 0.0;
    for (std::size_t c : members) sum += contributor_variance[c];
    return sum;
  }
};
// More bars than this in a band are a few pixels wide in report.pdf, their
// hatching illegible.
inline constexpr std::size_t kMostBarsPerBand = 8;

// The bars of each band of an output's band chart (report.pdf, the PNG and
// index.html alike): its contributors; over kMostBarsPerBand of them, the
// output's top level (GroupLevel "", as the stacked CPS shows it) where that
// has fewer items; largest first; past kMostBarsPerBand items, the largest
// kMostBarsPerBand - 1 and one bar for the rest. `what`, if given, says
// which of these in words, for a caption.
std::vector<BandBar> BandBars(const OutputResult& output, const FrequencyGrid& grid, std::string* what = nullptr);

// @pre output < result.outputs.size().
Plot BandsPlot(const BudgetResult& result, std::size_t output, int digits = 4);

}  // namespace deb::report
