// Internal: not part of the public API.
// Plots of one output over frequency: the stacked cumulative power spectrum
// (the budget's central figure: which contributor adds how much variance
// where), optionally the stacked reverse CPS, and the PSD (or ASD) of every
// contributor beside the total. Layers are stacked by share, largest at the
// top (the total is its upper edge); the key lists them top to bottom as
// they are stacked, with each RMS, then the total and the requirement.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/figure/figure_axis.h"
#include "deb/report/figure/plot.h"
#include "deb/report/figure/plot_style.h"
#include "deb/report/figure/report_options.h"

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
// The same axis as data, for a Figure.
FigureAxis FrequencyFigureAxis(const FrequencyRange& range, const FrequencyGrid& grid,
                               const std::string& shown = kDisplayTailNote);
std::string FrequencyAxis(const FrequencyRange& range, const FrequencyGrid& grid,
                          const std::string& shown = kDisplayTailNote);

// Contributor indices of an output by decreasing variance (ties: budget order).
std::vector<std::size_t> ShareOrder(const OutputResult& output);

// An output seen at one level of its group tree (groups.h), as its stacked
// plots show it: `out` is the output with the level's items as its
// contributors, `styles` their styles (a contributor's ContributorStyle by
// its index in the output, a group's GroupStyle by its place in
// ComputeGroups), so that an item looks alike on every level it appears.
// Group "" is the top level: each top-level group summed exactly from its
// members into one item "name/" (PSD, CPS, variance, tones), the
// contributors in no group as themselves, with the output's total,
// requirements and references; without groups the output itself. A group's
// path: its direct contributors and its subgroups summed, with the group's
// total as the total and no requirement, bands or references.
struct PlotLevel {
  OutputResult out;
  std::vector<SeriesStyle> styles;  // per item of out.contributors
  // Per item of out.contributors: the output's contributors it sums (one
  // for a contributor, every member at any depth for a group; empty for a
  // channel of ChannelLevel).
  std::vector<std::vector<std::size_t>> members;
  FrequencyRange range;             // shown: the output's DisplayRange at the top level, else the level's
  std::string items = "contributors", item = "contributor";  // what the captions call them
};
PlotLevel GroupLevel(const OutputResult& output, const FrequencyGrid& grid, const std::string& group);

// With groups: one drill-down CPS per group with two or more direct members
// (GroupLevel of its path), named <output>_cps_group_<path>; none without
// groups.
std::vector<Plot> GroupCpsPlots(const BudgetResult& result, std::size_t output, int digits);

// A contributor with `breakdown: channels` split by source channel: a layer
// per channel (ContributorResult::channels; a part that is zero but for
// rounding is 0), the contributor as the total, no requirement, bands or
// references.
PlotLevel ChannelLevel(const OutputResult& output, const FrequencyGrid& grid, std::size_t contributor);

// One stacked CPS per contributor with two or more channels that carry
// variance (ChannelLevel), named <output>_cps_channels_<contributor>.
std::vector<Plot> ChannelCpsPlots(const BudgetResult& result, std::size_t output, int digits);

// CPS, [reverse CPS,] PSD or ASD of output `output` at its top level
// (GroupLevel ""), then the group CPS plots, then the channel CPS plots, in
// that order. The CPS draws
// each measured reference's cumulative variance over the range it covers,
// the PSD its spectrum (grey dashed, never summed). With the output's
// outline (BudgetResult::outline), the captions state its weighting.
std::vector<Plot> SpectrumPlots(const BudgetResult& result, std::size_t output, const ReportOptions& options);

// Tics for an RMS axis drawn beside a linear variance axis [0, variance_max]
// plotted in units of `scale`: "set y2tics (...)" with labels r at positions
// r^2/scale, r on a 1-2-2.5-5 step, thinned near zero where the squares
// crowd together, plus a labelled tic at each marked RMS (the total, the
// requirement) that is > 0, the earlier winning where two crowd.
std::string RmsTics(double variance_max, double scale = 1.0,
                    const std::vector<std::pair<double, std::string>>& marked_rms = {});
// The same tics as (position on the variance axis, label).
std::vector<std::pair<double, std::string>> RmsTicList(double variance_max, double scale = 1.0,
                                                       const std::vector<std::pair<double, std::string>>& marked_rms = {});

// Smallest "nice" step (1, 2, 2.5, 5 x 10^n) not below x > 0.
double NiceStep(double x);

// Title of an output's CPS plot: "position: 7.121 nm RMS, FAIL 7.121× over
// 1 nm", "…, pass (limit 20 µm/s)", or the RMS alone without a requirement.
std::string CpsTitle(const OutputResult& output, int digits = 4);

}  // namespace deb::report
