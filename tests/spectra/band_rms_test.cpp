#include "deb/spectra/band_rms.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "deb/spectra/vc_curve.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

std::vector<double> LinearGrid(double lo, double hi, int n) {
  std::vector<double> f;
  for (int i = 0; i < n; ++i) f.push_back(lo + (hi - lo) * i / (n - 1));
  return f;
}

TEST_CASE("a white PSD S0 has band RMS^2 = S0 x bandwidth in every band (rel 1e-12)") {
  const std::vector<double> f = LinearGrid(0.0, 200.0, 4001);  // a Welch-like grid from 0 Hz
  const std::vector<double> psd(f.size(), 3e-4);
  for (auto series : {ThirdOctaveSeries::kBase2From1Hz, ThirdOctaveSeries::kIecBase10}) {
    const std::vector<BandRms> bands = ThirdOctaveBandRms(f, psd, series, 1.0, 100.0);
    REQUIRE(bands.size() == 21);
    for (const BandRms& b : bands)
      CHECK(b.rms * b.rms == doctest::Approx(3e-4 * b.band.BandwidthHz()).epsilon(1e-12));
    CHECK(bands.front().points == 5);  // 1 Hz band: 0.891-1.122 Hz holds 0.9, 0.95, 1, 1.05, 1.1
  }
}

TEST_CASE("a VC-D spectrum sampled on both sides of every band edge has 6.25 um/s in every band (rel 1e-9)") {
  const VcSpectrum vc(VcClass::kD, VcOptions::ThesisModified());
  std::vector<double> f, psd;
  for (const ThirdOctaveBand& band : vc.bands()) {
    for (double x : {band.lo_hz, band.centre_hz, band.hi_hz * (1.0 - 1e-12)}) {
      f.push_back(x);
      psd.push_back(vc.Psd(x)(0));
    }
  }
  const std::vector<BandRms> bands = ThirdOctaveBandRms(f, psd, ThirdOctaveSeries::kBase2From1Hz, 0.5, 64.0);
  REQUIRE(bands.size() == 22);  // the 80 Hz band's upper edge is not sampled
  for (const BandRms& b : bands) CHECK(b.rms == doctest::Approx(6.25).epsilon(1e-9));
}

TEST_CASE("band RMS to PSD and back returns the band RMS values (rel 1e-8)") {
  const std::vector<ThirdOctaveBand> bands = ThirdOctaveBandsBetween(1.0, 10.0, ThirdOctaveSeries::kIecBase10);
  std::vector<double> rms;
  for (std::size_t i = 0; i < bands.size(); ++i) rms.push_back(1.0 + 0.5 * static_cast<double>(i % 3));
  const PsdTable t = BandRmsToPsd(bands, rms);
  REQUIRE(t.f_hz.size() == 2 * bands.size());
  const std::vector<BandRms> back = ThirdOctaveBandRms(t.f_hz, t.psd, ThirdOctaveSeries::kIecBase10, 1.0, 8.0);
  for (std::size_t i = 0; i < back.size(); ++i) CHECK(back[i].rms == doctest::Approx(rms[i]).epsilon(1e-8));
  CHECK_THROWS_AS(BandRmsToPsd({bands[0], bands[2]}, {1.0, 1.0}), InputError);
  CHECK_THROWS_AS(BandRmsToPsd({bands[0]}, {-1.0}), InputError);
}

TEST_CASE("without a range, every band the data cover entirely is analysed") {
  const std::vector<double> f = LinearGrid(0.0, 100.0, 1001);  // first sample above 0: 0.1 Hz
  const std::vector<BandRms> bands = ThirdOctaveBandRms(f, std::vector<double>(f.size(), 1.0),
                                                        ThirdOctaveSeries::kBase2From1Hz);
  CHECK(bands.front().band.lo_hz >= 0.1);
  CHECK(ThirdOctaveBandAt(bands.front().band.index - 1, ThirdOctaveSeries::kBase2From1Hz).lo_hz < 0.1);
  CHECK(bands.back().band.hi_hz <= 100.0);
  CHECK(ThirdOctaveBandAt(bands.back().band.index + 1, ThirdOctaveSeries::kBase2From1Hz).hi_hz > 100.0);
}

