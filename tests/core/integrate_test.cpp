#include "deb/core/integrate.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/frequency_grid.h"

namespace deb {

TEST_CASE("a power law is integrated exactly whatever the grid spacing") {
  // s = 3 f^-2 on [1, 100] has integral 3 (1 - 1/100) = 2.97.
  const std::vector<double> f = FrequencyGrid::Log(1.0, 100.0, 5).f_hz();
  std::vector<double> s;
  for (double x : f) s.push_back(3.0 * std::pow(x, -2.0));
  const auto c = CumulativeIntegral(f, s);
  CHECK(c.back() == doctest::Approx(2.97).epsilon(1e-12));
}

TEST_CASE("the 1/f power law integrates to a logarithm") {
  const std::vector<double> f = {1.0, 10.0};
  CHECK(CumulativeIntegral(f, {1.0, 0.1}).back() == doctest::Approx(std::log(10.0)).epsilon(1e-12));
}

TEST_CASE("an interval with a zero end falls back to the trapezoid") {
  CHECK(PowerLawIntervalIntegral(1.0, 3.0, 0.0, 2.0) == doctest::Approx(2.0).epsilon(1e-15));
}

TEST_CASE("a partial-interval integral agrees with the full cumulative integral") {
  const std::vector<double> f = FrequencyGrid::Log(0.1, 1000.0, 41).f_hz();
  std::vector<double> s;
  for (double x : f) s.push_back(1.0 / (1.0 + x * x));
  const auto c = CumulativeIntegral(f, s);
  CHECK(IntegralBetween(f, s, f.front(), f.back()) == doctest::Approx(c.back()).epsilon(1e-13));
  // Splitting at a point inside an interval changes nothing for a power law segment.
  const double mid = 3.3;
  CHECK(IntegralBetween(f, s, f.front(), mid) + IntegralBetween(f, s, mid, f.back()) ==
        doctest::Approx(c.back()).epsilon(1e-13));
}

TEST_CASE("the cumulative integral is the same, bit for bit, on one thread and on four") {
  const std::vector<double> f = FrequencyGrid::Log(0.01, 1000.0, 20001).f_hz();
  std::vector<double> s;
  for (double x : f) s.push_back(1.0 / (1.0 + std::pow(x - 3.0, 2)));
  CHECK(CumulativeIntegral(f, s, 1) == CumulativeIntegral(f, s, 4));
}

TEST_CASE("a flat spectrum's band integral is level times bandwidth") {
  const std::vector<double> f = {0.5, 2.0, 7.0};
  const std::vector<double> s = {4.0, 4.0, 4.0};
  CHECK(IntegralBetween(f, s, 1.0, 5.0) == doctest::Approx(16.0).epsilon(1e-14));
}

}  // namespace deb
