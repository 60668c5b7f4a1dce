#include "deb/report/figure/plot_points.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

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

}  // namespace deb::report
