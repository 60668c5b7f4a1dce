#include "deb/uncertainty/sample_statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "deb/core/error.h"

namespace deb {

double Percentile(std::vector<double> values, double p) {
  DEB_DEMAND(!values.empty() && p >= 0.0 && p <= 1.0);
  std::sort(values.begin(), values.end());
  const double h = p * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

Moments MeanAndSd(const std::vector<double>& values) {
  DEB_DEMAND(!values.empty());
  Moments m;
  m.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  if (values.size() < 2) return m;
  double ss = 0.0;
  for (double v : values) ss += (v - m.mean) * (v - m.mean);
  m.sd = std::sqrt(ss / static_cast<double>(values.size() - 1));
  return m;
}

Interval WilsonInterval(std::size_t successes, std::size_t trials, double z) {
  DEB_DEMAND(trials >= 1 && successes <= trials);
  const double n = static_cast<double>(trials), p = static_cast<double>(successes) / n, z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n));
  // The ends are exact at 0 and N successes; the formula leaves rounding there.
  return {successes == 0 ? 0.0 : std::max(0.0, centre - half), successes == trials ? 1.0 : std::min(1.0, centre + half)};
}

namespace {

// Ranks from 1, ties given the mean of the ranks they share.
std::vector<double> Ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> rank(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double r = 0.5 * static_cast<double>(i + j) + 1.0;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = r;
    i = j + 1;
  }
  return rank;
}

}  // namespace

double RankCorrelationNoise(std::size_t n, double z) {
  DEB_DEMAND(n >= 2);
  return z / std::sqrt(static_cast<double>(n - 1));
}

double SpearmanCorrelation(const std::vector<double>& x, const std::vector<double>& y) {
  DEB_DEMAND(x.size() == y.size() && x.size() >= 2);
  const std::vector<double> rx = Ranks(x), ry = Ranks(y);
  const double mean = 0.5 * static_cast<double>(x.size() + 1);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (rx[i] - mean) * (ry[i] - mean);
    sxx += (rx[i] - mean) * (rx[i] - mean);
    syy += (ry[i] - mean) * (ry[i] - mean);
  }
  if (sxx == 0.0 || syy == 0.0) return 0.0;
  return sxy / std::sqrt(sxx * syy);
}

SobolIndices SobolIndicesOf(const std::vector<double>& f_a, const std::vector<double>& f_b,
                            const std::vector<double>& f_ab) {
  DEB_DEMAND(!f_a.empty() && f_a.size() == f_b.size() && f_a.size() == f_ab.size());
  std::vector<double> both = f_a;
  both.insert(both.end(), f_b.begin(), f_b.end());
  const Moments m = MeanAndSd(both);
  const double v = m.sd * m.sd;
  if (v == 0.0) return {};
  double first = 0.0, total = 0.0;
  for (std::size_t j = 0; j < f_a.size(); ++j) {
    first += f_b[j] * (f_ab[j] - f_a[j]);
    total += (f_a[j] - f_ab[j]) * (f_a[j] - f_ab[j]);
  }
  const double n = static_cast<double>(f_a.size());
  return {first / n / v, total / (2.0 * n) / v};
}

}  // namespace deb
