#include "deb/core/integrate.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/parallel.h"

namespace deb {

double PowerLawIntervalIntegral(double f1_hz, double f2_hz, double s1, double s2) {
  DEB_DEMAND(f1_hz > 0.0 && f2_hz > f1_hz && s1 >= 0.0 && s2 >= 0.0);
  const double width = f2_hz - f1_hz;
  if (s1 == 0.0 || s2 == 0.0) return 0.5 * (s1 + s2) * width;
  const double log_ratio_f = std::log(f2_hz / f1_hz);
  const double a = std::log(s2 / s1) / log_ratio_f;  // s = s1 (f/f1)^a
  const double e = (a + 1.0) * log_ratio_f;           // ln((f2/f1)^(a+1))
  // integral = s1 f1 ((f2/f1)^(a+1) - 1)/(a+1) = s1 f1 ln(f2/f1) (exp(e) - 1)/e
  if (std::abs(e) < 1e-8) return s1 * f1_hz * log_ratio_f * (1.0 + 0.5 * e);
  return s1 * f1_hz * log_ratio_f * std::expm1(e) / e;
}

std::vector<double> CumulativeIntegral(const std::vector<double>& f_hz,
                                       const std::vector<double>& s, int threads) {
  DEB_DEMAND(f_hz.size() == s.size() && !f_hz.empty());
  std::vector<double> cumulative(f_hz.size());
  cumulative[0] = 0.0;
  ParallelFor(
      f_hz.size() - 1,
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin + 1; i <= end; ++i)
          cumulative[i] = PowerLawIntervalIntegral(f_hz[i - 1], f_hz[i], s[i - 1], s[i]);
      },
      threads);
  for (std::size_t i = 1; i < f_hz.size(); ++i) cumulative[i] += cumulative[i - 1];
  return cumulative;
}

namespace {

// Value at f in [f1, f2] of the power law (or line, where an end is zero).
double Interpolate(double f1, double f2, double s1, double s2, double f) {
  if (s1 == 0.0 || s2 == 0.0) return s1 + (s2 - s1) * (f - f1) / (f2 - f1);
  return s1 * std::pow(f / f1, std::log(s2 / s1) / std::log(f2 / f1));
}

}  // namespace

double IntegralBetween(const std::vector<double>& f_hz, const std::vector<double>& s, double lo_hz,
                       double hi_hz) {
  DEB_DEMAND(f_hz.size() == s.size() && f_hz.size() >= 2);
  DEB_DEMAND(lo_hz >= f_hz.front() && hi_hz <= f_hz.back() && lo_hz <= hi_hz);
  double total = 0.0;
  for (std::size_t i = 1; i < f_hz.size(); ++i) {
    const double a = std::max(f_hz[i - 1], lo_hz), b = std::min(f_hz[i], hi_hz);
    if (!(b > a)) continue;
    const double sa = (a == f_hz[i - 1]) ? s[i - 1] : Interpolate(f_hz[i - 1], f_hz[i], s[i - 1], s[i], a);
    const double sb = (b == f_hz[i]) ? s[i] : Interpolate(f_hz[i - 1], f_hz[i], s[i - 1], s[i], b);
    total += PowerLawIntervalIntegral(a, b, sa, sb);
  }
  return total;
}

namespace {

// Walks the grid in order: panel(i) for a panel of kPanelNodes points
// starting at point i, interval(i) for a plain interval [f_i, f_i+1].
template <class Panel, class Interval>
void WalkGrid(const FrequencyGrid& grid, Panel panel, Interval interval) {
  const std::size_t n = grid.f_hz().size();
  constexpr int q = FrequencyGrid::kPanelNodes;
  const std::vector<std::size_t>& panels = grid.panel_starts();
  std::size_t next_panel = 0;
  for (std::size_t i = 0; i + 1 < n;) {
    if (next_panel < panels.size() && panels[next_panel] == i) {
      panel(i);
      i += q - 1;
      ++next_panel;
    } else {
      interval(i);
      ++i;
    }
  }
}

}  // namespace

