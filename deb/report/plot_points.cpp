#include "deb/report/plot_points.h"

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
  // The drawn y of a value; NaN where a log axis cannot show it.
  const auto y = [&](double v) { return y_scale == PlotScale::kLog ? (v > 0.0 ? std::log10(v) : NAN) : v / scale; };

  // Extend the drawn segment from the last kept point a to b while every point
  // between them stays within tolerance of the chord; segments span at most
  // kMaxSpanDecades so that the check stays cheap.
  constexpr double kMaxSpanDecades = 0.05;
  const auto deviates = [&](std::size_t a, std::size_t i, std::size_t b) {
    const double t = std::log(f_hz[i] / f_hz[a]) / std::log(f_hz[b] / f_hz[a]);
    for (const auto* s : series) {
      const double ya = y((*s)[a]), yi = y((*s)[i]), yb = y((*s)[b]);
      if (std::isnan(ya) || std::isnan(yi) || std::isnan(yb)) {
        // Where a curve starts or stops being drawable, keep the point.
        if (std::isnan(ya) != std::isnan(yi) || std::isnan(yi) != std::isnan(yb)) return true;
      } else if (std::abs(yi - (ya + t * (yb - ya))) > tolerance) {
        return true;
      }
    }
    return false;
  };
  keep.push_back(first);
  for (std::size_t k = first + 1; k + 1 < last; ++k) {
    const std::size_t a = keep.back(), b = k + 1;
    bool split = std::log10(f_hz[b] / f_hz[a]) > kMaxSpanDecades;
    for (std::size_t i = a + 1; i < b && !split; ++i) split = deviates(a, i, b);
    if (split) keep.push_back(k);
  }
  if (last - 1 > first) keep.push_back(last - 1);
  return keep;
}

}  // namespace deb::report
