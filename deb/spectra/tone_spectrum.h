// A tonal source: sinusoids at given frequencies (mains at 50 Hz and its
// harmonics, a pump, a fan), no random part. Its density is zero at every
// frequency; the engine propagates each line exactly, as |H(f0) a|^2 with a
// the complex RMS amplitudes on the channels (docs/method.md, convention 9),
// so no grid smears or misses a line, and the cumulative spectrum steps at f0.
#pragma once

#include <vector>

#include "deb/spectra/spectrum.h"

namespace deb {

class ToneSpectrum final : public Spectrum {
 public:
  // @throws InputError for no lines, more than limits::kMaxTones, a frequency
  //   not finite and > 0, two lines at one frequency, an amplitude vector of
  //   another size than `channels`, or an amplitude that is not finite.
  ToneSpectrum(std::vector<SpectralLine> lines, int channels);

  int channels() const override { return channels_; }
  Eigen::MatrixXcd Csd(double) const override { return Eigen::MatrixXcd::Zero(channels_, channels_); }
  Eigen::VectorXd Psd(double) const override { return Eigen::VectorXd::Zero(channels_); }
  bool IsDiagonal() const override { return true; }
  // The line frequencies: the automatic grid reaches them.
  std::vector<double> BreakpointsHz() const override;
  std::vector<SpectralLine> Lines() const override { return lines_; }
  std::string Describe() const override;

 private:
  std::vector<SpectralLine> lines_;  // by frequency
  int channels_;
};

}  // namespace deb
