#include "deb/core/frequency_grid.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/integrate.h"

namespace deb {

TEST_CASE("a log grid spans its range with equal ratios") {
  const FrequencyGrid g = FrequencyGrid::Log(0.1, 1000.0, 5);
  REQUIRE(g.size() == 5);
  CHECK(g.min_hz() == 0.1);
  CHECK(g.max_hz() == 1000.0);
  CHECK(g.f_hz()[2] == doctest::Approx(10.0).epsilon(1e-14));
}

TEST_CASE("a grid rejects non-increasing, non-positive and too few frequencies") {
  CHECK_THROWS_WITH_AS(FrequencyGrid({1.0, 2.0, 2.0}),
                       "frequency grid: frequencies must increase strictly, but [1] = 2 Hz >= [2] = 2 Hz",
                       InputError);
  CHECK_THROWS_WITH_AS(FrequencyGrid({0.0, 2.0}),
                       "frequency grid: frequency [0] = 0 Hz must be finite and > 0", InputError);
  CHECK_THROWS_AS(FrequencyGrid({1.0}), InputError);
  CHECK_THROWS_AS(FrequencyGrid::Log(10.0, 1.0, 10), InputError);
}

TEST_CASE("the automatic grid puts points either side of every breakpoint in range") {
  AutoGridOptions o;
  o.min_hz = 1.0;
  o.max_hz = 100.0;
  o.points_per_decade = 10;
  const FrequencyGrid g = AutoGrid(o, {}, {7.0, 1000.0});
  const auto& f = g.f_hz();
  const auto below = std::lower_bound(f.begin(), f.end(), 7.0);
  REQUIRE(below != f.begin());
  CHECK(*(below - 1) == doctest::Approx(7.0).epsilon(2e-9));
  CHECK(*below == doctest::Approx(7.0).epsilon(2e-9));
  CHECK(g.max_hz() == 100.0);
}

TEST_CASE("the automatic grid resolves a lightly damped resonance to 1e-4 of its peak area") {
  // Lorentzian peak of a resonance: area over all f is pi * f_n * zeta * height.
  for (double zeta : {1e-4, 1e-3, 1e-2}) {
    CAPTURE(zeta);
    AutoGridOptions o;
    o.min_hz = 1.0;
    o.max_hz = 1000.0;
    o.points_per_decade = 20;
    const double fn = 37.0;
    const FrequencyGrid g = AutoGrid(o, {{fn, zeta}}, {});
    std::vector<double> s;
    for (double f : g.f_hz()) s.push_back(1.0 / ((f - fn) * (f - fn) + fn * fn * zeta * zeta));
    const double exact = (std::atan((1000.0 - fn) / (fn * zeta)) - std::atan((1.0 - fn) / (fn * zeta))) /
                         (fn * zeta);
    CHECK(CumulativeIntegral(g.f_hz(), s).back() == doctest::Approx(exact).epsilon(1e-4));
  }
}

TEST_CASE("automatic grid options are validated with the option named") {
  AutoGridOptions o;
  o.points_per_decade = 1;
  CHECK_THROWS_WITH_AS(o.Validate(), "automatic grid: points_per_decade must be >= 2, got 1", InputError);
}

}  // namespace deb

namespace deb {
TEST_CASE("the automatic grid stays compact: under 2500 points for a resonance with zeta 1e-4") {
  AutoGridOptions o;
  o.min_hz = 0.1;
  o.max_hz = 1000.0;
  const std::size_t base = AutoGrid(o, {}, {}).size();
  const std::size_t refined = AutoGrid(o, {{10.0, 1e-4}}, {}).size();
  CHECK(base == 801);
  MESSAGE("points added for zeta = 1e-4: " << refined - base);
  CHECK(refined - base < 2500);
}
}  // namespace deb
