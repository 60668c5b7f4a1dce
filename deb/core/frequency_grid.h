// The frequencies at which a budget is evaluated. Every PSD, CPS and band
// figure is integrated over this grid, so its quality decides the accuracy of
// the budget: a lightly damped resonance needs points across its half-power
// band, a spectrum's jump needs points on both sides. AutoGrid builds such a
// grid from the poles of the paths and the breakpoints of the sources.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace deb {

class FrequencyGrid {
 public:
  // @throws InputError unless there are >= 2 points, all finite, > 0 and
  // strictly increasing (the message names the first offending index/value).
  explicit FrequencyGrid(std::vector<double> f_hz);

  // `points` logarithmically / linearly spaced points from min_hz to max_hz.
  // @throws InputError if 0 < min_hz < max_hz or points >= 2 is violated.
  // @throws InputError unless limits::kMinGridHz <= min_hz < max_hz <=
  //         limits::kMaxGridHz and 2 <= points <= limits::kMaxGridPoints.
  static FrequencyGrid Log(double min_hz, double max_hz, int points);
  static FrequencyGrid Linear(double min_hz, double max_hz, int points);
  // The range rule of Log and Linear alone; `what` names the grid in the message.
  static void CheckRange(double min_hz, double max_hz, const char* what);
  static void CheckPoints(double points, const char* what);

  const std::vector<double>& f_hz() const { return f_hz_; }
  std::size_t size() const { return f_hz_.size(); }
  double min_hz() const { return f_hz_.front(); }
  double max_hz() const { return f_hz_.back(); }

 private:
  std::vector<double> f_hz_;
};

// A pole pair of a path, as seen by the grid: natural frequency and damping ratio.
struct Resonance {
  double f_n_hz = 0.0;
  double zeta = 0.0;
};

struct AutoGridOptions {
  double min_hz = 0.1;
  double max_hz = 1000.0;
  int points_per_decade = 200;     // log base grid
  int points_per_resonance = 100;  // across the half-power core of each resonance
  int resonance_flank_points_per_decade = 200;  // in distance from f_n, on its flanks
  double max_refined_zeta = 0.3;   // resonances with zeta below this are refined

  // @throws InputError naming the option and the rule.
  void Validate() const;
};

// Log base grid, plus for every resonance with zeta < max_refined_zeta points
// f = f_n (1 + zeta x): near the peak tan-spaced in x (theta uniform, x =
// tan theta), which gives a Lorentzian 1/(1 + x^2) equal area per interval, and
// on the flanks geometric in |x|, where the peak decays as a power law in the
// distance from f_n; so a resonance is integrated to the same relative accuracy
// whatever its zeta. Every breakpoint b in range adds b(1 - 1e-9) and b(1 + 1e-9), so a
// jump of the PSD falls in an interval of negligible width.
FrequencyGrid AutoGrid(const AutoGridOptions& options, const std::vector<Resonance>& resonances,
                       const std::vector<double>& breakpoints_hz);

}  // namespace deb
