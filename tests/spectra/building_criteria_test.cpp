#include "deb/spectra/building_criteria.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "deb/spectra/vc_curve.h"
#include "tests/spectra/data_file.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

// Band RMS of a spectrum built exactly at `level` um/s in the bands 1-80 Hz.
std::vector<BandRms> FlatBands(double level, double lowest_hz = 1.0) {
  std::vector<double> rms;
  const std::vector<ThirdOctaveBand> bands =
      ThirdOctaveBandsBetween(lowest_hz, 80.0, ThirdOctaveSeries::kBase2From1Hz);
  const PsdTable t = BandRmsToPsd(bands, std::vector<double>(bands.size(), level));
  return ThirdOctaveBandRms(t.f_hz, t.psd, ThirdOctaveSeries::kBase2From1Hz, lowest_hz, 80.0);
}

std::size_t IndexOf(const Classification& c, const std::string& name) {
  for (std::size_t i = 0; i < c.criteria.size(); ++i)
    if (c.criteria[i].name == name) return i;
  FAIL("no criterion " << name);
  return 0;
}

TEST_CASE("a spectrum built exactly at each VC level classifies as that class, per band and overall") {
  for (const VcCriterion& row : VcCriteria()) {
    ClassifyOptions o;
    o.set = CriteriaSet::kVc;
    const Classification c = Classify(FlatBands(row.velocity_um_s), o);
    REQUIRE(c.overall.has_value());
    CHECK(c.criteria[*c.overall].name == row.name);
    for (const BandVerdict& v : c.bands) {
      CHECK(v.assessed == (v.band.band.centre_hz > 7.9));  // 8-80 Hz without the extension
      if (v.assessed) CHECK(c.criteria[*v.best].name == row.name);
    }
  }
}

TEST_CASE("1 % above VC-D in the 12.5 Hz band makes the floor VC-C, with that band limiting") {
  std::vector<BandRms> bands = FlatBands(6.25);
  std::size_t raised = 0;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    if (std::abs(bands[i].band.centre_hz - 12.7) < 0.1) {
      bands[i].rms *= 1.01;
      raised = i;
    }
  }
  const Classification c = Classify(bands);  // VC and ISO together
  CHECK(c.criteria[*c.overall].name == "VC-C");
  CHECK(*c.limiting_band == raised);
  CHECK(c.criteria[*c.bands[raised].best].name == "VC-C");
  CHECK(c.criteria[*c.bands[raised + 1].best].name == "VC-D");
  CHECK(c.Summary().find("VC-C; limiting band 12.7 Hz at 6.312 um/s RMS") != std::string::npos);
}

TEST_CASE("the ISO curves sit above VC-A: an office-level floor is ISO-office, and nothing is met above workshop") {
  const Classification office = Classify(FlatBands(400.0));
  CHECK(office.criteria[*office.overall].name == "ISO-office");
  ClassifyOptions iso;
  iso.set = CriteriaSet::kIso;
  const Classification loud = Classify(FlatBands(900.0), iso);
  CHECK_FALSE(loud.overall.has_value());
  CHECK(loud.limiting_band.has_value());
  CHECK(loud.Summary().find("none met") != std::string::npos);
  // Order: least stringent first, ISO then VC.
  const std::vector<BuildingCriterion> all = BuildingCriteria(CriteriaSet::kAll);
  for (std::size_t i = 1; i < all.size(); ++i) CHECK(all[i].velocity_um_s < all[i - 1].velocity_um_s);
}

TEST_CASE("bands below 8 Hz count only with the low-frequency extension, and only for the VC curves") {
  std::vector<BandRms> bands = FlatBands(6.25);
  bands.front().rms = 30.0;  // the 1 Hz band
  ClassifyOptions o;
  CHECK(Classify(bands, o).criteria[*Classify(bands, o).overall].name == "VC-D");
  o.low_frequency_extension = true;
  const Classification c = Classify(bands, o);
  CHECK(c.criteria[*c.overall].name == "VC-A");
  CHECK(*c.limiting_band == 0);
  CHECK(c.bands.front().best == IndexOf(c, "VC-A"));
  o.set = CriteriaSet::kIso;
  CHECK_FALSE(Classify(bands, o).bands.front().assessed);
}

TEST_CASE("criteria set names round-trip and an unknown one lists the allowed ones") {
  for (CriteriaSet s : {CriteriaSet::kVc, CriteriaSet::kIso, CriteriaSet::kAll}) CHECK(ParseCriteriaSet(ToString(s)) == s);
  CHECK(InputErrorText([] { ParseCriteriaSet("din"); }).find("allowed: vc, iso, all") != std::string::npos);
  ClassifyOptions o;
  o.tolerance = -1.0;
  CHECK_THROWS_AS(Classify({}, o), InputError);
}

