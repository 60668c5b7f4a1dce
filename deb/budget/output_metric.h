// Lithography metrics of an output over an exposure window T (a scanner
// exposes a field while the stage moves for T seconds):
//   moving average  MA(t)  = (1/T) integral_{t-T}^{t} y dt'          (overlay-like error)
//   moving std      MSD(t) = sqrt((1/T) integral_{t-T}^{t} (y - MA(t))^2 dt')   (fading)
// For a stationary y with one-sided PSD S(f),
//   E[MA^2]  = integral S(f) |sinc(pi f T)|^2 df,
//   E[MSD^2] = integral S(f) (1 - |sinc(pi f T)|^2) df,   sinc(x) = sin(x)/x,
// so both are PSD weightings and the engine treats them as such; the
// reported "variance" of an MSD output is E[MSD^2]. The weightings are not
// rational in s, so no Lyapunov (exact) variance exists for them.
#pragma once

#include <string>

namespace deb {

enum class MetricType { kMovingAverage, kMovingStd };
MetricType ParseMetricType(const std::string& text);  // @throws InputError listing allowed values
std::string ToString(MetricType type);

struct OutputMetric {
  MetricType type = MetricType::kMovingAverage;
  double window_s = 1.0;  // exposure time T > 0

  // |sinc(pi f T)|^2 (moving average) or 1 - |sinc(pi f T)|^2 (moving std) at f_hz.
  double PsdFactor(double f_hz) const;
  std::string Describe() const;  // e.g. "moving average over 0.01 s"
};

}  // namespace deb
