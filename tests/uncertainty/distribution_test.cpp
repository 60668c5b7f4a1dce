// Distributions of uncertain parameters (deb/uncertainty/distribution.h):
// quantiles against their closed forms, and Mean and StandardDeviation
// against the integrals of the quantile function over (0, 1) (an
// independent computation: E[X^k] = integral of Q(u)^k du).
#include <doctest/doctest.h>

#include <cmath>

#include "deb/uncertainty/distribution.h"

namespace deb {
namespace {

Distribution Normal(double mean, double sigma) {
  Distribution d;
  d.kind = DistributionKind::kNormal;
  d.mean = mean;
  d.sigma = sigma;
  return d;
}

// Mean and sd of Q(u) by the midpoint rule over 2e6 points of (0, 1).
std::pair<double, double> Integrated(const Distribution& d) {
  const int n = 2000000;
  double s1 = 0.0, s2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = d.Quantile((i + 0.5) / n);
    s1 += x;
    s2 += x * x;
  }
  const double mean = s1 / n;
  return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean))};
}

TEST_CASE("quantiles against their closed forms") {
  CHECK(StandardNormalQuantile(0.975) == doctest::Approx(1.959963984540054).epsilon(1e-15));
  CHECK(StandardNormalCdf(-3.0) == doctest::Approx(0.0013498980316301).epsilon(1e-13));
  CHECK(Normal(5.0, 2.0).Quantile(0.975) == doctest::Approx(5.0 + 2.0 * 1.959963984540054).epsilon(1e-15));

  Distribution u;
  u.kind = DistributionKind::kUniform;
  u.min = 1.0;
  u.max = 3.0;
  CHECK(u.Quantile(0.25) == 1.5);

  Distribution l;  // median 20, p95 40: sigma_log = ln 2 / 1.6449
  l.kind = DistributionKind::kLogNormal;
  l.mean = 20.0;
  l.sigma = std::log(2.0) / 1.6448536269514722;
  CHECK(l.Quantile(0.95) == doctest::Approx(40.0).epsilon(1e-14));
  CHECK(l.Quantile(0.5) == doctest::Approx(20.0).epsilon(1e-15));

  Distribution t;  // triangular (a, c, b): Q(u) = a + sqrt(u (b - a)(c - a)) below F(c)
  t.kind = DistributionKind::kTriangular;
  t.min = 2.0;
  t.mode = 3.0;
  t.max = 6.0;
  CHECK(t.Quantile(0.1) == doctest::Approx(2.0 + std::sqrt(0.1 * 4.0 * 1.0)).epsilon(1e-14));
  CHECK(t.Quantile(0.9) == doctest::Approx(6.0 - std::sqrt(0.1 * 4.0 * 3.0)).epsilon(1e-14));

  Distribution tn;  // symmetric truncation: the median is the mean; the ends are the bounds
  tn.kind = DistributionKind::kTruncatedNormal;
  tn.mean = 1.0;
  tn.sigma = 0.1;
  tn.min = 0.8;
  tn.max = 1.2;
  CHECK(tn.Quantile(0.5) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(tn.Quantile(1e-12) >= 0.8);
  CHECK(tn.Quantile(1 - 1e-12) <= 1.2);
  // A window far in the upper tail (mirrored internally) stays inside it and monotone.
  Distribution far = tn;
  far.min = 1.9;
  far.max = 2.0;
  double last = 1.9;
  for (double v : {0.001, 0.3, 0.7, 0.999}) {
    const double x = far.Quantile(v);
    CHECK(x >= last);
    CHECK(x <= 2.0);
    last = x;
  }

  Distribution c;
  c.kind = DistributionKind::kDiscrete;
  c.values = {10, 20, 30};
  c.probabilities = {0.2, 0.5, 0.3};
  CHECK(c.Quantile(0.19) == 10);
  CHECK(c.Quantile(0.21) == 20);
  CHECK(c.Quantile(0.71) == 30);
}

TEST_CASE("Mean and StandardDeviation equal the integrals of the quantile function") {
  std::vector<Distribution> all;
  all.push_back(Normal(5.0, 2.0));
  Distribution d;
  d.kind = DistributionKind::kUniform;
  d.min = 1.0;
  d.max = 3.0;
  all.push_back(d);
  d = {};
  d.kind = DistributionKind::kLogNormal;
  d.mean = 20.0;
  d.sigma = 0.4;
  all.push_back(d);
  d = {};
  d.kind = DistributionKind::kTruncatedNormal;
  d.mean = 1.0;
  d.sigma = 0.2;
  d.min = 0.9;
  d.max = 1.5;
  all.push_back(d);
  d = {};
  d.kind = DistributionKind::kTriangular;
  d.min = 2.0;
  d.mode = 3.0;
  d.max = 6.0;
  all.push_back(d);
  d = {};
  d.kind = DistributionKind::kDiscrete;
  d.values = {10, 20, 30};
  d.probabilities = {0.2, 0.5, 0.3};
  all.push_back(d);
  for (const Distribution& x : all) {
    CAPTURE(x.Text());
    REQUIRE(x.Problem().empty());
    const auto [mean, sd] = Integrated(x);
    // The midpoint rule misses the normal tails beyond u = 2.5e-7: 1e-4.
    CHECK(x.Mean() == doctest::Approx(mean).epsilon(1e-4));
    CHECK(x.StandardDeviation() == doctest::Approx(sd).epsilon(1e-4));
    CHECK(x.BoxLow() <= x.Quantile(0.01));
    CHECK(x.BoxHigh() >= x.Quantile(0.99));
  }
}

TEST_CASE("problems: each rule named") {
  CHECK(Normal(1.0, -1.0).Problem() == "sigma -1 must be finite and > 0");
  Distribution u;
  u.kind = DistributionKind::kUniform;
  u.min = 3.0;
  u.max = 1.0;
  CHECK(u.Problem() == "min 3 must be below max 1");
  Distribution c;
  c.kind = DistributionKind::kDiscrete;
  c.values = {1, 2};
  c.probabilities = {0.5, 0.6};
  CHECK(c.Problem() == "the probabilities add up to 1.1, not 1");
  Distribution t;
  t.kind = DistributionKind::kTriangular;
  t.min = 1;
  t.max = 2;
  t.mode = 3;
  CHECK(t.Problem() == "the mode (the parameter's value) 3 must lie within [1, 2]");
}

}  // namespace
}  // namespace deb

namespace deb {

TEST_CASE("a distribution's text for a reader is in the parameter's unit, to 4 digits; a sigma of log is not scaled") {
  Distribution u;
  u.kind = DistributionKind::kUniform;
  u.min = 70.0;  // N s/m
  u.max = 130.0;
  CHECK(u.Text() == "uniform(70, 130)");
  CHECK(u.Text(1000.0) == "uniform(0.07, 0.13)");  // in N s/mm
  Distribution l;
  l.kind = DistributionKind::kLogNormal;
  l.mean = 20.0;
  l.sigma = 0.2465052825762026;
  CHECK(l.Text() == "lognormal(median 20, sigma of log 0.2465052825762026)");  // exact, for summary.json
  CHECK(l.Text(1.0) == "lognormal(median 20, sigma of log 0.2465)");
  CHECK(l.Text(1e-3) == "lognormal(median 2e+04, sigma of log 0.2465)");
}

}  // namespace deb