TEST_CASE("spectra/iso_building_curves.csv matches the compiled ISO table exactly and cites its sources") {
  const std::string path = std::string(DEB_SOURCE_DIR) + "/spectra/iso_building_curves.csv";
  const test::DataFile file = test::ReadDataFile(path);
  REQUIRE_MESSAGE(file.opened, "cannot open " << path);
  const std::string& comments = file.comments;
  const std::vector<std::vector<std::string>>& rows = file.rows;
  CHECK(comments.find("Proc. SPIE 1619") != std::string::npos);
  CHECK(comments.find("Proc. SPIE 5933") != std::string::npos);
  CHECK(comments.find("could not be verified") != std::string::npos);
  REQUIRE(rows.size() == IsoBuildingCriteria().size() + 1);
  CHECK(rows[0] == std::vector<std::string>{"name", "velocity_um_s", "velocity_uin_s", "lowest_band_hz",
                                            "highest_band_hz", "iso_factor"});
  for (std::size_t i = 0; i < IsoBuildingCriteria().size(); ++i) {
    const IsoBuildingCriterion& row = IsoBuildingCriteria()[i];
    const std::vector<std::string>& cells = rows[i + 1];
    REQUIRE(cells.size() == 6);
    CHECK(cells[0] == row.name);
    CHECK(std::stod(cells[1]) == row.velocity_um_s);
    CHECK(std::stod(cells[2]) == row.velocity_uin_s);
    CHECK(std::stod(cells[3]) == row.lowest_band_hz);
    CHECK(std::stod(cells[4]) == row.highest_band_hz);
    CHECK(std::stod(cells[5]) == row.iso_factor);
    CHECK(row.velocity_um_s == 100.0 * row.iso_factor);  // base curve 100 um/s
  }
}

TEST_CASE("a displacement spectrum at VC-D, converted to velocity before integrating, classifies as VC-D") {
  // S_v = 6.25 um/s RMS in every band 1-80 Hz, given as displacement in nm:
  // S_x = S_v / (1e-6 (2 pi f)^2), taken back by the factor UnitConversion gives for nm -> um/s.
  const std::vector<ThirdOctaveBand> bands = ThirdOctaveBandsBetween(1.0, 80.0, ThirdOctaveSeries::kBase2From1Hz);
  const PsdTable v = BandRmsToPsd(bands, std::vector<double>(bands.size(), 6.25));
  const auto factor = [](double f) { return 1e-6 * std::pow(2.0 * M_PI * f, 2); };
  Eigen::MatrixXd x(static_cast<Eigen::Index>(v.f_hz.size()), 2);
  for (std::size_t k = 0; k < v.f_hz.size(); ++k)
    x.row(static_cast<Eigen::Index>(k)).setConstant(v.psd[k] / factor(v.f_hz[k]));
  x.col(1) *= 4.0;  // twice the RMS: VC-C is 12.5 um/s
  SpectrumClassOptions o;
  o.to_velocity_psd = factor;
  o.lowest_hz = 1.0;
  o.highest_hz = 80.0;
  const SpectrumClasses c = ClassifySpectrum(v.f_hz, x, SpectrumInterpolation::kLogLog, o);
  REQUIRE(c.bands.size() == 2);
  REQUIRE(c.classes.size() == 2);
  REQUIRE(c.bands[0].size() == bands.size());
  for (const BandRms& b : c.bands[0]) CHECK(b.rms == doctest::Approx(6.25).epsilon(1e-9));
  for (const BandRms& b : c.bands[1]) CHECK(b.rms == doctest::Approx(12.5).epsilon(1e-9));
  REQUIRE(c.classes[0].overall.has_value());
  CHECK(c.classes[0].criteria[*c.classes[0].overall].name == "VC-D");
  REQUIRE(c.classes[1].overall.has_value());
  CHECK(c.classes[1].criteria[*c.classes[1].overall].name == "VC-C");
  // Without classification: band RMS of the table as given (nm), no classes.
  o.classify_bands = false;
  o.to_velocity_psd = nullptr;
  const SpectrumClasses raw = ClassifySpectrum(v.f_hz, x, SpectrumInterpolation::kLogLog, o);
  CHECK(raw.classes.empty());
  CHECK(raw.bands[0].front().rms == doctest::Approx(ThirdOctaveBandRms(v.f_hz, std::vector<double>(x.col(0).data(),
                                                                       x.col(0).data() + x.rows()),
                                                                       ThirdOctaveSeries::kBase2From1Hz, 1.0, 80.0)
                                                        .front()
                                                        .rms));
}

}  // namespace
}  // namespace deb
