#include "deb/spectra/flat_spectrum.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

TEST_CASE("a white flat spectrum has its level at every frequency and reports it as its white level") {
  const FlatSpectrum flat(20.0);
  for (double f_hz : {1e-6, 0.5, 1.0, 80.0, 1e6}) {
    CHECK(flat.Psd(f_hz)(0) == 20.0);  // exact
    CHECK(flat.Csd(f_hz)(0, 0) == std::complex<double>(20.0, 0.0));
  }
  REQUIRE(flat.WhiteLevel().has_value());
  CHECK((*flat.WhiteLevel())(0, 0) == 20.0);
  CHECK(flat.BreakpointsHz().empty());
  CHECK(flat.channels() == 1);
  CHECK(flat.IsDiagonal());
}

TEST_CASE("a band-limited flat spectrum is zero outside its band, has breakpoints at the limits and no white level") {
  const FlatSpectrum flat(3.0, 2.0, 50.0);
  CHECK(flat.Psd(2.0 * (1 - 1e-9))(0) == 0.0);
  CHECK(flat.Psd(2.0)(0) == 3.0);
  CHECK(flat.Psd(10.0)(0) == 3.0);
  CHECK(flat.Psd(50.0)(0) == 3.0);
  CHECK(flat.Psd(50.0 * (1 + 1e-9))(0) == 0.0);
  CHECK(flat.BreakpointsHz() == std::vector<double>{2.0, 50.0});
  CHECK_FALSE(flat.WhiteLevel().has_value());
  CHECK(flat.IsBandLimited());
}

TEST_CASE("a flat spectrum limited only from above or below has one breakpoint") {
  CHECK(FlatSpectrum(1.0, 0.0, 100.0).BreakpointsHz() == std::vector<double>{100.0});
  CHECK(FlatSpectrum(1.0, 5.0, kInf).BreakpointsHz() == std::vector<double>{5.0});
  CHECK(FlatSpectrum(1.0, 5.0, kInf).Psd(1e9)(0) == 1.0);
}

TEST_CASE("band limits [0, infinity) are no limits: the spectrum stays white") {
  const FlatSpectrum flat(4.0, 0.0, kInf);
  CHECK_FALSE(flat.IsBandLimited());
  REQUIRE(flat.WhiteLevel().has_value());
  CHECK((*flat.WhiteLevel())(0, 0) == 4.0);
}

TEST_CASE("a flat spectrum rejects a negative or non-finite level and an empty or negative band, quoting the value") {
  CHECK(InputErrorText([] { FlatSpectrum(-1.5); }).find("-1.5") != std::string::npos);
  CHECK(InputErrorText([] { FlatSpectrum(std::nan("")); }).find("finite") != std::string::npos);
  CHECK(InputErrorText([] { FlatSpectrum{kInf}; }).find("inf") != std::string::npos);
  CHECK(InputErrorText([] { FlatSpectrum(1.0, 10.0, 10.0); }).find("greater than the lower band limit 10") !=
        std::string::npos);
  CHECK(InputErrorText([] { FlatSpectrum(1.0, -1.0, 10.0); }).find("-1") != std::string::npos);
  CHECK_THROWS_AS(FlatSpectrum(1.0, 0.0, std::nan("")), InputError);
  CHECK_NOTHROW(FlatSpectrum(0.0));
}

TEST_CASE("a flat spectrum describes its level and band") {
  CHECK(FlatSpectrum(20.0).Describe().find("20") != std::string::npos);
  CHECK(FlatSpectrum(20.0, 1.0, 100.0).Describe().find("1-100 Hz") != std::string::npos);
}

}  // namespace
}  // namespace deb
