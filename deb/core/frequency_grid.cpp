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

FrequencyGrid::FrequencyGrid(std::vector<double> f_hz, std::vector<std::size_t> panel_starts)
    : FrequencyGrid(std::move(f_hz)) {
  const std::vector<double>& x = LobattoNodes();
  std::size_t next_free = 0;
  for (std::size_t p : panel_starts) {
    DEB_DEMAND(p >= next_free && p + kPanelNodes <= f_hz_.size());
    const double a = f_hz_[p], b = f_hz_[p + kPanelNodes - 1];
    for (int j = 1; j + 1 < kPanelNodes; ++j)
      DEB_DEMAND(std::abs(f_hz_[p + j] - (a + 0.5 * (b - a) * (x[j] + 1.0))) <= 1e-9 * (b - a));
    next_free = p + kPanelNodes - 1;
  }
  panel_starts_ = std::move(panel_starts);
}

const std::vector<double>& FrequencyGrid::LobattoNodes() {
  // +-1 and the roots of P_5', +-sqrt(1/3 +- 2 sqrt(7) / 21).
  static const std::vector<double> nodes = [] {
    const double s7 = std::sqrt(7.0);
    const double outer = std::sqrt(1.0 / 3.0 + 2.0 * s7 / 21.0), inner = std::sqrt(1.0 / 3.0 - 2.0 * s7 / 21.0);
    return std::vector<double>{-1.0, -outer, -inner, inner, outer, 1.0};
  }();
  static_assert(kPanelNodes == 6, "LobattoNodes holds the 6-point rule");
  return nodes;
}

const std::vector<std::vector<double>>& FrequencyGrid::LobattoCumulativeWeights() {
  // Lagrange polynomial i = sum_k c_ik x^k from the Vandermonde system; its
  // integral from -1 to x_j = sum_k c_ik (x_j^(k+1) - (-1)^(k+1)) / (k+1).
  static const std::vector<std::vector<double>> weights = [] {
    const std::vector<double>& x = LobattoNodes();
    constexpr int n = kPanelNodes;
    double v[n][n], inv[n][n];
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) {
        v[i][k] = std::pow(x[i], k);
        inv[i][k] = i == k ? 1.0 : 0.0;
      }
    // Gauss-Jordan with partial pivoting: inv = V^-1 (coefficients by column).
    for (int c = 0; c < n; ++c) {
      int piv = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(v[r][c]) > std::abs(v[piv][c])) piv = r;
      for (int k = 0; k < n; ++k) {
        std::swap(v[c][k], v[piv][k]);
        std::swap(inv[c][k], inv[piv][k]);
      }
      for (int r = 0; r < n; ++r) {
        if (r == c) continue;
        const double f = v[r][c] / v[c][c];
        for (int k = 0; k < n; ++k) {
          v[r][k] -= f * v[c][k];
          inv[r][k] -= f * inv[c][k];
        }
      }
    }
    // V c_i = e_i, so c_ik = (V^-1)_ki.
    std::vector<std::vector<double>> w(n, std::vector<double>(n, 0.0));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double sum = 0.0;
        for (int k = 0; k < n; ++k) {
          const double c = inv[k][i] / v[k][k];
          sum += c * (std::pow(x[j], k + 1) - std::pow(-1.0, k + 1)) / (k + 1);
        }
        w[j][i] = sum;
      }
    return w;
  }();
  return weights;
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
  } else if (points_per_resonance > limits::kMaxPointsPerResonance) {
    os << "automatic grid: points_per_resonance " << points_per_resonance << " may be at most "
       << limits::kMaxPointsPerResonance;
  } else if (base_points > static_cast<double>(limits::kMaxGridPoints)) {
    os << "automatic grid: " << points_per_decade << " points per decade over " << min_hz << "-" << max_hz
       << " Hz make " << base_points << " points, more than the " << limits::kMaxGridPoints << " a grid may have";
  } else if (points_per_decade < 2) {
    os << "automatic grid: points_per_decade must be >= 2, got " << points_per_decade;
  } else if (points_per_resonance < 4) {
    os << "automatic grid: points_per_resonance must be >= 4, got " << points_per_resonance;
  } else if (!(max_refined_zeta > 0.0 && max_refined_zeta < 1.0)) {
    os << "automatic grid: max_refined_zeta must be in (0, 1), got " << max_refined_zeta;
  }
  if (!os.str().empty()) throw InputError(os.str());
}

