#include "deb/spectra/vc_curve.h"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

const VcClass kAllClasses[] = {VcClass::kA, VcClass::kB, VcClass::kC, VcClass::kD,
                               VcClass::kE, VcClass::kF, VcClass::kG};

TEST_CASE("every band of a VC curve integrates to the squared class velocity (rel 1e-12)") {
  for (VcClass vc_class : kAllClasses) {
    for (auto series : {ThirdOctaveSeries::kBase2From1Hz, ThirdOctaveSeries::kIecBase2,
                        ThirdOctaveSeries::kIecBase10}) {
      VcOptions options = VcOptions::ThesisModified();
      options.series = series;
      const VcSpectrum vc(vc_class, options);
      const double v = VcCriterionOf(vc_class).velocity_um_s;
      const double g = series == ThirdOctaveSeries::kIecBase10 ? std::pow(10.0, 0.3) : 2.0;
      for (const ThirdOctaveBand& band : vc.bands()) {
        // The PSD is constant on the band, so the integral is PSD x width, with
        // the edges f_c G^(+-1/6) computed here independently.
        const double lo = band.centre_hz * std::pow(g, -1.0 / 6);
        const double hi = band.centre_hz * std::pow(g, 1.0 / 6);
        const double psd = vc.Psd(band.centre_hz)(0);
        CHECK(psd * (hi - lo) == doctest::Approx(v * v).epsilon(1e-12));
        CHECK(vc.Psd(lo * (1 + 1e-9))(0) == psd);
        CHECK(vc.Psd(hi * (1 - 1e-9))(0) == psd);
      }
    }
  }
}

TEST_CASE("the thesis' modified VC has 23 bands whose centres round to its Table 4-1 (abs 0.006 Hz)") {
  // Nizamoglu (2015) Table 4-1, printed to 0.01 Hz (80.64 is 64 x 1.26).
  const double table_4_1[] = {0.5,  0.63,  0.79,  1,    1.26,  1.59, 2,     2.52,
                              3.17, 4,     5.04,  6.35, 8,     10.08, 12.7, 16,
                              20.16, 25.4, 32,    40.32, 50.8,  64,    80.64};
  const VcSpectrum vc(VcClass::kD, VcOptions::ThesisModified());
  REQUIRE(vc.bands().size() == 23);
  for (std::size_t i = 0; i < 23; ++i) {
    CHECK(std::abs(vc.bands()[i].centre_hz - table_4_1[i]) <= 0.006);
  }
  // Covered range 0.445-90.5 Hz (the thesis quotes 0.44-90.49 Hz).
  CHECK(vc.BreakpointsHz().front() == doctest::Approx(0.5 * std::pow(2.0, -1.0 / 6)).epsilon(1e-14));
  CHECK(vc.BreakpointsHz().back() == doctest::Approx(64 * std::pow(2.0, 1.0 / 3 + 1.0 / 6)).epsilon(1e-14));
}

TEST_CASE("the IEC base-2 centres would not reproduce Table 4-1: they sit 2.4 % lower") {
  VcOptions options = VcOptions::ThesisModified();
  options.series = ThirdOctaveSeries::kIecBase2;
  const VcSpectrum vc(VcClass::kD, options);
  REQUIRE(vc.bands().size() == 23);
  CHECK(std::abs(vc.bands().front().centre_hz - 0.5) > 0.006);
}

TEST_CASE("the modified VC-D carries 23 v^2 in total, an RMS of 29.97 um/s (rel 1e-12)") {
  const VcSpectrum vc(VcClass::kD, VcOptions::ThesisModified());
  double variance = 0.0;
  for (std::size_t i = 0; i < vc.bands().size(); ++i) variance += vc.band_psd()[i] * vc.bands()[i].BandwidthHz();
  CHECK(variance == doctest::Approx(23 * 6.25 * 6.25).epsilon(1e-12));
  CHECK(std::sqrt(variance) == doctest::Approx(29.974).epsilon(1e-4));
}

