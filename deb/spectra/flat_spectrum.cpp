#include "deb/spectra/flat_spectrum.h"

#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

void CheckLevel(double level_psd) {
  if (!std::isfinite(level_psd) || level_psd < 0.0) {
    throw InputError("flat spectrum: level " + NumberText(level_psd) +
                     " /Hz is invalid; a PSD level must be finite and >= 0");
  }
}

}  // namespace

FlatSpectrum::FlatSpectrum(double level_psd) : level_psd_(level_psd) { CheckLevel(level_psd); }

FlatSpectrum::FlatSpectrum(double level_psd, double lo_hz, double hi_hz)
    : level_psd_(level_psd), lo_hz_(lo_hz), hi_hz_(hi_hz) {
  CheckLevel(level_psd);
  if (!std::isfinite(lo_hz) || lo_hz < 0.0) {
    throw InputError("flat spectrum: lower band limit " + NumberText(lo_hz) +
                     " Hz is invalid; it must be finite and >= 0");
  }
  // NaN fails every comparison, so test for "not greater" rather than "<=".
  if (!(hi_hz > lo_hz)) {
    throw InputError("flat spectrum: upper band limit " + NumberText(hi_hz) +
                     " Hz must be greater than the lower band limit " + NumberText(lo_hz) + " Hz");
  }
}

bool FlatSpectrum::IsBandLimited() const { return lo_hz_ > 0.0 || std::isfinite(hi_hz_); }

double FlatSpectrum::PsdAt(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz) && f_hz > 0.0);
  return (f_hz >= lo_hz_ && f_hz <= hi_hz_) ? level_psd_ : 0.0;
}

Eigen::MatrixXcd FlatSpectrum::Csd(double f_hz) const {
  return Eigen::MatrixXcd::Constant(1, 1, PsdAt(f_hz));
}

Eigen::VectorXd FlatSpectrum::Psd(double f_hz) const {
  return Eigen::VectorXd::Constant(1, PsdAt(f_hz));
}

std::vector<double> FlatSpectrum::BreakpointsHz() const {
  std::vector<double> breakpoints;
  if (lo_hz_ > 0.0) breakpoints.push_back(lo_hz_);
  if (std::isfinite(hi_hz_)) breakpoints.push_back(hi_hz_);
  return breakpoints;
}

std::optional<Eigen::MatrixXd> FlatSpectrum::WhiteLevel() const {
  if (IsBandLimited()) return std::nullopt;
  return Eigen::MatrixXd::Constant(1, 1, level_psd_);
}

std::string FlatSpectrum::Describe() const {
  std::string text = "flat, one-sided PSD " + NumberText(level_psd_) + " unit^2/Hz";
  if (IsBandLimited()) {
    text += ", band " + NumberText(lo_hz_) + "-" + NumberText(hi_hz_) + " Hz (zero outside)";
  }
  return text;
}

}  // namespace deb
