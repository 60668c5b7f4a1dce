// A spectrum expressed in another unit of the same signal, possibly a time
// derivative or integral of it: a floor acceleration PSD read as velocity,
// a reference model tabulated in (m/s^2)^2/Hz used in (um/s)^2/Hz. If
//   y(t) = scale (d/dt)^n x(t),  then  S_y(f) = scale^2 (2 pi f)^(2n) S_x(f)
// (docs/method.md, convention 4), for the whole matrix alike. deb/units finds scale
// and n for two unit strings (UnitConversion); this class only applies them,
// so deb/spectra stays free of UDUNITS. Use ScaledSpectrum when n = 0 is known.
#pragma once

#include <memory>
#include <string>

#include "deb/spectra/spectrum.h"

namespace deb {

class ConvertedSpectrum final : public Spectrum {
 public:
  // `unit`: the new unit, for Describe() only.
  // @throws InputError if scale is not finite and > 0 or |derivative_order|
  //   > 2. A null base is a bug (DEB_DEMAND).
  ConvertedSpectrum(std::shared_ptr<const Spectrum> base, double scale, int derivative_order, std::string unit);

  const Spectrum& base() const { return *base_; }
  double scale() const { return scale_; }
  int derivative_order() const { return derivative_order_; }

  // scale^2 (2 pi f)^(2n) at f_hz > 0.
  double Factor(double f_hz) const;

  int channels() const override { return base_->channels(); }
  Eigen::MatrixXcd Csd(double f_hz) const override { return Factor(f_hz) * base_->Csd(f_hz); }
  Eigen::VectorXd Psd(double f_hz) const override { return Factor(f_hz) * base_->Psd(f_hz); }
  bool IsDiagonal() const override { return base_->IsDiagonal(); }
  // The base's: a power of f moves no corner.
  std::vector<double> BreakpointsHz() const override { return base_->BreakpointsHz(); }
  std::optional<FrequencyInterval> DefinedRangeHz() const override { return base_->DefinedRangeHz(); }
  // The base's level times scale^2 when n = 0; otherwise none (f^(2n) is not white).
  std::optional<Eigen::MatrixXd> WhiteLevel() const override;
  // Amplitudes times scale (j 2 pi f)^n at each line's frequency.
  std::vector<SpectralLine> Lines() const override;
  std::string Describe() const override;

 private:
  std::shared_ptr<const Spectrum> base_;
  double scale_;
  int derivative_order_;
  std::string unit_;
};

}  // namespace deb
