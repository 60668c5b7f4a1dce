// Sample statistics (deb/uncertainty/sample_statistics.h) against hand
// computations: numpy's default percentile, the Wilson interval's formula,
// Spearman with ties, and the Sobol indices of an additive model against
// their analytic values.
#include <doctest/doctest.h>

#include <vector>

#include <random>

#include <cmath>

#include "deb/uncertainty/sample_design.h"
#include "deb/uncertainty/sample_statistics.h"

namespace deb {
namespace {

TEST_CASE("percentiles as numpy.percentile (linear), mean and sd with N - 1") {
  const std::vector<double> v = {7, 1, 3, 5, 9};  // sorted 1 3 5 7 9
  CHECK(Percentile(v, 0.0) == 1);
  CHECK(Percentile(v, 1.0) == 9);
  CHECK(Percentile(v, 0.5) == 5);
  CHECK(Percentile(v, 0.05) == doctest::Approx(1.4));   // h = 0.2: 1 + 0.2 * 2
  CHECK(Percentile(v, 0.95) == doctest::Approx(8.6));
  const Moments m = MeanAndSd(v);
  CHECK(m.mean == 5);
  CHECK(m.sd == doctest::Approx(std::sqrt(10.0)));
}

TEST_CASE("Wilson interval: 8 of 10 and the edge cases") {
  // (p + z^2/2n +- z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n), z = 1.96: [0.4902, 0.9433].
  const Interval i = WilsonInterval(8, 10);
  CHECK(i.low == doctest::Approx(0.49016).epsilon(1e-4));
  CHECK(i.high == doctest::Approx(0.94332).epsilon(1e-4));
  CHECK(WilsonInterval(0, 100).low == 0.0);
  CHECK(WilsonInterval(100, 100).high == 1.0);
  CHECK(WilsonInterval(100, 100).low == doctest::Approx(0.96301).epsilon(1e-4));
}

TEST_CASE("the rank correlation of independent samples stays within its noise bound 95 % of the time") {
  CHECK(RankCorrelationNoise(400) == doctest::Approx(1.959963984540054 / std::sqrt(399.0)));
  // 2000 pairs of 400 independent draws (a fixed generator: the same on
  // every machine; only ranks matter): about 5 % beyond the bound, within
  // the binomial's 3 sigma, 0.5 %.
  std::mt19937_64 draw(20261207);
  const double bound = RankCorrelationNoise(400);
  int beyond = 0;
  const int trials = 2000;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> x(400), y(400);
    for (double& v : x) v = static_cast<double>(draw());
    for (double& v : y) v = static_cast<double>(draw());
    beyond += std::abs(SpearmanCorrelation(x, y)) > bound ? 1 : 0;
  }
  const double fraction = static_cast<double>(beyond) / trials;
  MESSAGE("beyond the bound: " << fraction);
  CHECK(std::abs(fraction - 0.05) < 3.0 * std::sqrt(0.05 * 0.95 / trials));
}

TEST_CASE("Spearman: monotone, reversed, ties, constant") {
  CHECK(SpearmanCorrelation({1, 2, 3, 4}, {1, 8, 27, 64}) == doctest::Approx(1.0));
  CHECK(SpearmanCorrelation({1, 2, 3, 4}, {4, 3, 2, 1}) == doctest::Approx(-1.0));
  // Ranks x 1 2 3 4, y 1.5 1.5 3 4: rho = Pearson of the ranks = 0.9486833.
  CHECK(SpearmanCorrelation({1, 2, 3, 4}, {5, 5, 6, 7}) == doctest::Approx(0.9486832980505138));
  CHECK(SpearmanCorrelation({1, 2, 3}, {2, 2, 2}) == 0.0);
}

TEST_CASE("Sobol indices of f = x1 + 2 x2 + 0 x3, uniform x: S = ST = 1/5, 4/5, 0") {
  const std::size_t n = 8192;
  const SampleDesign d(SamplingMethod::kSobol, 1, n, 6);
  std::vector<double> fa, fb;
  std::vector<std::vector<double>> fab(3);
  const auto f = [](double a, double b, double) { return a + 2 * b; };
  for (std::size_t j = 0; j < n; ++j) {
    const auto u = d.Point(j);
    fa.push_back(f(u[0], u[1], u[2]));
    fb.push_back(f(u[3], u[4], u[5]));
    for (int i = 0; i < 3; ++i) {
      double a[3] = {u[0], u[1], u[2]};
      a[i] = u[3 + static_cast<std::size_t>(i)];
      fab[static_cast<std::size_t>(i)].push_back(f(a[0], a[1], a[2]));
    }
  }
  const double expected[3] = {0.2, 0.8, 0.0};
  for (int i = 0; i < 3; ++i) {
    const SobolIndices s = SobolIndicesOf(fa, fb, fab[static_cast<std::size_t>(i)]);
    MESSAGE("x" << i + 1 << ": S " << s.first << ", ST " << s.total << " (exact " << expected[i] << ")");
    CHECK(std::abs(s.first - expected[i]) < 0.01);
    CHECK(std::abs(s.total - expected[i]) < 0.01);
  }
}

}  // namespace
}  // namespace deb