std::vector<double> CumulativeIntegral(const FrequencyGrid& grid, const std::vector<double>& s) {
  const std::vector<double>& f = grid.f_hz();
  DEB_DEMAND(f.size() == s.size());
  constexpr int q = FrequencyGrid::kPanelNodes;
  const std::vector<std::vector<double>>& w = FrequencyGrid::LobattoCumulativeWeights();
  std::vector<double> c(f.size(), 0.0);
  WalkGrid(
      grid,
      [&](std::size_t i) {
        const double half = 0.5 * (f[i + q - 1] - f[i]);
        double end = 0.0;
        for (int k = 0; k < q; ++k) end += w[q - 1][k] * s[i + k];
        end = c[i] + half * end;  // Lobatto weights are positive: end >= c[i]
        double running = c[i];
        for (int j = 1; j + 1 < q; ++j) {
          double v = 0.0;
          for (int k = 0; k < q; ++k) v += w[j][k] * s[i + k];
          running = std::max(running, std::min(c[i] + half * v, end));
          c[i + j] = running;
        }
        c[i + q - 1] = end;
      },
      [&](std::size_t i) { c[i + 1] = c[i] + PowerLawIntervalIntegral(f[i], f[i + 1], s[i], s[i + 1]); });
  return c;
}

namespace {

// Adds the Lobatto weights of the panel starting at point i to `weight`.
void AddPanelWeights(const std::vector<double>& f, std::size_t i, std::vector<double>* weight) {
  constexpr int q = FrequencyGrid::kPanelNodes;
  const std::vector<double>& lobatto = FrequencyGrid::LobattoCumulativeWeights()[q - 1];
  const double half = 0.5 * (f[i + q - 1] - f[i]);
  for (int k = 0; k < q; ++k) (*weight)[i + k] += half * lobatto[k];
}

// (exp(e) - 1 - e) / e^2, by its series where the quotient would cancel.
double ExpRemainderQuotient(double e) {
  if (std::abs(e) < 1e-3) return 0.5 + e * (1.0 / 6.0 + e * (1.0 / 24.0 + e / 120.0));
  return (std::expm1(e) / e - 1.0) / e;
}

}  // namespace

std::vector<double> LinearQuadratureWeights(const FrequencyGrid& grid) {
  const std::vector<double>& f = grid.f_hz();
  std::vector<double> weight(f.size(), 0.0);
  WalkGrid(
      grid, [&](std::size_t i) { AddPanelWeights(f, i, &weight); },
      [&](std::size_t i) {
        const double half = 0.5 * (f[i + 1] - f[i]);
        weight[i] += half;
        weight[i + 1] += half;
      });
  return weight;
}

std::vector<double> IntegralGradientWeights(const FrequencyGrid& grid, const std::vector<double>& s) {
  const std::vector<double>& f = grid.f_hz();
  DEB_DEMAND(f.size() == s.size());
  std::vector<double> weight(f.size(), 0.0);
  WalkGrid(
      grid, [&](std::size_t i) { AddPanelWeights(f, i, &weight); },
      [&](std::size_t i) {
        DEB_DEMAND(s[i] >= 0.0 && s[i + 1] >= 0.0);
        if (s[i] == 0.0 || s[i + 1] == 0.0) {  // the trapezoid, as the integral
          const double half = 0.5 * (f[i + 1] - f[i]);
          weight[i] += half;
          weight[i + 1] += half;
          return;
        }
        // I = L (y - x) / ln(y / x) with x = s1 f1, y = s2 f2, L = ln(f2 / f1):
        // dI/ds1 = L f1 g(e), dI/ds2 = L f2 g(-e), e = ln(y / x),
        // g(e) = (exp(e) - 1 - e) / e^2.
        const double log_ratio_f = std::log(f[i + 1] / f[i]);
        const double e = std::log(s[i + 1] / s[i]) + log_ratio_f;
        weight[i] += log_ratio_f * f[i] * ExpRemainderQuotient(e);
        weight[i + 1] += log_ratio_f * f[i + 1] * ExpRemainderQuotient(-e);
      });
  return weight;
}

double IntegralBetween(const FrequencyGrid& grid, const std::vector<double>& s,
                       const std::vector<double>& cumulative, double lo_hz, double hi_hz) {
  const std::vector<double>& f = grid.f_hz();
  DEB_DEMAND(f.size() == s.size() && cumulative.size() == f.size());
  DEB_DEMAND(grid.Covers(lo_hz, hi_hz));  // the engine's band check (CheckBandsInGrid) applies the same rule
  lo_hz = grid.ClampToRange(lo_hz);
  hi_hz = grid.ClampToRange(hi_hz);
  const auto at = [&](double x) {
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(f.begin(), f.end(), x) - f.begin()) - 1;
    if (i + 1 >= f.size() || f[i] == x) return cumulative[i];
    const double sx = Interpolate(f[i], f[i + 1], s[i], s[i + 1], x);
    return cumulative[i] + PowerLawIntervalIntegral(f[i], x, s[i], sx);
  };
  return hi_hz > lo_hz ? std::max(0.0, at(hi_hz) - at(lo_hz)) : 0.0;
}

}  // namespace deb
