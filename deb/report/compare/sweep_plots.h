// Internal: not part of the public API.
// Plots of `deb sweep`, per output:
//  - <output>_sweep: small multiples, one panel per combination of the other
//    parameters' values, each showing RMS against the first parameter, one
//    colour per contributor and the total in black, on one shared RMS axis
//    with the requirement; parameters named by their label and unit.
//  - <output>_map, for a grid of exactly two parameters of two or more
//    values each: the total RMS as a heat map over both, the requirement's
//    contour and the best variant (lowest total RMS) marked.
#pragma once

#include <cstddef>
#include <vector>

#include "deb/budget/result.h"
#include "deb/budget/sweep.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// At most this many panels in a small-multiples plot (the rest are named in the caption).
inline constexpr std::size_t kMaxSweepPanels = 16;

// Per output its small multiples, then its map where there is one.
// DEB_DEMANDs one result per variant of spec.
std::vector<Plot> SweepPlots(const SweepSpec& spec, const std::vector<BudgetResult>& results);

// A straight piece of a contour line.
struct ContourSegment {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};

// The contour z = level of values z[i][j] at (x[i], y[j]) (x and y
// ascending): per grid cell the segment between the crossings on its
// edges, interpolated linearly along each edge (marching squares; a saddle
// cell gives two segments). DEB_DEMANDs matching sizes.
std::vector<ContourSegment> LevelSegments(const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<std::vector<double>>& z, double level);

}  // namespace deb::report
