#include "deb/spectra/peterson_noise_model.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "tests/spectra/data_file.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

double Db(double psd) { return 10.0 * std::log10(psd); }

TEST_CASE("the models evaluate A + B log10(P) dB: NLNM -166.4 dB and NHNM -116.85 dB at 1 s (abs 1e-10 dB)") {
  CHECK(std::abs(Db(PetersonAccelerationPsd(PetersonModel::kLow, 1.0)) - -166.40) < 1e-10);
  CHECK(std::abs(Db(PetersonAccelerationPsd(PetersonModel::kHigh, 1.0)) - -116.85) < 1e-10);
  // 10 s (the NLNM's 6-10 s segment ends there): -97.26 - 66.49 = -163.75 dB.
  CHECK(std::abs(Db(PetersonAccelerationPsd(PetersonModel::kLow, 0.1)) - -163.75) < 1e-2);
  CHECK(PetersonAccelerationPsd(PetersonModel::kLow, 0.2) < PetersonAccelerationPsd(PetersonModel::kHigh, 0.2));
}

TEST_CASE("neighbouring segments meet within 0.02 dB, a check of the transcribed coefficients") {
  for (PetersonModel m : {PetersonModel::kLow, PetersonModel::kHigh}) {
    const std::vector<PetersonSegment>& s = PetersonSegments(m);
    CHECK(s.front().period_from_s == 0.1);
    CHECK(s.back().period_to_s == 100000.0);
    for (std::size_t i = 1; i < s.size(); ++i) {
      const double p = s[i].period_from_s;
      CHECK(p == s[i - 1].period_to_s);
      const double left = s[i - 1].a_db + s[i - 1].b_db * std::log10(p);
      const double right = s[i].a_db + s[i].b_db * std::log10(p);
      CHECK(std::abs(left - right) < 0.02);
    }
  }
  CHECK(PetersonSegments(PetersonModel::kLow).size() == 21);
  CHECK(PetersonSegments(PetersonModel::kHigh).size() == 11);
}

TEST_CASE("outside 1e-5-10 Hz the model is an error unless an extrapolation is chosen") {
  CHECK(InputErrorText([] { PetersonAccelerationPsd(PetersonModel::kLow, 20.0); }).find("outside the model's range") !=
        std::string::npos);
  const PetersonSpectrum zero(PetersonModel::kHigh, Extrapolation::kZero);
  CHECK(zero.Psd(20.0)(0) == 0.0);
  const PetersonSpectrum hold(PetersonModel::kHigh, Extrapolation::kHold);
  CHECK(hold.Psd(20.0)(0) == PetersonAccelerationPsd(PetersonModel::kHigh, 10.0));
  CHECK_THROWS_AS(PetersonSpectrum(PetersonModel::kLow).Psd(20.0), InputError);
  const std::vector<double> breaks = PetersonSpectrum(PetersonModel::kLow).BreakpointsHz();
  CHECK(breaks.size() == 22);
  CHECK(breaks.front() == doctest::Approx(1e-5));
  CHECK(breaks.back() == doctest::Approx(10.0));
  CHECK(ParsePetersonModel("NLNM") == PetersonModel::kLow);
  CHECK(InputErrorText([] { ParsePetersonModel("nmnm"); }).find("allowed: nlnm, nhnm") != std::string::npos);
}

TEST_CASE("spectra/peterson_1993_noise_models.csv matches the compiled tables exactly and cites OFR 93-322") {
  const std::string path = std::string(DEB_SOURCE_DIR) + "/spectra/peterson_1993_noise_models.csv";
  const test::DataFile file = test::ReadDataFile(path);
  REQUIRE_MESSAGE(file.opened, "cannot open " << path);
  const std::string& comments = file.comments;
  const std::vector<std::vector<std::string>>& rows = file.rows;
  CHECK(comments.find("Open-File Report 93-322") != std::string::npos);
  REQUIRE(rows.size() == 1 + 21 + 11);
  CHECK(rows[0] == std::vector<std::string>{"model", "period_from_s", "period_to_s", "a_db", "b_db"});
  std::size_t r = 1;
  for (PetersonModel m : {PetersonModel::kLow, PetersonModel::kHigh}) {
    for (const PetersonSegment& s : PetersonSegments(m)) {
      const std::vector<std::string>& cells = rows[r++];
      REQUIRE(cells.size() == 5);
      CHECK(cells[0] == (m == PetersonModel::kLow ? "NLNM" : "NHNM"));
      CHECK(std::stod(cells[1]) == s.period_from_s);
      CHECK(std::stod(cells[2]) == s.period_to_s);
      CHECK(std::stod(cells[3]) == s.a_db);
      CHECK(std::stod(cells[4]) == s.b_db);
    }
  }
}

}  // namespace
}  // namespace deb

namespace deb {

TEST_CASE("a model is tabulated from 1e-5 to 10 Hz, evenly in log f, at the points per decade asked for") {
  const std::vector<double> f = PetersonFrequencies(2.0);
  REQUIRE(f.size() == 13);  // six decades, 2 per decade, both ends
  CHECK(f.front() == PetersonSpectrum::kMinHz);
  CHECK(f.back() == PetersonSpectrum::kMaxHz);
  CHECK(f[2] == doctest::Approx(1e-4).epsilon(1e-12));
  CHECK_THROWS_AS(PetersonFrequencies(0.5), InputError);
  CHECK_THROWS_AS(PetersonFrequencies(2e5), InputError);
}

}  // namespace deb
