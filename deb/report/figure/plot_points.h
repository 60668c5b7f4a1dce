// Internal: not part of the public API.
// Which grid points a plot draws. A budget's grid can hold 10^4..10^5 points
// (resonance refinement, wide ranges), far more than a plot can show; drawing
// them all makes gnuplot slow and the files large. PlotPoints keeps, within the
// display range plus one point either side, only the points a reader can see:
// walking along the grid, a drawn segment is extended while every grid point
// it skips lies, for every series, within `tolerance` of the segment as drawn
// (and the segment spans at most 0.05 decade). Peaks, notches and jumps are
// kept; straight stretches shrink to a few points per decade.
#pragma once

#include <cstddef>
#include <vector>

namespace deb::report {

enum class PlotScale { kLog, kLinear };

// Log x always. kLog y: tolerance in decades; kLinear y: tolerance as a
// fraction of the largest |value| of all series in range.
std::vector<std::size_t> PlotPoints(const std::vector<double>& f_hz,
                                    const std::vector<const std::vector<double>*>& series, double lo_hz,
                                    double hi_hz, PlotScale y_scale = PlotScale::kLog, double tolerance = 2e-3);

// The same rule on coordinates as drawn: x = log10 f (increasing), ys per
// series (log10 of a value on a log axis, NaN where it cannot be shown;
// value / largest |value| on a linear one), all of x's length. Returns
// indices into x, its first and last included. For callers that thin the
// same series more than once (FigurePoints): the logarithms are taken once.
std::vector<std::size_t> DrawnPoints(const std::vector<double>& x, const std::vector<std::vector<double>>& ys,
                                     double tolerance);

// log10 of each value, NaN where a log axis cannot show it (v <= 0).
std::vector<double> LogCoordinates(const std::vector<double>& values);

}  // namespace deb::report
