#include "deb/spectra/band_table.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/core/error.h"

namespace deb {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParseBandTable(text, "t.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("a band table as deb spectrum bands writes it reads past the edges, counts and classes") {
  const BandTable t = ParseBandTable(
      "# one-third-octave band RMS\n# unit: um/s\ncentre_hz, lo_hz, hi_hz, points, x, x_class, y, y_class\n"
      "8, 7.1, 8.9, 3, 1.5, VC-D, 2.5, none\n10, 8.9, 11.2, 4, 0.5, -, 3.5, VC-A\n",
      "t.csv");
  CHECK(t.unit == std::string("um/s"));
  CHECK(t.channel_names == std::vector<std::string>{"x", "y"});
  CHECK(t.centre_hz == std::vector<double>{8.0, 10.0});
  REQUIRE(t.rms.rows() == 2);
  CHECK(t.rms(0, 0) == 1.5);
  CHECK(t.rms(1, 1) == 3.5);
}

TEST_CASE("a band table by hand may have no header; bad cells are located") {
  const BandTable t = ParseBandTable("8 1\n10 2\n", "t.csv");
  CHECK(t.channel_names == std::vector<std::string>{"ch1"});
  CHECK(t.rms(1, 0) == 2.0);
  // The class column's word does not shift the columns of the cells after it.
  CHECK(ErrorOf("centre_hz, x_class, x\n8, VC-D, abc\n") == "t.csv:2:10: column 'x': 'abc' is not a number");
  CHECK(ErrorOf("centre_hz, x\n8, -1\n").find("t.csv:2:4: band RMS '-1' in column 'x' is negative") == 0);
  CHECK(ErrorOf("centre_hz, x\n10, 1\n8, 1\n").find("t.csv:3:1: ") == 0);
  CHECK(ErrorOf("# quantity: asd\ncentre_hz, x\n8, 1\n").find("t.csv:1:") == 0);
  CHECK(ErrorOf("centre_hz, lo_hz\n8, 7\n").find("no channel column") != std::string::npos);
}

}  // namespace deb

namespace deb {

TEST_CASE("a band table written from band RMS values reads back to the same centres, channels and RMS") {
  SpectrumClasses classes;
  const std::vector<ThirdOctaveBand> bands = {ThirdOctaveBandNear(8.0, ThirdOctaveSeries::kBase2From1Hz),
                                              ThirdOctaveBandNear(10.0, ThirdOctaveSeries::kBase2From1Hz)};
  classes.bands = {{{bands[0], 1.5, 3}, {bands[1], 0.5, 7}}, {{bands[0], 2.5, 3}, {bands[1], 3.5, 7}}};
  const std::string text = BandTableText({"band RMS of psd.csv"}, "um/s", {"x", "y"}, classes);
  CHECK(text.rfind("# band RMS of psd.csv\n# unit: um/s\ncentre_hz, lo_hz, hi_hz, points, x, y\n", 0) == 0);
  const BandTable t = ParseBandTable(text, "t.csv");
  CHECK(t.unit == std::string("um/s"));
  CHECK(t.channel_names == std::vector<std::string>{"x", "y"});
  REQUIRE(t.rms.rows() == 2);
  CHECK(t.centre_hz[0] == doctest::Approx(bands[0].centre_hz).epsilon(1e-9));
  CHECK(t.rms(0, 1) == 2.5);
  CHECK(t.rms(1, 0) == 0.5);
  CHECK(BandTableText({}, "", {"x", "y"}, classes).rfind("centre_hz,", 0) == 0);  // no unit line
}

TEST_CASE("a band table as a PSD holds each band's RMS squared over its width") {
  const BandTable t = ParseBandTable("8 1 2\n10 3 4\n", "t.csv");
  const BandTablePsd p = PsdOfBandTable(t, ThirdOctaveSeries::kBase2From1Hz);
  REQUIRE(p.psd.cols() == 2);
  REQUIRE(p.f_hz.size() == 4);  // two points per band
  const ThirdOctaveBand b = ThirdOctaveBandNear(10.0, ThirdOctaveSeries::kBase2From1Hz);
  CHECK(p.psd(2, 1) == doctest::Approx(16.0 / (b.hi_hz - b.lo_hz)).epsilon(1e-12));
}

}  // namespace deb
