#include "deb/spectra/scaled_spectrum.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/vc_curve.h"

namespace deb {
namespace {

TEST_CASE("the thesis' two-sided 20 (um/s)^2/Hz becomes one-sided 40 with factor 2, white level included") {
  const ScaledSpectrum one_sided(std::make_shared<FlatSpectrum>(20.0), 2.0);
  CHECK(one_sided.Psd(3.0)(0) == 40.0);  // exact
  CHECK(one_sided.Csd(3.0)(0, 0) == std::complex<double>(40.0, 0.0));
  REQUIRE(one_sided.WhiteLevel().has_value());
  CHECK((*one_sided.WhiteLevel())(0, 0) == 40.0);
}

TEST_CASE("scaling keeps breakpoints, diagonal structure and band shape") {
  const auto vc = std::make_shared<VcSpectrum>(VcClass::kD, VcOptions::ThesisModified());
  const double um_to_m_squared = 1e-12;  // (um/s)^2 -> (m/s)^2
  const ScaledSpectrum scaled(vc, um_to_m_squared);
  CHECK(scaled.BreakpointsHz() == vc->BreakpointsHz());
  CHECK(scaled.IsDiagonal());
  CHECK(scaled.channels() == 1);
  CHECK_FALSE(scaled.WhiteLevel().has_value());
  for (double f_hz : {0.5, 3.0, 70.0}) {
    CHECK(scaled.Psd(f_hz)(0) == doctest::Approx(1e-12 * vc->Psd(f_hz)(0)).epsilon(1e-15));
  }
  CHECK(scaled.Describe().find("1e-12 x [VC-D") == 0);
}

TEST_CASE("a negative or non-finite scale factor is rejected quoting it") {
  const auto flat = std::make_shared<FlatSpectrum>(1.0);
  try {
    ScaledSpectrum(flat, -2.0);
    FAIL("negative factor accepted");
  } catch (const InputError& error) {
    CHECK(std::string(error.what()).find("factor -2 is invalid") != std::string::npos);
  }
  CHECK_THROWS_AS(ScaledSpectrum(flat, std::nan("")), InputError);
  CHECK_NOTHROW(ScaledSpectrum(flat, 0.0));
}

}  // namespace
}  // namespace deb
