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

#include "deb/core/enum_names.h"

namespace deb {

enum class MetricType { kMovingAverage, kMovingStd };
inline constexpr EnumName<MetricType> kMetricTypeNames[] = {{MetricType::kMovingAverage, "moving_average"},
                                                            {MetricType::kMovingStd, "moving_std"}};
constexpr EnumNames<MetricType> NamesOf(MetricType) { return kMetricTypeNames; }
// @throws InputError listing allowed values.
inline MetricType ParseMetricType(const std::string& text) { return ParseEnum<MetricType>(text, "metric type"); }

struct OutputMetric {
  // sinc^2 ripples with zeros at k/T. The first kResolvedLobes lobes are
  // evaluated exactly, and the automatic grid puts kPointsPerLobe points
  // across each; beyond f T = kResolvedLobes the weight is its average over
  // a lobe, 1/(2 (pi f T)^2), because no grid of a budget's size resolves
  // thousands of lobes and a PSD that varies slowly across a lobe sees only
  // that average (relative error of order (1/(f T))^2 times S''/S).
  static constexpr int kResolvedLobes = 32;
  static constexpr int kPointsPerLobe = 64;

  MetricType type = MetricType::kMovingAverage;
  double window_s = 1.0;  // exposure time T > 0

  // |sinc(pi f T)|^2 (moving average) or 1 - |sinc(pi f T)|^2 (moving std) at
  // f_hz, with the lobe average beyond kResolvedLobes (above).
  double PsdFactor(double f_hz) const;
  std::string Describe() const;  // e.g. "moving average over 0.01 s"
  // The weighting in words: "|sinc(pi f T)|^2" or "1 - |sinc(pi f T)|^2".
  std::string WeightingText() const {
    return type == MetricType::kMovingStd ? "1 - |sinc(pi f T)|^2" : "|sinc(pi f T)|^2";
  }
};

}  // namespace deb
