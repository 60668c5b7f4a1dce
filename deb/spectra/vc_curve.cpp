#include "deb/spectra/vc_curve.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {

VcOptions VcOptions::ThesisModified() {
  VcOptions options;
  options.lowest_band_hz = 0.5;
  options.highest_band_hz = 80.0;
  options.low_frequency_extension = true;
  options.series = ThirdOctaveSeries::kBase2From1Hz;
  return options;
}

VcSpectrum::VcSpectrum(VcClass vc_class, const VcOptions& options)
    : vc_class_(vc_class), options_(options), velocity_um_s_(VcCriterionOf(vc_class).velocity_um_s) {
  Build(VcCriterionOf(vc_class));
}

VcSpectrum::VcSpectrum(double velocity_um_s, const VcOptions& options)
    : vc_class_(VcClass::kA), named_(false), options_(options), velocity_um_s_(velocity_um_s) {
  DEB_DEMAND(std::isfinite(velocity_um_s) && velocity_um_s > 0.0);
  for (const VcCriterion& row : VcCriteria())
    if (std::abs(row.velocity_um_s - velocity_um_s) <= 1e-9 * row.velocity_um_s) {
      vc_class_ = row.vc_class;
      named_ = true;
    }
  // Every class has the same constant-velocity range (spectra/vc_curves.csv).
  Build(VcCriterionOf(vc_class_));
}

void VcSpectrum::Build(const VcCriterion& row) {
  const VcOptions& options = options_;
  const std::string where = named_ ? std::string(row.name) + ": " : "VC curve of " + NumberText(velocity_um_s_) + " um/s: ";
  const ThirdOctaveBand range_lo = ThirdOctaveBandNear(row.lowest_band_hz, options.series);
  const ThirdOctaveBand range_hi = ThirdOctaveBandNear(row.highest_band_hz, options.series);
  const ThirdOctaveBand lowest = ThirdOctaveBandNear(options.lowest_band_hz, options.series);
  const ThirdOctaveBand highest = ThirdOctaveBandNear(options.highest_band_hz, options.series);
  if (highest.index > range_hi.index) {
    throw InputError(where + "highest band " + NumberText(options.highest_band_hz) +
                     " Hz is above the criterion's highest band " + NumberText(row.highest_band_hz) + " Hz");
  }
  if (lowest.index < range_lo.index && !options.low_frequency_extension) {
    throw InputError(where + "lowest band " + NumberText(options.lowest_band_hz) +
                     " Hz is below the criterion's constant-velocity range, which starts at the " +
                     NumberText(row.lowest_band_hz) +
                     " Hz band; set low_frequency_extension to continue the constant velocity down "
                     "(the thesis' modified VC)");
  }
  if (lowest.index > highest.index) {
    throw InputError(where + "lowest band " + NumberText(options.lowest_band_hz) +
                     " Hz is above highest band " + NumberText(options.highest_band_hz) + " Hz");
  }
  bands_ = ThirdOctaveBandsBetween(options.lowest_band_hz, options.highest_band_hz, options.series);
  const double variance = velocity_um_s_ * velocity_um_s_;
  for (const ThirdOctaveBand& band : bands_) {
    // S = v^2 / B over the band (eq. 4-2), B from the same edges used to
    // evaluate the PSD, so the band integral is v^2 to rounding.
    band_psd_.push_back(variance / band.BandwidthHz());
    edges_hz_.push_back(band.lo_hz);
  }
  edges_hz_.push_back(bands_.back().hi_hz);
}

double VcSpectrum::PsdAt(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz) && f_hz > 0.0);
  // First edge above f; band i spans [edges_hz_[i], edges_hz_[i+1]).
  const auto above = std::upper_bound(edges_hz_.begin(), edges_hz_.end(), f_hz);
  if (above == edges_hz_.begin() || above == edges_hz_.end()) return 0.0;
  return band_psd_[static_cast<std::size_t>(above - edges_hz_.begin()) - 1];
}

Eigen::MatrixXcd VcSpectrum::Csd(double f_hz) const {
  return Eigen::MatrixXcd::Constant(1, 1, PsdAt(f_hz));
}

Eigen::VectorXd VcSpectrum::Psd(double f_hz) const { return Eigen::VectorXd::Constant(1, PsdAt(f_hz)); }

std::vector<double> VcSpectrum::BreakpointsHz() const { return edges_hz_; }

std::string VcSpectrum::Describe() const {
  std::string text = (named_ ? ToString(vc_class_) : std::string("VC curve")) + " (" + NumberText(velocity_um_s_) +
                     " um/s RMS per band), " +
                     std::to_string(bands_.size()) + " one-third-octave bands " +
                     NumberText(options_.lowest_band_hz) + "-" + NumberText(options_.highest_band_hz) +
                     " Hz (" + ToString(options_.series) + " centres)";
  const double range_lo_hz = VcCriterionOf(vc_class_).lowest_band_hz;
  if (ThirdOctaveBandNear(options_.lowest_band_hz, options_.series).index <
      ThirdOctaveBandNear(range_lo_hz, options_.series).index) {
    text += ", constant velocity extended below " + NumberText(range_lo_hz) + " Hz";
  }
  return text + "; PSD in (um/s)^2/Hz";
}

}  // namespace deb
