#include "deb/core/frequency_grid.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/limits.h"

namespace deb {

void FrequencyGrid::CheckRange(double min_hz, double max_hz, const char* what) {
  std::ostringstream os;
  if (!(std::isfinite(min_hz) && std::isfinite(max_hz) && min_hz > 0.0 && max_hz > min_hz))
    os << what << ": need 0 < min_hz < max_hz, got min_hz = " << min_hz << ", max_hz = " << max_hz;
  else if (min_hz < limits::kMinGridHz || max_hz > limits::kMaxGridHz)
    os << what << ": min_hz = " << min_hz << ", max_hz = " << max_hz << " leaves the range " << limits::kMinGridHz
       << " to " << limits::kMaxGridHz << " Hz that deb computes in (powers of 2 pi f overflow beyond it)";
  if (!os.str().empty()) throw InputError(os.str());
}

void FrequencyGrid::CheckPoints(double points, const char* what) {
  std::ostringstream os;
  if (!(points >= 2.0)) os << what << ": points must be >= 2, got " << points;
  else if (points > static_cast<double>(limits::kMaxGridPoints))
    os << what << ": " << points << " points is more than the " << limits::kMaxGridPoints
       << " a grid may have";
  if (!os.str().empty()) throw InputError(os.str());
}

FrequencyGrid::FrequencyGrid(std::vector<double> f_hz) : f_hz_(std::move(f_hz)) {
  if (f_hz_.size() < 2) {
    throw InputError("frequency grid: need at least 2 frequencies, got " +
                     std::to_string(f_hz_.size()));
  }
  if (f_hz_.size() > limits::kMaxGridPoints)
    throw InputError("frequency grid: " + std::to_string(f_hz_.size()) + " frequencies is more than the " +
                     std::to_string(limits::kMaxGridPoints) + " a grid may have");

  for (std::size_t i = 0; i < f_hz_.size(); ++i) {
    const bool bad_value = !std::isfinite(f_hz_[i]) || f_hz_[i] <= 0.0;
    const bool bad_order = !bad_value && i > 0 && !(f_hz_[i] > f_hz_[i - 1]);
    if (!bad_value && !bad_order) continue;  // no stream per point: grids hold 10^5 of them
    std::ostringstream os;
    if (bad_value) {
      os << "frequency grid: frequency [" << i << "] = " << f_hz_[i]
         << " Hz must be finite and > 0";
    } else {
      os << "frequency grid: frequencies must increase strictly, but [" << i - 1
         << "] = " << f_hz_[i - 1] << " Hz >= [" << i << "] = " << f_hz_[i] << " Hz";
    }
    throw InputError(os.str());
  }
  CheckRange(f_hz_.front(), f_hz_.back(), "frequency grid");
}

FrequencyGrid FrequencyGrid::Log(double min_hz, double max_hz, int points) {
  CheckRange(min_hz, max_hz, "log grid");
  CheckPoints(points, "log grid");
  std::vector<double> f(points);
  const double l0 = std::log(min_hz), l1 = std::log(max_hz);
  for (int i = 0; i < points; ++i) f[i] = std::exp(l0 + (l1 - l0) * i / (points - 1));
  f.front() = min_hz;
  f.back() = max_hz;
  return FrequencyGrid(std::move(f));
}

FrequencyGrid FrequencyGrid::Linear(double min_hz, double max_hz, int points) {
  CheckRange(min_hz, max_hz, "linear grid");
  CheckPoints(points, "linear grid");
  std::vector<double> f(points);
  for (int i = 0; i < points; ++i) f[i] = min_hz + (max_hz - min_hz) * i / (points - 1);
  f.back() = max_hz;
  return FrequencyGrid(std::move(f));
}

void AutoGridOptions::Validate() const {
  FrequencyGrid::CheckRange(min_hz, max_hz, "automatic grid");
  std::ostringstream os;
  const double base_points = std::log10(max_hz / min_hz) * points_per_decade;
  if (points_per_decade > limits::kMaxPointsPerDecade) {
    os << "automatic grid: points_per_decade " << points_per_decade << " is more than the limit "
       << limits::kMaxPointsPerDecade;
  } else if (points_per_resonance > limits::kMaxPointsPerResonance ||
             resonance_flank_points_per_decade > limits::kMaxPointsPerResonance) {
    os << "automatic grid: points_per_resonance " << points_per_resonance << " and resonance_flank_points_per_decade "
       << resonance_flank_points_per_decade << " may be at most " << limits::kMaxPointsPerResonance;
  } else if (base_points > static_cast<double>(limits::kMaxGridPoints)) {
    os << "automatic grid: " << points_per_decade << " points per decade over " << min_hz << "-" << max_hz
       << " Hz make " << base_points << " points, more than the " << limits::kMaxGridPoints << " a grid may have";
  } else if (points_per_decade < 2) {
    os << "automatic grid: points_per_decade must be >= 2, got " << points_per_decade;
  } else if (points_per_resonance < 4) {
    os << "automatic grid: points_per_resonance must be >= 4, got " << points_per_resonance;
  } else if (resonance_flank_points_per_decade < 4) {
    os << "automatic grid: resonance_flank_points_per_decade must be >= 4, got "
       << resonance_flank_points_per_decade;
  } else if (!(max_refined_zeta > 0.0 && max_refined_zeta < 1.0)) {
    os << "automatic grid: max_refined_zeta must be in (0, 1), got " << max_refined_zeta;
  }
  if (!os.str().empty()) throw InputError(os.str());
}

FrequencyGrid AutoGrid(const AutoGridOptions& options, const std::vector<Resonance>& resonances,
                       const std::vector<double>& breakpoints_hz) {
  options.Validate();
  const double decades = std::log10(options.max_hz / options.min_hz);
  // Validate() bounds decades * points_per_decade by limits::kMaxGridPoints.
  const int base_points =
      std::max(2, static_cast<int>(std::ceil(decades * options.points_per_decade)) + 1);
  std::vector<double> f = FrequencyGrid::Log(options.min_hz, options.max_hz, base_points).f_hz();

  const auto in_range = [&](double x) { return x > options.min_hz && x < options.max_hz; };
  const double kPi = std::acos(-1.0);
  for (const Resonance& r : resonances) {
    if (!(r.f_n_hz > 0.0) || !(r.zeta > 0.0) || r.zeta >= options.max_refined_zeta) continue;
    // Step outward from f_n in x = (f - f_n)/(zeta f_n) with
    // dx = min((1 + x^2) dtheta, rho |x|): tan-spaced (equal area per step of
    // the Lorentzian core) near the peak, geometric in the distance from f_n
    // in its 1/x^2 flanks, out to f_n/2 and 3 f_n/2.
    const double dtheta = kPi / options.points_per_resonance;
    const double rho = std::log(10.0) / options.resonance_flank_points_per_decade;
    const double x_end = 0.5 / r.zeta;
    if (in_range(r.f_n_hz)) f.push_back(r.f_n_hz);
    for (double x = 0.0; x < x_end;) {
      x += std::min((1.0 + x * x) * dtheta, std::max(rho * x, dtheta));
      for (double y : {r.f_n_hz * (1.0 - r.zeta * x), r.f_n_hz * (1.0 + r.zeta * x)})
        if (y > 0.0 && in_range(y)) f.push_back(y);
    }
    if (f.size() > limits::kMaxGridPoints)
      throw InputError("automatic grid: the resonances of the paths need more than the " +
                       std::to_string(limits::kMaxGridPoints) +
                       " points a grid may have; lower points_per_resonance, resonance_flank_points_per_decade "
                       "or max_refined_zeta");
  }
  constexpr double kSide = 1e-9;
  for (double b : breakpoints_hz) {
    if (!std::isfinite(b)) continue;
    for (double x : {b * (1.0 - kSide), b * (1.0 + kSide)})
      if (in_range(x)) f.push_back(x);
  }
  std::sort(f.begin(), f.end());
  // Drop points closer than 1e-12 relative to their predecessor (coincidences
  // between base grid, refinements and breakpoints), keeping min and max.
  std::vector<double> merged;
  merged.reserve(f.size());
  for (double x : f) {
    if (merged.empty() || x > merged.back() * (1.0 + 1e-12)) merged.push_back(x);
  }
  merged.back() = options.max_hz;
  return FrequencyGrid(std::move(merged));
}

}  // namespace deb
