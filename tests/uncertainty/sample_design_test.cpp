// Sample designs (deb/uncertainty/sample_design.h): a point depends on
// (seed, index) only; Latin hypercube strata hold one point each; the first
// 2^m Sobol points hold one point in each shifted stratum and integrate a
// smooth function closely; different seeds differ.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "deb/uncertainty/sample_design.h"

namespace deb {
namespace {

TEST_CASE("a point depends on (seed, index) only, and lies in (0, 1)") {
  for (SamplingMethod m : {SamplingMethod::kMonteCarlo, SamplingMethod::kLatinHypercube, SamplingMethod::kSobol}) {
    const SampleDesign a(m, 7, 100, 3), b(m, 7, 100, 3), c(m, 8, 100, 3);
    CHECK(a.Point(42) == b.Point(42));
    CHECK(a.Point(42) != c.Point(42));
    for (std::size_t i = 99; i < 100; --i)
      for (double u : a.Point(i)) {
        CHECK(u > 0.0);
        CHECK(u < 1.0);
      }
  }
}

TEST_CASE("Latin hypercube: one point in each of the N strata of every dimension") {
  const std::size_t n = 500;
  const SampleDesign d(SamplingMethod::kLatinHypercube, 3, n, 4);
  for (std::size_t dim = 0; dim < 4; ++dim) {
    std::set<std::size_t> strata;
    for (std::size_t i = 0; i < n; ++i) strata.insert(static_cast<std::size_t>(d.Point(i)[dim] * n));
    CHECK(strata.size() == n);
  }
}

TEST_CASE("Sobol: one point per shifted stratum, and the integral of x y to 2e-3 with 1024 points") {
  const std::size_t n = 1024;
  const SampleDesign sobol(SamplingMethod::kSobol, 5, n, 2), mc(SamplingMethod::kMonteCarlo, 5, n, 2);
  // The shift of each dimension: where point 0 (the origin) went.
  const std::vector<double> shift = sobol.Point(0);
  for (std::size_t dim = 0; dim < 2; ++dim) {
    std::set<std::size_t> strata;
    for (std::size_t i = 0; i < n; ++i) {
      double x = sobol.Point(i)[dim] - shift[dim];
      x -= std::floor(x);
      // The first 2^m points of a Sobol dimension are exactly the multiples of 1/2^m.
      strata.insert(static_cast<std::size_t>(std::lround(x * n)) % n);
    }
    CHECK(strata.size() == n);
  }
  // The integral of x y over the unit square is 1/4.
  double s_sobol = 0.0, s_mc = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto p = sobol.Point(i), q = mc.Point(i);
    s_sobol += p[0] * p[1];
    s_mc += q[0] * q[1];
  }
  const double e_sobol = std::abs(s_sobol / n - 0.25), e_mc = std::abs(s_mc / n - 0.25);
  MESSAGE("integral of x y with 1024 points: Sobol error " << e_sobol << ", Monte Carlo error " << e_mc);
  CHECK(e_sobol < 2e-3);
}

TEST_CASE("Monte Carlo uniforms: mean 1/2 and variance 1/12 within 4 standard errors") {
  const std::size_t n = 100000;
  const SampleDesign d(SamplingMethod::kMonteCarlo, 11, n, 1);
  double s = 0.0, s2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = d.Point(i)[0];
    s += u;
    s2 += u * u;
  }
  const double mean = s / n, var = s2 / n - mean * mean;
  CHECK(std::abs(mean - 0.5) < 4 * std::sqrt(1.0 / 12 / n));
  CHECK(std::abs(var - 1.0 / 12) < 4 * std::sqrt(1.0 / 180 / n));
}

}  // namespace
}  // namespace deb
