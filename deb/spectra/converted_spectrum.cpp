#include "deb/spectra/converted_spectrum.h"

#include <cmath>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"

namespace deb {

ConvertedSpectrum::ConvertedSpectrum(std::shared_ptr<const Spectrum> base, double scale, int derivative_order,
                                     std::string unit)
    : base_(std::move(base)), scale_(scale), derivative_order_(derivative_order), unit_(std::move(unit)) {
  DEB_DEMAND(base_ != nullptr);
  if (!std::isfinite(scale_) || scale_ <= 0.0)
    throw InputError("converted spectrum: scale " + NumberText(scale_) + " is invalid; it must be finite and > 0 (" +
                     base_->Describe() + ")");
  if (derivative_order_ < -2 || derivative_order_ > 2)
    throw InputError("converted spectrum: derivative order " + std::to_string(derivative_order_) +
                     " is invalid; units relate by at most two time derivatives or integrals");
}

double ConvertedSpectrum::Factor(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz) && f_hz > 0.0);
  const double omega2 = (kTwoPi * f_hz) * (kTwoPi * f_hz);
  double factor = scale_ * scale_;
  for (int k = 0; k < derivative_order_; ++k) factor *= omega2;
  for (int k = 0; k > derivative_order_; --k) factor /= omega2;
  return factor;
}

std::vector<SpectralLine> ConvertedSpectrum::Lines() const {
  std::vector<SpectralLine> lines = base_->Lines();
  for (SpectralLine& l : lines) {
    std::complex<double> factor = scale_;
    const std::complex<double> j_omega(0.0, 2.0 * kPi * l.f_hz);
    for (int k = 0; k < derivative_order_; ++k) factor *= j_omega;
    for (int k = 0; k > derivative_order_; --k) factor /= j_omega;
    l.rms *= factor;
  }
  return lines;
}

std::optional<Eigen::MatrixXd> ConvertedSpectrum::WhiteLevel() const {
  if (derivative_order_ != 0) return std::nullopt;
  auto level = base_->WhiteLevel();
  if (!level) return std::nullopt;
  return Eigen::MatrixXd(scale_ * scale_ * *level);
}

std::string ConvertedSpectrum::Describe() const {
  std::string how;
  switch (derivative_order_) {
    case -2: how = ", integrated twice in time"; break;
    case -1: how = ", integrated once in time"; break;
    case 1: how = ", differentiated once in time"; break;
    case 2: how = ", differentiated twice in time"; break;
    default: break;
  }
  return "[" + base_->Describe() + "] in " + (unit_.empty() ? std::string("another unit") : unit_) + " (scale " +
         NumberText(scale_) + how + ")";
}

}  // namespace deb
