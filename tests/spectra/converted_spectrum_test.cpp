#include "deb/spectra/converted_spectrum.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/spectra/channel_set.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/peterson_noise_model.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

TEST_CASE("acceleration to velocity divides by (2 pi f)^2 and scales by the unit ratio squared (rel 1e-14)") {
  const auto accel = std::make_shared<PetersonSpectrum>(PetersonModel::kLow);
  const ConvertedSpectrum velocity(accel, 1e6, -1, "um/s");  // m/s^2 -> um/s
  for (double f : {0.01, 0.2, 1.0, 9.5}) {
    CAPTURE(f);
    const double w = kTwoPi * f;
    CHECK(velocity.Psd(f)(0) == doctest::Approx(1e12 * accel->Psd(f)(0) / (w * w)).epsilon(1e-14));
    CHECK(velocity.Csd(f)(0, 0).real() == doctest::Approx(1e12 * accel->Psd(f)(0) / (w * w)).epsilon(1e-14));
  }
  CHECK(velocity.BreakpointsHz() == accel->BreakpointsHz());
  CHECK_FALSE(velocity.WhiteLevel());
  CHECK(velocity.Describe().find("] in um/s (scale 1e+06, integrated once in time)") != std::string::npos);
  const ConvertedSpectrum displacement(accel, 1e9, -2, "nm");
  CHECK(displacement.Psd(2.0)(0) ==
        doctest::Approx(1e18 * accel->Psd(2.0)(0) / std::pow(kTwoPi * 2.0, 4)).epsilon(1e-14));
  const ConvertedSpectrum jerk(accel, 1.0, 1, "m/s^3");
  CHECK(jerk.Psd(2.0)(0) == doctest::Approx(accel->Psd(2.0)(0) * std::pow(kTwoPi * 2.0, 2)).epsilon(1e-14));
}

TEST_CASE("a pure scale keeps a white level and the channel structure; bad parameters are rejected") {
  const auto white = std::make_shared<FlatSpectrum>(3.0);
  const auto pair = std::make_shared<CorrelatedChannels>(
      std::make_shared<IndependentChannels>(std::vector<std::shared_ptr<const Spectrum>>{white, white}),
      (Eigen::Matrix2d() << 1.0, 0.5, 0.5, 1.0).finished());
  const ConvertedSpectrum scaled(pair, 1e3, 0, "mm/s");
  REQUIRE(scaled.WhiteLevel());
  CHECK((*scaled.WhiteLevel() - 1e6 * *pair->WhiteLevel()).norm() <= 1e-15 * (1e6 * *pair->WhiteLevel()).norm());
  CHECK_FALSE(scaled.IsDiagonal());
  CHECK(scaled.Csd(5.0)(0, 1).real() == doctest::Approx(1.5e6));
  CHECK(InputErrorText([&] { ConvertedSpectrum(white, 0.0, 0, "m"); }).find("scale 0 is invalid") !=
        std::string::npos);
  CHECK(InputErrorText([&] { ConvertedSpectrum(white, 1.0, 3, "m"); }).find("derivative order 3 is invalid") !=
        std::string::npos);
}

}  // namespace
}  // namespace deb
