#include "deb/spectra/band_rms.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/spectra/number_text.h"

namespace deb {
namespace {

struct Samples {
  std::vector<double> f_hz, psd;
};

// The samples above 0 Hz, validated.
Samples Positive(const std::vector<double>& f_hz, const std::vector<double>& psd) {
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
  return s;
}

BandRms Integrate(const Samples& s, const ThirdOctaveBand& band) {
  BandRms r;
  r.band = band;
  r.rms = std::sqrt(IntegralBetween(s.f_hz, s.psd, band.lo_hz, band.hi_hz));
  const auto lo = std::lower_bound(s.f_hz.begin(), s.f_hz.end(), band.lo_hz);
  const auto hi = std::lower_bound(s.f_hz.begin(), s.f_hz.end(), band.hi_hz);
  r.points = static_cast<int>(hi - lo);
  return r;
}

}  // namespace

std::vector<BandRms> ThirdOctaveBandRms(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                        ThirdOctaveSeries series, double lowest_nominal_hz,
                                        double highest_nominal_hz) {
  const Samples s = Positive(f_hz, psd);
  std::vector<BandRms> result;
  for (const ThirdOctaveBand& band : ThirdOctaveBandsBetween(lowest_nominal_hz, highest_nominal_hz, series)) {
    if (band.lo_hz < s.f_hz.front() || band.hi_hz > s.f_hz.back())
      throw InputError("band RMS: the one-third-octave band at " + NumberText(band.centre_hz) + " Hz (" +
                       NumberText(band.lo_hz) + "-" + NumberText(band.hi_hz) + " Hz) reaches outside the data, " +
                       NumberText(s.f_hz.front()) + "-" + NumberText(s.f_hz.back()) + " Hz");
    result.push_back(Integrate(s, band));
  }
  return result;
}

std::vector<BandRms> ThirdOctaveBandRms(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                        ThirdOctaveSeries series) {
  const Samples s = Positive(f_hz, psd);
  // First band whose lower edge is at or above the first sample.
  int k = ThirdOctaveBandAt(0, series).index;
  while (ThirdOctaveBandAt(k, series).lo_hz < s.f_hz.front()) ++k;
  while (k > -1000 && ThirdOctaveBandAt(k - 1, series).lo_hz >= s.f_hz.front()) --k;
  std::vector<BandRms> result;
  for (; ThirdOctaveBandAt(k, series).hi_hz <= s.f_hz.back(); ++k) result.push_back(Integrate(s, ThirdOctaveBandAt(k, series)));
  if (result.empty())
    throw InputError("band RMS: no one-third-octave band fits inside the data, " + NumberText(s.f_hz.front()) +
                     "-" + NumberText(s.f_hz.back()) + " Hz");
  return result;
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
    t.f_hz.push_back(bands[i].hi_hz * (1.0 - 1e-9));
    t.psd.push_back(level);
  }
  return t;
}

}  // namespace deb