namespace {

// The poles of |H|^2 near the real frequency axis: f_n sqrt(1 - zeta^2) +-
// j zeta f_n, sorted by the real part, for the distance d(f).
class PoleDistance {
 public:
  PoleDistance(const std::vector<Resonance>& resonances, double max_zeta) {
    for (const Resonance& r : resonances)
      if (r.f_n_hz > 0.0 && r.zeta > 0.0 && r.zeta < max_zeta && std::isfinite(r.f_n_hz))
        poles_.push_back({r.f_n_hz * std::sqrt((1.0 - r.zeta) * (1.0 + r.zeta)), r.zeta * r.f_n_hz});
    std::sort(poles_.begin(), poles_.end());
  }
  // Distance from the real f to the nearest pole; infinite without poles.
  double operator()(double f) const {
    double best = HUGE_VAL;
    const auto it = std::lower_bound(poles_.begin(), poles_.end(), std::make_pair(f, 0.0));
    for (auto up = it; up != poles_.end() && up->first - f < best; ++up) best = std::min(best, std::hypot(up->first - f, up->second));
    for (auto down = it; down != poles_.begin();) {
      --down;
      if (f - down->first >= best) break;
      best = std::min(best, std::hypot(f - down->first, down->second));
    }
    return best;
  }

 private:
  std::vector<std::pair<double, double>> poles_;  // (real part, |imaginary part|) in Hz
};

}  // namespace

FrequencyGrid AutoGrid(const AutoGridOptions& options, const std::vector<Resonance>& resonances,
                       const std::vector<double>& breakpoints_hz) {
  options.Validate();
  constexpr int q = FrequencyGrid::kPanelNodes;
  const double log_span = std::pow(10.0, (q - 1.0) / options.points_per_decade) - 1.0;
  const double pole_span = 2.0 * (q - 1.0) / options.points_per_resonance;
  const PoleDistance distance(resonances, options.max_refined_zeta);
  // Panel width at f: pole_span times the distance to the nearest pole over
  // the whole panel (sampled at its middle and far end). d is 1-Lipschitz, so
  // pole_span d(f) / (1 + pole_span) always holds: approaching a pole, the
  // panels halve the distance (for pole_span = 1), not shrink to its width.
  const auto width = [&](double f) {
    const double d0 = distance(f), safe = pole_span * d0 / (1.0 + pole_span);
    double w = std::min(log_span * f, pole_span * d0);
    for (int i = 0; i < 4 && w > safe; ++i) {
      const double m = std::min({d0, distance(f + 0.5 * w), distance(f + w)});
      if (pole_span * m >= w) break;
      w = std::max(pole_span * m, safe);
    }
    return std::min(w, log_span * f);
  };

  // Hard ends: the range and both sides of every breakpoint inside it.
  constexpr double kSide = 1e-9;
  std::vector<double> ends = {options.min_hz, options.max_hz};
  for (double b : breakpoints_hz) {
    if (!std::isfinite(b)) continue;
    for (double x : {b * (1.0 - kSide), b * (1.0 + kSide)})
      if (x > options.min_hz && x < options.max_hz) ends.push_back(x);
  }
  std::sort(ends.begin(), ends.end());
  std::vector<double> merged_ends;
  for (double x : ends)
    if (merged_ends.empty() || x > merged_ends.back() * (1.0 + 1e-12)) merged_ends.push_back(x);
  merged_ends.back() = options.max_hz;

  const std::vector<double>& nodes = FrequencyGrid::LobattoNodes();
  std::vector<double> f = {merged_ends.front()};
  std::vector<std::size_t> panels;
  const auto add_panel = [&](double a, double b) {
    panels.push_back(f.size() - 1);
    for (int j = 1; j < q; ++j) f.push_back(j + 1 == q ? b : a + 0.5 * (b - a) * (nodes[j] + 1.0));
    if (f.size() > limits::kMaxGridPoints)
      throw InputError("automatic grid: the resonances of the paths need more than the " +
                       std::to_string(limits::kMaxGridPoints) +
                       " points a grid may have; lower points_per_resonance, points_per_decade or max_refined_zeta");
  };
  for (std::size_t e = 1; e < merged_ends.size(); ++e) {
    const double lo = merged_ends[e - 1], hi = merged_ends[e];
    // The interval inside a breakpoint (b(1 - 1e-9), b(1 + 1e-9)): one power-law step.
    if (hi <= lo * (1.0 + 4.0 * kSide)) {
      f.push_back(hi);
      continue;
    }
    for (double x = lo; x < hi;) {
      const double w = width(x), rest = hi - x;
      double next;
      if (rest <= w * (1.0 + 1e-12)) next = hi;
      else if (rest <= 2.0 * w) next = x + 0.5 * rest;  // two equal panels rather than a sliver
      else next = x + w;
      add_panel(x, next);
      x = next;
    }
  }
  f.back() = options.max_hz;
  return FrequencyGrid(std::move(f), std::move(panels));
}

}  // namespace deb
