#include "deb/budget/output_metric.h"

#include <cmath>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"

namespace deb {

double OutputMetric::PsdFactor(double f_hz) const {
  const double x = kPi * f_hz * window_s;
  // sin(x)/x loses no accuracy near 0 for |x| > 1e-4; below, its series 1 - x^2/6.
  const double sinc = std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
  const double ma = std::abs(f_hz * window_s) > kResolvedLobes ? 0.5 / (x * x) : sinc * sinc;
  if (type == MetricType::kMovingAverage) return ma;
  // 1 - sinc^2 cancels for small x: use its series x^2/3 - 2 x^4/45 there.
  return std::abs(x) < 1e-3 ? x * x / 3.0 - 2.0 * x * x * x * x / 45.0 : 1.0 - ma;
}

std::string OutputMetric::Describe() const {
  std::ostringstream os;
  os << (type == MetricType::kMovingAverage ? "moving average" : "moving standard deviation") << " over "
     << window_s << " s";
  return os.str();
}

}  // namespace deb
