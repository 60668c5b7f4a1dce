#include "deb/spectra/scaled_spectrum.h"

#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {

ScaledSpectrum::ScaledSpectrum(std::shared_ptr<const Spectrum> base, double factor)
    : base_(std::move(base)), factor_(factor) {
  DEB_DEMAND(base_ != nullptr);
  if (!std::isfinite(factor) || factor < 0.0) {
    throw InputError("scaled spectrum: factor " + NumberText(factor) +
                     " is invalid; a PSD scale factor must be finite and >= 0 (" + base_->Describe() + ")");
  }
}

std::optional<Eigen::MatrixXd> ScaledSpectrum::WhiteLevel() const {
  auto level = base_->WhiteLevel();
  if (!level) return std::nullopt;
  return Eigen::MatrixXd(factor_ * *level);
}

std::vector<SpectralLine> ScaledSpectrum::Lines() const {
  std::vector<SpectralLine> lines = base_->Lines();
  for (SpectralLine& l : lines) l.rms *= std::sqrt(factor_);
  return lines;
}

std::string ScaledSpectrum::Describe() const { return NumberText(factor_) + " x [" + base_->Describe() + "]"; }

}  // namespace deb
