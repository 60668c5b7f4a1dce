#include "deb/spectra/band_rms.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

struct Samples {
  std::vector<double> f_hz, psd;
  std::vector<double> edges_hz;  // kBins: the bins' edges (measured_spectrum.h)
  double lo_hz = 0.0, hi_hz = 0.0;  // the range the data cover
};

// The samples above 0 Hz, validated.
Samples Positive(const std::vector<double>& f_hz, const std::vector<double>& psd,
                 SpectrumInterpolation interpolation) {
  if (f_hz.size() != psd.size())
    throw InputError("band RMS: " + std::to_string(f_hz.size()) + " frequencies but " + std::to_string(psd.size()) +
                     " PSD values");
  Samples s;
  for (std::size_t i = 0; i < f_hz.size(); ++i) {
    if (!std::isfinite(f_hz[i]) || (i > 0 && !(f_hz[i] > f_hz[i - 1])))
      throw InputError("band RMS: frequency[" + std::to_string(i) + "] = " + NumberText(f_hz[i]) +
                       " Hz; frequencies must be finite and strictly increasing");
    if (!std::isfinite(psd[i]) || psd[i] < 0.0)
      throw InputError("band RMS: PSD at " + NumberText(f_hz[i]) + " Hz is " + NumberText(psd[i]) +
                       "; it must be finite and >= 0");
    if (f_hz[i] <= 0.0) continue;
    s.f_hz.push_back(f_hz[i]);
    s.psd.push_back(psd[i]);
  }
  if (s.f_hz.size() < 2)
    throw InputError("band RMS: " + std::to_string(s.f_hz.size()) + " samples above 0 Hz; at least 2 are needed");
  s.lo_hz = s.f_hz.front();
  s.hi_hz = s.f_hz.back();
  if (interpolation == SpectrumInterpolation::kBins) {
    MeasuredSpectrumOptions o;
    o.interpolation = interpolation;
    s.edges_hz = MeasuredSpectrum(s.f_hz, Eigen::Map<const Eigen::MatrixXd>(s.psd.data(), s.psd.size(), 1), o)
                     .bin_edges_hz();
    s.lo_hz = s.edges_hz.front();
    s.hi_hz = s.edges_hz.back();
  }
  return s;
}

BandRms Integrate(const Samples& s, const ThirdOctaveBand& band) {
  BandRms r;
  r.band = band;
  if (s.edges_hz.empty()) {
    r.rms = std::sqrt(IntegralBetween(s.f_hz, s.psd, band.lo_hz, band.hi_hz));
  } else {
    double variance = 0.0;
    for (std::size_t i = 0; i < s.psd.size(); ++i) {
      const double width = std::min(s.edges_hz[i + 1], band.hi_hz) - std::max(s.edges_hz[i], band.lo_hz);
      if (width > 0.0) variance += s.psd[i] * width;
    }
    r.rms = std::sqrt(variance);
  }
  const auto lo = std::lower_bound(s.f_hz.begin(), s.f_hz.end(), band.lo_hz);
  const auto hi = std::lower_bound(s.f_hz.begin(), s.f_hz.end(), band.hi_hz);
  r.points = static_cast<int>(hi - lo);
  return r;
}

}  // namespace

std::vector<BandRms> ThirdOctaveBandRms(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                        ThirdOctaveSeries series, double lowest_nominal_hz,
                                        double highest_nominal_hz, SpectrumInterpolation interpolation) {
  const Samples s = Positive(f_hz, psd, interpolation);
  std::vector<BandRms> result;
  for (const ThirdOctaveBand& band : ThirdOctaveBandsBetween(lowest_nominal_hz, highest_nominal_hz, series)) {
    if (band.lo_hz < s.lo_hz || band.hi_hz > s.hi_hz)
      throw InputError("band RMS: the one-third-octave band at " + NumberText(band.centre_hz) + " Hz (" +
                       NumberText(band.lo_hz) + "-" + NumberText(band.hi_hz) + " Hz) reaches outside the data, " +
                       NumberText(s.lo_hz) + "-" + NumberText(s.hi_hz) + " Hz");
    result.push_back(Integrate(s, band));
  }
  return result;
}

std::vector<BandRms> ThirdOctaveBandRms(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                        ThirdOctaveSeries series, SpectrumInterpolation interpolation) {
  const Samples s = Positive(f_hz, psd, interpolation);
  // First band whose lower edge is at or above the start of the data.
  int k = ThirdOctaveBandAt(0, series).index;
  while (ThirdOctaveBandAt(k, series).lo_hz < s.lo_hz) ++k;
  while (k > -1000 && ThirdOctaveBandAt(k - 1, series).lo_hz >= s.lo_hz) --k;
  std::vector<BandRms> result;
  for (; ThirdOctaveBandAt(k, series).hi_hz <= s.hi_hz; ++k) result.push_back(Integrate(s, ThirdOctaveBandAt(k, series)));
  if (result.empty())
    throw InputError("band RMS: no one-third-octave band fits inside the data, " + NumberText(s.lo_hz) +
                     "-" + NumberText(s.hi_hz) + " Hz");
  return result;
}

int CoarseBandCount(const std::vector<BandRms>& bands) {
  return static_cast<int>(
      std::count_if(bands.begin(), bands.end(), [](const BandRms& b) { return b.points < kFewLines; }));
}

PsdTable BandRmsToPsd(const std::vector<ThirdOctaveBand>& bands, const std::vector<double>& rms) {
  if (bands.size() != rms.size() || bands.empty())
    throw InputError("band RMS to PSD: " + std::to_string(bands.size()) + " bands but " + std::to_string(rms.size()) +
                     " RMS values");
  PsdTable t;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    if (!std::isfinite(rms[i]) || rms[i] < 0.0)
      throw InputError("band RMS to PSD: RMS " + NumberText(rms[i]) + " in the band at " +
                       NumberText(bands[i].centre_hz) + " Hz must be finite and >= 0");
    if (i > 0 && bands[i].index != bands[i - 1].index + 1)
      throw InputError("band RMS to PSD: the band at " + NumberText(bands[i].centre_hz) +
                       " Hz does not follow the one at " + NumberText(bands[i - 1].centre_hz) +
                       " Hz; bands must be contiguous and increasing");
    const double level = rms[i] * rms[i] / bands[i].BandwidthHz();
    t.f_hz.push_back(bands[i].lo_hz);
    t.psd.push_back(level);
    // The last band ends on its edge, so the table covers every band it holds.
    t.f_hz.push_back(i + 1 == bands.size() ? bands[i].hi_hz : bands[i].hi_hz * (1.0 - 1e-9));
    t.psd.push_back(level);
  }
  return t;
}

}  // namespace deb