TEST_CASE("the default VC curve spans the 11 bands from 8 Hz to 80 Hz") {
  const VcSpectrum vc(VcClass::kC);
  REQUIRE(vc.bands().size() == 11);
  CHECK(vc.bands().front().centre_hz == 8.0);
  CHECK(vc.bands().back().centre_hz == doctest::Approx(80.635).epsilon(1e-5));
  CHECK(vc.Psd(7.0)(0) == 0.0);
  CHECK(vc.Psd(8.0)(0) > 0.0);
}

TEST_CASE("a VC curve is zero outside its bands and breaks at every band edge") {
  const VcSpectrum vc(VcClass::kD, VcOptions::ThesisModified());
  const std::vector<double> edges = vc.BreakpointsHz();
  REQUIRE(edges.size() == 24);
  for (std::size_t i = 0; i < 23; ++i) {
    CHECK(edges[i] == vc.bands()[i].lo_hz);
    CHECK(edges[i + 1] == vc.bands()[i].hi_hz);
  }
  CHECK(vc.Psd(edges.front() * (1 - 1e-12))(0) == 0.0);
  CHECK(vc.Psd(edges.back())(0) == 0.0);  // bands are [lo, hi)
  CHECK(vc.Psd(edges.back() * (1 - 1e-12))(0) > 0.0);
  CHECK(vc.Psd(1000.0)(0) == 0.0);
  // Constant band RMS over growing bandwidth: the PSD steps down by 2^(1/3).
  CHECK(vc.band_psd()[0] / vc.band_psd()[1] == doctest::Approx(std::cbrt(2.0)).epsilon(1e-12));
  CHECK_FALSE(vc.WhiteLevel().has_value());
}

TEST_CASE("VC classes halve from one to the next (rel 2e-3: the sources print 3.12, 1.56, 0.78)") {
  const auto& table = VcCriteria();
  REQUIRE(table.size() == 7);
  CHECK(table.front().velocity_um_s == 50.0);
  for (std::size_t i = 1; i < table.size(); ++i) {
    CHECK(table[i].velocity_um_s / table[i - 1].velocity_um_s == doctest::Approx(0.5).epsilon(2e-3));
    const VcSpectrum upper(table[i - 1].vc_class), lower(table[i].vc_class);
    CHECK(lower.Psd(10.0)(0) / upper.Psd(10.0)(0) == doctest::Approx(0.25).epsilon(4e-3));
  }
}

TEST_CASE("a lowest band below 8 Hz needs the low-frequency extension, and bands stop at 80 Hz") {
  VcOptions options;
  options.lowest_band_hz = 0.5;
  const std::string message = InputErrorText([&] { VcSpectrum(VcClass::kD, options); });
  CHECK(message.find("VC-D") != std::string::npos);
  CHECK(message.find("0.5 Hz") != std::string::npos);
  CHECK(message.find("low_frequency_extension") != std::string::npos);
  options.low_frequency_extension = true;
  CHECK(VcSpectrum(VcClass::kD, options).bands().size() == 23);

  VcOptions high;
  high.highest_band_hz = 100.0;
  CHECK(InputErrorText([&] { VcSpectrum(VcClass::kD, high); }).find("100 Hz is above") != std::string::npos);
  VcOptions inverted;
  inverted.lowest_band_hz = 40.0;
  inverted.highest_band_hz = 20.0;
  CHECK_THROWS_AS(VcSpectrum(VcClass::kD, inverted), InputError);
}

TEST_CASE("VC class names parse in any case, round-trip, and an unknown name lists the allowed ones") {
  for (VcClass vc_class : kAllClasses) CHECK(ParseVcClass(ToString(vc_class)) == vc_class);
  CHECK(ParseVcClass("vc-d") == VcClass::kD);
  // The name table and the compiled VC table name every class alike.
  for (const VcCriterion& row : VcCriteria()) CHECK(ToString(row.vc_class) == row.name);
  CHECK(InputErrorText([] { ParseVcClass("VC-H"); })
            .find("'VC-H'; allowed: VC-A, VC-B, VC-C, VC-D, VC-E, VC-F, VC-G") != std::string::npos);
}