TEST_CASE("a band outside the data, a negative PSD and mismatched sizes are input errors") {
  const std::vector<double> f = LinearGrid(1.0, 50.0, 100);
  const std::vector<double> psd(f.size(), 1.0);
  const std::string message =
      InputErrorText([&] { ThirdOctaveBandRms(f, psd, ThirdOctaveSeries::kBase2From1Hz, 1.0, 80.0); });
  CHECK(message.find("band at 1 Hz (0.8908987") != std::string::npos);
  CHECK(message.find("Hz) reaches outside the data, 1-50 Hz") != std::string::npos);
  std::vector<double> negative = psd;
  negative[3] = -1.0;
  CHECK(InputErrorText([&] { ThirdOctaveBandRms(f, negative, ThirdOctaveSeries::kBase2From1Hz); })
            .find("must be finite and >= 0") != std::string::npos);
  CHECK_THROWS_AS(ThirdOctaveBandRms(f, {1.0}, ThirdOctaveSeries::kBase2From1Hz), InputError);
}


TEST_CASE("the bins of a spectral estimate give each band the part of each bin inside it (exact)") {
  // Bins 1 Hz apart at 1..100 Hz, each holding 1 except 3 bins of a tone at
  // 39-41 Hz: the 40 Hz band (35.92-45.25 Hz) holds the 9 whole bins 37..45
  // (edges 36.5..45.5 minus the parts outside) plus the tone.
  const std::vector<double> f = LinearGrid(1.0, 100.0, 100);
  std::vector<double> psd(f.size(), 1.0);
  psd[38] = psd[40] = 2.0;  // 39 and 41 Hz
  psd[39] = 5.0;            // 40 Hz
  const std::vector<BandRms> bands =
      ThirdOctaveBandRms(f, psd, ThirdOctaveSeries::kBase2From1Hz, 40.0, 40.0, SpectrumInterpolation::kBins);
  REQUIRE(bands.size() == 1);
  const ThirdOctaveBand& b = bands[0].band;
  const double expected = (b.hi_hz - b.lo_hz) * 1.0 + (1.0 + 4.0 + 1.0);  // flat part + the tone above it
  CHECK(bands[0].rms * bands[0].rms == doctest::Approx(expected).epsilon(1e-13));
  // The bins cover half a spacing beyond the first and last point.
  CHECK_NOTHROW(ThirdOctaveBandRms(f, psd, ThirdOctaveSeries::kBase2From1Hz, 0.63, 80.0, SpectrumInterpolation::kBins));
  CHECK_THROWS_AS(ThirdOctaveBandRms(f, psd, ThirdOctaveSeries::kBase2From1Hz, 0.63, 80.0), InputError);
}

TEST_CASE("a band RMS table as PSD covers its last band up to the band's edge") {
  const std::vector<ThirdOctaveBand> bands = ThirdOctaveBandsBetween(8.0, 80.0, ThirdOctaveSeries::kBase2From1Hz);
  const PsdTable t = BandRmsToPsd(bands, std::vector<double>(bands.size(), 6.25));
  CHECK(t.f_hz.back() == bands.back().hi_hz);
  const std::vector<BandRms> back = ThirdOctaveBandRms(t.f_hz, t.psd, ThirdOctaveSeries::kBase2From1Hz, 8.0, 80.0);
  CHECK(back.size() == 11);
  CHECK(back.back().rms == doctest::Approx(6.25).epsilon(1e-8));
}

}  // namespace
}  // namespace deb

namespace deb {

TEST_CASE("bands holding fewer than kFewLines spectral lines are counted as coarse") {
  const ThirdOctaveBand band{};
  const std::vector<BandRms> bands = {{band, 1.0, 0}, {band, 1.0, kFewLines - 1}, {band, 1.0, kFewLines},
                                      {band, 1.0, 40}};
  CHECK(CoarseBandCount(bands) == 2);
  CHECK(CoarseBandCount({}) == 0);
}

}  // namespace deb
