// A spectrum multiplied by a constant factor >= 0: S(f) = factor S_base(f).
// Conversions happen once, when a source is built, and this is how: a
// two-sided PSD becomes one-sided with factor 2 (docs/method.md, convention 2), a
// unit change (um/s -> m/s) is the squared unit ratio, and a gain g on an
// amplitude is g^2. Breakpoints and the white level pass through (scaled).
#pragma once

#include <memory>

#include "deb/spectra/spectrum.h"

namespace deb {

class ScaledSpectrum final : public Spectrum {
 public:
  // @throws InputError if factor is negative or not finite. A null base is a
  //   bug (DEB_DEMAND).
  ScaledSpectrum(std::shared_ptr<const Spectrum> base, double factor);

  const Spectrum& base() const { return *base_; }
  double factor() const { return factor_; }

  int channels() const override { return base_->channels(); }
  Eigen::MatrixXcd Csd(double f_hz) const override { return factor_ * base_->Csd(f_hz); }
  Eigen::VectorXd Psd(double f_hz) const override { return factor_ * base_->Psd(f_hz); }
  bool IsDiagonal() const override { return base_->IsDiagonal(); }
  std::vector<double> BreakpointsHz() const override { return base_->BreakpointsHz(); }
  std::optional<FrequencyInterval> DefinedRangeHz() const override { return base_->DefinedRangeHz(); }
  std::optional<Eigen::MatrixXd> WhiteLevel() const override;
  // Amplitudes times sqrt(factor).
  std::vector<SpectralLine> Lines() const override;
  std::string Describe() const override;

 private:
  std::shared_ptr<const Spectrum> base_;
  double factor_;
};

}  // namespace deb
