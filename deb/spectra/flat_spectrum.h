// Single-channel flat (white) noise: sensor noise, electronics noise, the
// simplest disturbance model. Optionally band-limited to [lo_hz, hi_hz], which
// models noise that is flat only up to a roll-off the budget does not resolve.
// Without band limits the level is exposed through WhiteLevel(), which lets the
// budget use the exact Lyapunov variance (docs/method.md, convention 3).
#pragma once

#include <limits>

#include "deb/spectra/spectrum.h"

namespace deb {

class FlatSpectrum final : public Spectrum {
 public:
  // White noise: S(f) = level_psd for all f > 0. level_psd is one-sided, in
  // unit^2/Hz, finite and >= 0.
  // @throws InputError if level_psd is negative or not finite.
  explicit FlatSpectrum(double level_psd);

  // Band-limited: S(f) = level_psd for lo_hz <= f <= hi_hz, 0 elsewhere.
  // hi_hz may be +infinity (no upper limit); lo_hz = 0 means no lower limit.
  // @throws InputError if level_psd < 0 or not finite, lo_hz < 0 or not
  //   finite, or hi_hz <= lo_hz.
  FlatSpectrum(double level_psd, double lo_hz, double hi_hz);

  double level_psd() const { return level_psd_; }
  double lo_hz() const { return lo_hz_; }
  double hi_hz() const { return hi_hz_; }
  bool IsBandLimited() const;

  int channels() const override { return 1; }
  Eigen::MatrixXcd Csd(double f_hz) const override;
  Eigen::VectorXd Psd(double f_hz) const override;
  bool IsDiagonal() const override { return true; }
  // The band limits that are finite and > 0.
  std::vector<double> BreakpointsHz() const override;
  // 1x1 level, only when the spectrum has no band limits.
  std::optional<Eigen::MatrixXd> WhiteLevel() const override;
  std::string Describe() const override;

 private:
  double PsdAt(double f_hz) const;

  double level_psd_;
  double lo_hz_ = 0.0;
  double hi_hz_ = std::numeric_limits<double>::infinity();
};

}  // namespace deb
