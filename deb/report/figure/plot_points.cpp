#include "deb/report/figure/plot_points.h"

#include <algorithm>
#include <cmath>

namespace deb::report {

std::vector<double> LogCoordinates(const std::vector<double>& values) {
  std::vector<double> y(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) y[k] = values[k] > 0.0 ? std::log10(values[k]) : NAN;
  return y;
}

std::vector<std::size_t> PlotPoints(const std::vector<double>& f_hz,
                                    const std::vector<const std::vector<double>*>& series, double lo_hz,
                                    double hi_hz, PlotScale y_scale, double tolerance) {
  const std::size_t n = f_hz.size();
  std::size_t first = std::lower_bound(f_hz.begin(), f_hz.end(), lo_hz) - f_hz.begin();
  std::size_t last = std::upper_bound(f_hz.begin(), f_hz.end(), hi_hz) - f_hz.begin();
  if (first > 0) --first;
  if (last < n) ++last;  // one past the last index kept
  if (last <= first) return {};

  double scale = 1.0;  // kLinear: tolerance relative to the largest value shown
  if (y_scale == PlotScale::kLinear) {
    double largest = 0.0;
    for (const auto* s : series)
      for (std::size_t k = first; k < last; ++k) largest = std::max(largest, std::abs((*s)[k]));
    scale = largest > 0.0 ? largest : 1.0;
  }
  // Drawn coordinates, computed once: x = log10 f; y per series (NaN where a
  // log axis cannot show the value).
  const std::size_t m = last - first;
  std::vector<double> x(m);
  for (std::size_t k = 0; k < m; ++k) x[k] = std::log10(f_hz[first + k]);
  std::vector<std::vector<double>> ys(series.size(), std::vector<double>(m));
  for (std::size_t c = 0; c < series.size(); ++c)
    for (std::size_t k = 0; k < m; ++k) {
      const double v = (*series[c])[first + k];
      ys[c][k] = y_scale == PlotScale::kLog ? (v > 0.0 ? std::log10(v) : NAN) : v / scale;
    }
  std::vector<std::size_t> keep = DrawnPoints(x, ys, tolerance);
  for (std::size_t& k : keep) k += first;
  return keep;
}

std::vector<std::size_t> DrawnPoints(const std::vector<double>& x, const std::vector<std::vector<double>>& ys,
                                     double tolerance) {
  const std::size_t m = x.size();
  std::vector<std::size_t> keep;
  if (m == 0) return keep;
  // Extend the drawn segment from the last kept point a to b while every point
  // between them stays within tolerance of the chord; segments span at most
  // kMaxSpanDecades. A point i between a and b is within tolerance of the
  // chord exactly when the chord's slope s = (y_b - y_a) / (x_b - x_a)
  // satisfies |y_i - y_a - s (x_i - x_a)| <= tol, an interval of slopes per
  // point: their intersection, kept per series as points join the segment,
  // decides each b in constant time (testing every skipped point again for
  // every b made this quadratic in the points per segment: 60 % of a
  // wafer-stage run without plots).
  constexpr double kMaxSpanDecades = 0.05;
  struct Segment {
    double slope_lo = -INFINITY, slope_hi = INFINITY;  // from the points between a and b with values
    bool has_nan = false, has_value = false;           // among the points between a and b
  };
  std::vector<Segment> seg(ys.size());
  std::size_t a = 0;
  // Point k joins the segment from a; then whether it can end at b = k + 1.
  const auto extends = [&](std::size_t k) {
    const std::size_t b = k + 1;
    if (x[b] - x[a] > kMaxSpanDecades) return false;
    for (std::size_t c = 0; c < ys.size(); ++c) {
      const std::vector<double>& yc = ys[c];
      Segment& g = seg[c];
      const double ya = yc[a], yk = yc[k], yb = yc[b];
      if (std::isnan(yk)) {
        g.has_nan = true;
      } else {
        g.has_value = true;
        if (!std::isnan(ya)) {
          const double dx = x[k] - x[a];
          g.slope_lo = std::max(g.slope_lo, (yk - ya - tolerance) / dx);
          g.slope_hi = std::min(g.slope_hi, (yk - ya + tolerance) / dx);
        }
      }
      // Where a curve starts or stops being drawable, keep the point. Once
      // one series ends the segment, the others need no update: every
      // segment starts again at k.
      if ((std::isnan(ya) ? g.has_value : g.has_nan) || (std::isnan(yb) ? g.has_value : g.has_nan)) return false;
      if (!std::isnan(ya) && !std::isnan(yb)) {
        const double slope = (yb - ya) / (x[b] - x[a]);
        if (!(slope >= g.slope_lo && slope <= g.slope_hi)) return false;
      }
    }
    return true;
  };
  keep.push_back(0);
  for (std::size_t k = 1; k + 1 < m; ++k) {
    if (extends(k)) continue;
    keep.push_back(k);
    a = k;
    std::fill(seg.begin(), seg.end(), Segment{});
  }
  if (m > 1) keep.push_back(m - 1);
  return keep;
}

}  // namespace deb::report