TEST_CASE("a VC spectrum describes class, level, bands and the extension, and declares its unit") {
  const std::string text = VcSpectrum(VcClass::kD, VcOptions::ThesisModified()).Describe();
  CHECK(text.find("VC-D") != std::string::npos);
  CHECK(text.find("6.25 um/s") != std::string::npos);
  CHECK(text.find("23 one-third-octave bands 0.5-80 Hz") != std::string::npos);
  CHECK(text.find("extended below 8 Hz") != std::string::npos);
  CHECK(std::string(VcSpectrum::kUnit) == "um/s");
}

// spectra/vc_curves.csv is what a user reads; vc_table.cpp is what runs.
TEST_CASE("spectra/vc_curves.csv matches the compiled VC table exactly and cites its sources") {
  const std::string path = std::string(DEB_SOURCE_DIR) + "/spectra/vc_curves.csv";
  std::ifstream in(path);
  REQUIRE_MESSAGE(in.good(), "cannot open " << path);
  std::string line, comments;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      comments += line + "\n";
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream cells_in(line);
    std::string cell;
    while (std::getline(cells_in, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  CHECK(comments.find("Proc. SPIE 1619") != std::string::npos);
  CHECK(comments.find("Proc. SPIE 5933") != std::string::npos);
  REQUIRE(rows.size() == VcCriteria().size() + 1);
  CHECK(rows[0] == std::vector<std::string>{"class", "velocity_um_s", "velocity_uin_s", "lowest_band_hz",
                                            "highest_band_hz", "source"});
  for (std::size_t i = 0; i < VcCriteria().size(); ++i) {
    const VcCriterion& row = VcCriteria()[i];
    const std::vector<std::string>& cells = rows[i + 1];
    REQUIRE(cells.size() == 6);
    CHECK(cells[0] == row.name);
    CHECK(std::stod(cells[1]) == row.velocity_um_s);  // exact: same decimal text
    CHECK(std::stod(cells[2]) == row.velocity_uin_s);
    CHECK(std::stod(cells[3]) == row.lowest_band_hz);
    CHECK(std::stod(cells[4]) == row.highest_band_hz);
    CHECK(cells[5] == row.source);
  }
}

}  // namespace
}  // namespace deb

namespace deb {
namespace {

TEST_CASE("a VC curve of a velocity: a class' velocity gives that class' curve; any other scales it") {
  for (const VcCriterion& row : VcCriteria()) {
    CAPTURE(row.name);
    const VcSpectrum by_class(row.vc_class, VcOptions::ThesisModified());
    const VcSpectrum by_velocity(row.velocity_um_s, VcOptions::ThesisModified());
    CHECK(by_velocity.vc_class() == row.vc_class);
    CHECK(by_velocity.Describe() == by_class.Describe());
    CHECK(by_velocity.band_psd() == by_class.band_psd());
  }
  const VcSpectrum ten(10.0, VcOptions{});
  CHECK(ten.Describe().rfind("VC curve (10 um/s RMS per band), 11 one-third-octave bands 8-80 Hz", 0) == 0);
  const VcSpectrum c(VcClass::kC);
  for (std::size_t i = 0; i < ten.bands().size(); ++i) {
    // Each band holds v^2: 100 (um/s)^2.
    CHECK(ten.band_psd()[i] * ten.bands()[i].BandwidthHz() == doctest::Approx(100.0).epsilon(1e-14));
    CHECK(ten.band_psd()[i] / c.band_psd()[i] == doctest::Approx(100.0 / (12.5 * 12.5)).epsilon(1e-14));
  }
  CHECK_THROWS_WITH_AS(VcSpectrum(10.0, VcOptions{2.0, 80.0, false, ThirdOctaveSeries::kBase2From1Hz}),
                       doctest::Contains("VC curve of 10 um/s: lowest band 2 Hz is below"), InputError);
}

}  // namespace
}  // namespace deb
