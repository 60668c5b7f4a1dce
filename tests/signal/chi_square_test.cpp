#include "deb/signal/chi_square.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"

namespace deb {
namespace {

TEST_CASE("chi-square with 2 degrees of freedom is exponential: the p-quantile is -2 ln(1 - p) (rel 1e-9)") {
  for (double p : {1e-6, 0.025, 0.5, 0.975, 0.999999}) {
    // The CDF near 1 is 1 - Q, good to 1e-16 absolute: 1e-9 relative in x at p = 1 - 1e-6.
    CHECK(ChiSquareQuantile(p, 2.0) == doctest::Approx(-2.0 * std::log1p(-p)).epsilon(1e-9));
    CHECK(ChiSquareCdf(-2.0 * std::log1p(-p), 2.0) == doctest::Approx(p).epsilon(1e-13));
  }
}

TEST_CASE("chi-square quantiles match printed tables to their 5 significant digits") {
  // Abramowitz & Stegun Table 26.8 / any statistics table.
  CHECK(ChiSquareQuantile(0.5, 1.0) == doctest::Approx(0.45494).epsilon(2e-5));
  CHECK(ChiSquareQuantile(0.025, 10.0) == doctest::Approx(3.2470).epsilon(2e-5));
  CHECK(ChiSquareQuantile(0.975, 10.0) == doctest::Approx(20.483).epsilon(2e-5));
  CHECK(ChiSquareQuantile(0.95, 100.0) == doctest::Approx(124.34).epsilon(2e-5));
  // Fractional degrees of freedom are used by overlapped Welch estimates.
  const double x = ChiSquareQuantile(0.3, 7.5);
  CHECK(ChiSquareCdf(x, 7.5) == doctest::Approx(0.3).epsilon(1e-12));
}

TEST_CASE("a probability outside (0, 1) or non-positive degrees of freedom are input errors") {
  CHECK_THROWS_AS(ChiSquareQuantile(0.0, 2.0), InputError);
  CHECK_THROWS_AS(ChiSquareQuantile(1.0, 2.0), InputError);
  CHECK_THROWS_AS(ChiSquareQuantile(0.5, 0.0), InputError);
}

}  // namespace
}  // namespace deb
