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

}  // namespace deb::report
