#include "deb/signal/window.h"

#include <cmath>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"

namespace deb {
namespace {

std::vector<double> Coefficients(WindowKind kind) {
  switch (kind) {
    case WindowKind::kRectangular: return {1.0};
    case WindowKind::kHann: return {0.5, 0.5};
    case WindowKind::kHamming: return {0.54, 0.46};
    case WindowKind::kBlackmanHarris: return {0.35875, 0.48829, 0.14128, 0.01168};
    case WindowKind::kFlatTop: return {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368};
  }
  DEB_DEMAND(false);
  return {};
}

}  // namespace

std::vector<double> MakeWindow(WindowKind kind, int size) {
  if (size < 1) throw InputError("window length " + std::to_string(size) + " is invalid; it must be >= 1");
  const std::vector<double> a = Coefficients(kind);
  std::vector<double> w(static_cast<std::size_t>(size));
  const double step = 2.0 * kPi / size;  // periodic: period N, not N - 1
  for (int n = 0; n < size; ++n) {
    double value = 0.0, sign = 1.0;
    for (std::size_t m = 0; m < a.size(); ++m, sign = -sign) value += sign * a[m] * std::cos(step * m * n);
    w[static_cast<std::size_t>(n)] = value;
  }
  return w;
}

WindowSums SumsOf(const std::vector<double>& window) {
  WindowSums s;
  for (double w : window) {
    s.sum += w;
    s.sum_squares += w * w;
  }
  return s;
}

double EnbwBins(const std::vector<double>& window) {
  const WindowSums s = SumsOf(window);
  return static_cast<double>(window.size()) * s.sum_squares / (s.sum * s.sum);
}

}  // namespace deb
