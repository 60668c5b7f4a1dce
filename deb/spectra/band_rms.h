// One-third-octave band RMS of a sampled PSD, the form in which vibration
// criteria are stated (docs/method.md, convention 5), and the way back: a band-RMS
// spectrum as a PSD that is constant inside each band.
//
// RMS_i = sqrt( integral of S over [f_c G^(-1/6), f_c G^(1/6)] ), integrated
// with deb's power-law rule between the samples (core/integrate.h), the band
// edges interpolated on the same law; or, for the bins of a spectral estimate
// (SpectrumInterpolation::kBins, measured_spectrum.h), as the sum of each
// bin's PSD times the part of its width inside the band, which keeps the
// estimate's variance exactly (a tone a few bins wide is not cut down). A band is analysed only when the data
// cover it entirely; `points` says how many samples fall inside it, and a
// band with fewer than kFewLines is resolved too coarsely to trust (raise the
// frequency resolution, i.e. the segment length, to fix it).
#pragma once

#include <vector>

#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/third_octave.h"

namespace deb {

struct BandRms {
  ThirdOctaveBand band;
  double rms = 0.0;  // in the unit of the signal whose PSD was integrated
  int points = 0;    // samples with lo_hz <= f < hi_hz
};

// A band holding fewer spectral lines (samples) than this is resolved too
// coarsely to trust.
inline constexpr int kFewLines = 5;

// How many of `bands` hold fewer than kFewLines samples.
int CoarseBandCount(const std::vector<BandRms>& bands);

// Bands named lowest_nominal_hz .. highest_nominal_hz. Samples at f <= 0
// (a 0 Hz bin) are ignored.
// @throws InputError if f_hz and psd differ in size, f is not strictly
//   increasing, a PSD value is negative or not finite, fewer than 2 samples
//   are above 0 Hz, or a band reaches outside the data (naming the band, its
//   edges and the data range).
std::vector<BandRms> ThirdOctaveBandRms(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                        ThirdOctaveSeries series, double lowest_nominal_hz,
                                        double highest_nominal_hz,
                                        SpectrumInterpolation interpolation = SpectrumInterpolation::kLogLog);

// Every band the data cover entirely.
// @throws InputError as above, or if no band fits inside the data range.
std::vector<BandRms> ThirdOctaveBandRms(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                        ThirdOctaveSeries series,
                                        SpectrumInterpolation interpolation = SpectrumInterpolation::kLogLog);

// A PSD table that holds rms_i^2 / bandwidth_i across band i, so that each
// band integral returns rms_i^2 (as a VC curve). Bands must be contiguous
// and increasing. The table has two points per band: lo_hz and
// hi_hz (1 - 1e-9) (the last band: hi_hz, so the table covers it); the step between bands is taken across that last 1e-9 of
// the band, which changes a band integral by about 5e-9 times the ratio of
// neighbouring levels (negligible for any real spectrum).
// @throws InputError if sizes differ, an RMS is negative or not finite, or
//   the bands are not contiguous.
struct PsdTable {
  std::vector<double> f_hz;
  std::vector<double> psd;
};
PsdTable BandRmsToPsd(const std::vector<ThirdOctaveBand>& bands, const std::vector<double>& rms);

}  // namespace deb
