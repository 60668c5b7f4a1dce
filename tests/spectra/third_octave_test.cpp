#include "deb/spectra/third_octave.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

TEST_CASE("base-2 centres from 1 Hz hit the powers of two exactly") {
  for (int k = -3; k <= 18; k += 3) {
    CHECK(ThirdOctaveBandAt(k, ThirdOctaveSeries::kBase2From1Hz).centre_hz == std::ldexp(1.0, k / 3));
  }
}

TEST_CASE("adjacent bands share an edge bit for bit and each bandwidth is f_c (G^(1/6) - G^(-1/6))") {
  for (auto series : {ThirdOctaveSeries::kBase2From1Hz, ThirdOctaveSeries::kIecBase2,
                      ThirdOctaveSeries::kIecBase10}) {
    const double g = series == ThirdOctaveSeries::kIecBase10 ? std::pow(10.0, 0.3) : 2.0;
    for (int k = -40; k < 40; ++k) {
      const ThirdOctaveBand band = ThirdOctaveBandAt(k, series);
      CHECK(band.hi_hz == ThirdOctaveBandAt(k + 1, series).lo_hz);  // exact
      const double expected = band.centre_hz * (std::pow(g, 1.0 / 6) - std::pow(g, -1.0 / 6));
      CHECK(band.BandwidthHz() == doctest::Approx(expected).epsilon(1e-12));
    }
  }
  // The base-2 bandwidth is about 0.2316 f_c (docs/method.md, convention 5).
  const ThirdOctaveBand one = ThirdOctaveBandAt(0, ThirdOctaveSeries::kBase2From1Hz);
  CHECK(one.BandwidthHz() == doctest::Approx(0.2316).epsilon(1e-4));
}

TEST_CASE("nominal 0.5 Hz to 80 Hz selects 23 bands in each series, ending at that series' exact centres") {
  struct Expected {
    ThirdOctaveSeries series;
    double lowest_hz, highest_hz;
  };
  // 2^(-1), 2^(19/3); 1000 2^(-11), 1000 2^(-11/3); 1000 10^(-3.3), 1000 10^(-1.1).
  for (const Expected& e : {Expected{ThirdOctaveSeries::kBase2From1Hz, 0.5, 80.63494719327},
                            Expected{ThirdOctaveSeries::kIecBase2, 0.48828125, 78.74506561842},
                            Expected{ThirdOctaveSeries::kIecBase10, 0.50118723362, 79.43282347243}}) {
    const auto bands = ThirdOctaveBandsBetween(0.5, 80.0, e.series);
    CHECK(bands.size() == 23);
    CHECK(bands.front().centre_hz == doctest::Approx(e.lowest_hz).epsilon(1e-10));
    CHECK(bands.back().centre_hz == doctest::Approx(e.highest_hz).epsilon(1e-10));
  }
}

TEST_CASE("a frequency halfway between two band centres is not a band name") {
  const std::string message = InputErrorText([] { ThirdOctaveBandNear(0.56, ThirdOctaveSeries::kBase2From1Hz); });
  CHECK(message.find("0.56 Hz is not a band centre") != std::string::npos);
  CHECK(message.find("base2_1hz") != std::string::npos);
  CHECK_THROWS_AS(ThirdOctaveBandNear(0.0, ThirdOctaveSeries::kBase2From1Hz), InputError);
  CHECK_THROWS_AS(ThirdOctaveBandsBetween(80.0, 0.5, ThirdOctaveSeries::kBase2From1Hz), InputError);
}

TEST_CASE("nominal band names within rounding select their band") {
  CHECK(ThirdOctaveBandNear(6.3, ThirdOctaveSeries::kBase2From1Hz).index == 8);
  CHECK(ThirdOctaveBandNear(12.5, ThirdOctaveSeries::kBase2From1Hz).index == 11);
  CHECK(ThirdOctaveBandNear(31.5, ThirdOctaveSeries::kIecBase10).index == -15);
}

TEST_CASE("one-third-octave series names round-trip and an unknown name lists the allowed ones") {
  for (auto series : {ThirdOctaveSeries::kBase2From1Hz, ThirdOctaveSeries::kIecBase2,
                      ThirdOctaveSeries::kIecBase10}) {
    CHECK(ParseThirdOctaveSeries(ToString(series)) == series);
  }
  CHECK(InputErrorText([] { ParseThirdOctaveSeries("base2"); }).find("'base2'; allowed: base2_1hz, iec_base2, iec_base10") !=
        std::string::npos);
}

}  // namespace
}  // namespace deb
