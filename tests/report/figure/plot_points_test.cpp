#include "deb/report/figure/plot_points.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "deb/core/frequency_grid.h"

namespace deb::report {

TEST_CASE("a straight stretch shrinks to its ends, one point beyond the range either side") {
  const std::vector<double> f = {1, 2, 3, 4, 5, 6};
  const std::vector<double> s = {1, 1, 1, 1, 1, 1};
  CHECK(PlotPoints(f, {&s}, 2.5, 4.5) == std::vector<std::size_t>{1, 2, 3, 4});  // 0.05-decade segments
  std::vector<double> g(101), one(101, 1.0);
  for (int i = 0; i <= 100; ++i) g[i] = 1.0 + 0.001 * i;
  CHECK(PlotPoints(g, {&one}, 1.0, 1.1) == std::vector<std::size_t>{0, 100});
}

TEST_CASE("a curve that stops being drawable on a log axis keeps its last drawable point") {
  std::vector<double> g(101), s(101, 1.0);
  for (int i = 0; i <= 100; ++i) g[i] = 1.0 + 0.001 * i;
  for (int i = 60; i <= 100; ++i) s[i] = 0.0;
  CHECK(PlotPoints(g, {&s}, 1.0, 1.1) == std::vector<std::size_t>{0, 59, 60, 100});
}

TEST_CASE("a dense series is thinned but keeps its peak and both sides of a jump") {
  const std::vector<double> f = FrequencyGrid::Log(0.01, 1000.0, 100001).f_hz();
  std::vector<double> s(f.size());
  std::size_t peak = 0, jump = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    s[i] = 1.0 / (1.0 + std::pow((f[i] - 7.3) / 0.01, 2)) + (f[i] < 30.0 ? 1e-3 : 1e-6);
    if (s[i] > s[peak]) peak = i;
    if (f[i] < 30.0) jump = i;
  }
  const auto k = PlotPoints(f, {&s}, 0.01, 1000.0);
  MESSAGE("kept " << k.size() << " of " << f.size());
  CHECK(k.size() < 2000);
  CHECK(k.size() > 5 * 20);  // at least every 0.05 decade
  // Every dropped point lies within the tolerance (2e-3 decades) of the drawn line.
  for (std::size_t j = 1; j < k.size(); ++j)
    for (std::size_t i = k[j - 1] + 1; i < k[j]; ++i) {
      const double t = std::log(f[i] / f[k[j - 1]]) / std::log(f[k[j]] / f[k[j - 1]]);
      const double drawn = std::log10(s[k[j - 1]]) + t * (std::log10(s[k[j]]) - std::log10(s[k[j - 1]]));
      REQUIRE(std::abs(std::log10(s[i]) - drawn) <= 2e-3);
    }
  CHECK(std::is_sorted(k.begin(), k.end()));
  CHECK(std::binary_search(k.begin(), k.end(), peak));
  CHECK(std::binary_search(k.begin(), k.end(), jump));
  CHECK(std::binary_search(k.begin(), k.end(), jump + 1));
  CHECK(k.front() == 0);
  CHECK(k.back() == f.size() - 1);
}


// The rule stated in plot_points.h, tested point by point: every grid point a
// drawn segment skips lies within the tolerance of it, for every series (the
// exhaustive check PlotPoints made before it kept the slope intervals).
std::vector<std::size_t> ExhaustivePoints(const std::vector<double>& f, const std::vector<std::vector<double>>& ys,
                                          double tolerance) {
  const std::size_t m = f.size();
  std::vector<double> x(m);
  for (std::size_t k = 0; k < m; ++k) x[k] = std::log10(f[k]);
  std::vector<std::vector<double>> ly = ys;
  for (auto& y : ly)
    for (double& v : y) v = v > 0.0 ? std::log10(v) : NAN;
  const auto deviates = [&](std::size_t a, std::size_t i, std::size_t b) {
    const double t = (x[i] - x[a]) / (x[b] - x[a]);
    for (const auto& yc : ly) {
      const double ya = yc[a], yi = yc[i], yb = yc[b];
      if (std::isnan(ya) || std::isnan(yi) || std::isnan(yb)) {
        if (std::isnan(ya) != std::isnan(yi) || std::isnan(yi) != std::isnan(yb)) return true;
      } else if (std::abs(yi - (ya + t * (yb - ya))) > tolerance) {
        return true;
      }
    }
    return false;
  };
  std::vector<std::size_t> keep = {0};
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const std::size_t a = keep.back(), b = k + 1;
    bool split = x[b] - x[a] > 0.05;
    for (std::size_t i = a + 1; i < b && !split; ++i) split = deviates(a, i, b);
    if (split) keep.push_back(k);
  }
  keep.push_back(m - 1);
  return keep;
}

TEST_CASE("the points kept are those of the exhaustive chord test, on resonances, noise and gaps") {
  // A log grid of 20000 points over 0.1..1000 Hz; three series: two lightly
  // damped resonances, a noisy floor, and a series with gaps (zero: not
  // drawable on a log axis).
  std::vector<double> f(20000);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = 0.1 * std::pow(10.0, 4.0 * double(k) / double(f.size() - 1));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(0.998, 1.002);
  std::vector<std::vector<double>> ys(3, std::vector<double>(f.size()));
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double r1 = f[k] / 3.0, r2 = f[k] / 140.0;
    ys[0][k] = 1.0 / (std::pow(1 - r1 * r1, 2) + std::pow(0.004 * r1, 2)) +
               0.1 / (std::pow(1 - r2 * r2, 2) + std::pow(0.01 * r2, 2));
    ys[1][k] = 1e-6 * noise(random) / (1.0 + f[k]);
    ys[2][k] = (k / 1500) % 3 == 1 ? 0.0 : std::exp(-f[k] / 300.0);
  }
  for (const double tolerance : {2e-3, 1e-2, 0.1}) {
    CAPTURE(tolerance);
    const std::vector<const std::vector<double>*> view = {&ys[0], &ys[1], &ys[2]};
    const std::vector<std::size_t> fast = PlotPoints(f, view, f.front(), f.back(), PlotScale::kLog, tolerance);
    const std::vector<std::size_t> exhaustive = ExhaustivePoints(f, ys, tolerance);
    CHECK(fast.size() > 100);
    CHECK(fast.size() < f.size() / 2);
    // The two tests of a chord differ only in rounding: where a point lies on
    // the tolerance's edge to the last bit. None does here.
    CHECK(fast == exhaustive);
  }
}

}  // namespace deb::report
