#include "deb/report/figure/plot_points.h"

#include <algorithm>
#include <cmath>

namespace deb::report {

std::vector<std::size_t> PlotPoints(const std::vector<double>& f_hz,
                                    const std::vector<const std::vector<double>*>& series, double lo_hz,
                                    double hi_hz, PlotScale y_scale, double tolerance) {
  const std::size_t n = f_hz.size();
  std::size_t first = std::lower_bound(f_hz.begin(), f_hz.end(), lo_hz) - f_hz.begin();
  std::size_t last = std::upper_bound(f_hz.begin(), f_hz.end(), hi_hz) - f_hz.begin();
  if (first > 0) --first;
  if (last < n) ++last;  // one past the last index kept
  std::vector<std::size_t> keep;
  if (last <= first) return keep;

  double scale = 1.0;  // kLinear: tolerance relative to the largest value shown
  if (y_scale == PlotScale::kLinear) {
    double largest = 0.0;
    for (const auto* s : series)
      for (std::size_t k = first; k < last; ++k) largest = std::max(largest, std::abs((*s)[k]));
    scale = largest > 0.0 ? largest : 1.0;
  }
  // Drawn coordinates, computed once: x = log10 f; y per series (NaN where a
  // log axis cannot show the value). The chord test below visits each point
  // many times, so no logarithm is taken inside it.
  const std::size_t m = last - first;
  std::vector<double> x(m);
  for (std::size_t k = 0; k < m; ++k) x[k] = std::log10(f_hz[first + k]);
  std::vector<std::vector<double>> ys(series.size(), std::vector<double>(m));
  for (std::size_t c = 0; c < series.size(); ++c)
    for (std::size_t k = 0; k < m; ++k) {
      const double v = (*series[c])[first + k];
      ys[c][k] = y_scale == PlotScale::kLog ? (v > 0.0 ? std::log10(v) : NAN) : v / scale;
    }

  // Extend the drawn segment from the last kept point a to b while every point
  // between them stays within tolerance of the chord; segments span at most
  // kMaxSpanDecades so that the check stays cheap. Indices are relative to first.
  constexpr double kMaxSpanDecades = 0.05;
  const auto deviates = [&](std::size_t a, std::size_t i, std::size_t b) {
    const double t = (x[i] - x[a]) / (x[b] - x[a]);
    for (const std::vector<double>& yc : ys) {
      const double ya = yc[a], yi = yc[i], yb = yc[b];
      if (std::isnan(ya) || std::isnan(yi) || std::isnan(yb)) {
        // Where a curve starts or stops being drawable, keep the point.
        if (std::isnan(ya) != std::isnan(yi) || std::isnan(yi) != std::isnan(yb)) return true;
      } else if (std::abs(yi - (ya + t * (yb - ya))) > tolerance) {
        return true;
      }
    }
    return false;
  };
  keep.push_back(0);
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const std::size_t a = keep.back(), b = k + 1;
    bool split = x[b] - x[a] > kMaxSpanDecades;
    for (std::size_t i = a + 1; i < b && !split; ++i) split = deviates(a, i, b);
    if (split) keep.push_back(k);
  }
  if (m > 1) keep.push_back(m - 1);
  for (std::size_t& k : keep) k += first;
  return keep;
}

}  // namespace deb::report
