// The frequencies at which a budget is evaluated. Every PSD, CPS and band
// figure is integrated over this grid, so its quality decides the accuracy of
// the budget: a lightly damped resonance needs points across its half-power
// band, a spectrum's jump needs points on both sides. AutoGrid builds such a
// grid from the poles of the paths and the breakpoints of the sources.
//
// A grid integrates each interval between neighbouring points by the power
// law through its ends (integrate.h), except on its panels: runs of
// kPanelNodes points placed at the Gauss-Lobatto nodes of an interval, which
// integrate a polynomial of degree 2 kPanelNodes - 3 = 9 exactly (panels share
// their end points). The automatic grid is made of panels.
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
  // Points 0-based panel_starts[i] .. panel_starts[i] + kPanelNodes - 1 form
  // a panel (they must lie at the Lobatto nodes of the panel's ends,
  // LobattoNodes; DEB_DEMANDed to 1e-9 of the width). Panels may touch, not
  // overlap.
  FrequencyGrid(std::vector<double> f_hz, std::vector<std::size_t> panel_starts);

  static constexpr int kPanelNodes = 6;
  // The kPanelNodes Lobatto nodes of [-1, 1], increasing (ends included).
  static const std::vector<double>& LobattoNodes();
  // W[j][i]: integral from -1 to node j of the Lagrange polynomial of node i
  // over the nodes; row kPanelNodes - 1 holds the Lobatto weights.
  static const std::vector<std::vector<double>>& LobattoCumulativeWeights();

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
  const std::vector<std::size_t>& panel_starts() const { return panel_starts_; }

  // Band edges within kEdgeTolerance (relative) of the grid's ends count as
  // on them: a band [0.9999999999995, 10] on a grid from 1 Hz is [1, 10].
  // Covers is the one rule for "inside the grid"; ClampToRange moves an edge
  // that Covers accepts onto the grid's end.
  static constexpr double kEdgeTolerance = 1e-12;
  bool Covers(double lo_hz, double hi_hz) const {
    return lo_hz <= hi_hz && lo_hz >= min_hz() * (1.0 - kEdgeTolerance) && hi_hz <= max_hz() * (1.0 + kEdgeTolerance);
  }
  double ClampToRange(double f_hz) const { return f_hz < min_hz() ? min_hz() : f_hz > max_hz() ? max_hz() : f_hz; }

 private:
  std::vector<double> f_hz_;
  std::vector<std::size_t> panel_starts_;
};

// A pole pair of a path, as seen by the grid: natural frequency and damping ratio.
struct Resonance {
  double f_n_hz = 0.0;
  double zeta = 0.0;
};

struct AutoGridOptions {
  double min_hz = 0.1;
  double max_hz = 1000.0;
  int points_per_decade = 40;     // away from resonances
  int points_per_resonance = 10;  // across the half-power band f_n (1 +- zeta) of each resonance
  double max_refined_zeta = 0.3;  // resonances with zeta below this are refined

  // @throws InputError naming the option and the rule.
  void Validate() const;
};

// Panels between the breakpoints, each as wide as the smallest of
//   f (10^((kPanelNodes - 1) / points_per_decade) - 1)           (log density)
//   2 (kPanelNodes - 1) / points_per_resonance x d(f)            (resonances)
// where d(f) is the distance from f to the nearest pole of |H|^2 in the
// complex frequency plane, f_n (sqrt(1 - zeta^2) +- j zeta), over every
// resonance with zeta < max_refined_zeta. A Gauss-Lobatto panel converges
// geometrically in the ratio of that distance to its width, so the rule
// integrates a resonance of any zeta, and clusters of them, to the same
// relative accuracy with points only where the poles are: at the peak
// points_per_resonance across f_n (1 +- zeta), then panels growing in
// proportion to the distance from the pole. Every breakpoint b in range adds
// b(1 - 1e-9) and b(1 + 1e-9) as panel ends, with a power-law interval
// between them, so a jump of the PSD falls in an interval of negligible width.
FrequencyGrid AutoGrid(const AutoGridOptions& options, const std::vector<Resonance>& resonances,
                       const std::vector<double>& breakpoints_hz);

}  // namespace deb
