#include "deb/report/figure/phase_axis.h"

#include <doctest/doctest.h>

#include <cmath>

namespace deb::report {

TEST_CASE("a phase axis steps by 45 degrees times a power of two, at most 5 steps over any span") {
  CHECK(PhaseStepDeg(90.0) == 45.0);
  CHECK(PhaseStepDeg(225.0) == 45.0);
  CHECK(PhaseStepDeg(226.0) == 90.0);
  CHECK(PhaseStepDeg(450.0) == 90.0);
  CHECK(PhaseStepDeg(451.0) == 180.0);
  CHECK(PhaseStepDeg(900.0) == 180.0);
  // The unwrapped phase of a 180-mode path: ~6800 degrees, ticks every 1440 (not 38 ticks of 180).
  CHECK(PhaseStepDeg(6800.0) == 1440.0);
  for (double span = 1.0; span < 1e6; span *= 1.07) {
    CAPTURE(span);
    FigureAxis y;
    SetPhaseAxis(y, -span, 0.0);
    const double step = PhaseStepDeg(span);
    CHECK(std::fmod(step / 45.0, 1.0) == 0.0);
    CHECK(std::log2(step / 45.0) == std::round(std::log2(step / 45.0)));
    REQUIRE(y.min);
    REQUIRE(y.max);
    CHECK(*y.min <= -span);
    CHECK(*y.max >= 0.0);
    // Whole steps, every one labelled, no more than 5 intervals (6 ticks).
    CHECK(y.tics.size() >= 2);
    CHECK(y.tics.size() <= static_cast<std::size_t>(kMaxPhaseIntervals) + 1);
    for (const auto& [value, label] : y.tics) CHECK(std::fmod(std::abs(value), step) == 0.0);
  }
}

TEST_CASE("a phase axis holds at least the span asked for") {
  FigureAxis y;
  SetPhaseAxis(y, -10.0, -10.0, 90.0);
  REQUIRE(y.min);
  CHECK(*y.min == -45.0);
  CHECK(*y.max - *y.min >= 90.0);
  CHECK(y.tics.front().first == -45.0);
  CHECK(y.tics.front().second == "-45");
}

}  // namespace deb::report
