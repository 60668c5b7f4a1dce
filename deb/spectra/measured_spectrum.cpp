#include "deb/spectra/measured_spectrum.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

// S at f_hz between the points (f0, s0) and (f1, s1), per the rules in the header.
double Interpolate(double f_hz, double log_f, double f0, double log_f0, double s0, double f1,
                   double log_f1, double s1) {
  if (s0 > 0.0 && s1 > 0.0) {
    const double t = (log_f - log_f0) / (log_f1 - log_f0);
    return std::exp(std::log(s0) + t * (std::log(s1) - std::log(s0)));
  }
  return s0 + (s1 - s0) * (f_hz - f0) / (f1 - f0);
}

}  // namespace

MeasuredSpectrum::MeasuredSpectrum(std::vector<double> f_hz, Eigen::MatrixXd psd,
                                   MeasuredSpectrumOptions options)
    : f_hz_(std::move(f_hz)), psd_(std::move(psd)), options_(std::move(options)) {
  const std::string where =
      "measured spectrum" + (options_.origin.empty() ? std::string() : " '" + options_.origin + "'") + ": ";
  const std::size_t n = f_hz_.size();
  if (n < 2) {
    throw InputError(where + std::to_string(n) + " frequencies given; at least 2 are needed");
  }
  if (psd_.rows() != static_cast<Eigen::Index>(n) || psd_.cols() < 1) {
    throw InputError(where + "PSD table is " + std::to_string(psd_.rows()) + " x " +
                     std::to_string(psd_.cols()) + "; expected " + std::to_string(n) +
                     " rows (one per frequency) and at least 1 column");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(f_hz_[i]) || f_hz_[i] <= 0.0) {
      throw InputError(where + "frequency[" + std::to_string(i) + "] = " + NumberText(f_hz_[i]) +
                       " Hz; frequencies must be finite and > 0");
    }
    if (i > 0 && !(f_hz_[i] > f_hz_[i - 1])) {
      throw InputError(where + "frequency[" + std::to_string(i) + "] = " + NumberText(f_hz_[i]) +
                       " Hz is not greater than frequency[" + std::to_string(i - 1) + "] = " +
                       NumberText(f_hz_[i - 1]) + " Hz; frequencies must increase strictly");
    }
  }
  if (options_.channel_names.empty()) {
    for (Eigen::Index c = 0; c < psd_.cols(); ++c) options_.channel_names.push_back("ch" + std::to_string(c + 1));
  } else if (options_.channel_names.size() != static_cast<std::size_t>(psd_.cols())) {
    throw InputError(where + std::to_string(options_.channel_names.size()) + " channel names for " +
                     std::to_string(psd_.cols()) + " PSD columns");
  }
  for (Eigen::Index c = 0; c < psd_.cols(); ++c) {
    for (std::size_t i = 0; i < n; ++i) {
      const double value = psd_(static_cast<Eigen::Index>(i), c);
      if (!std::isfinite(value) || value < 0.0) {
        throw InputError(where + "PSD of channel '" + options_.channel_names[c] + "' at " +
                         NumberText(f_hz_[i]) + " Hz is " + NumberText(value) +
                         "; PSD values must be finite and >= 0");
      }
    }
  }
  for (double f : f_hz_) log_f_.push_back(std::log(f));
  lo_hz_ = f_hz_.front();
  hi_hz_ = f_hz_.back();
  if (options_.interpolation == SpectrumInterpolation::kBins) {
    edges_hz_.push_back(std::max(f_hz_[0] - 0.5 * (f_hz_[1] - f_hz_[0]), 0.5 * f_hz_[0]));
    for (std::size_t i = 1; i < n; ++i) edges_hz_.push_back(0.5 * (f_hz_[i - 1] + f_hz_[i]));
    edges_hz_.push_back(f_hz_[n - 1] + 0.5 * (f_hz_[n - 1] - f_hz_[n - 2]));
    lo_hz_ = edges_hz_.front();
    hi_hz_ = edges_hz_.back();
  }
}

std::size_t MeasuredSpectrum::BinOf(double f_hz) const {
  DEB_DEMAND(!edges_hz_.empty());
  const auto above = std::upper_bound(edges_hz_.begin(), edges_hz_.end(), f_hz);
  const std::size_t i = static_cast<std::size_t>(above - edges_hz_.begin());
  return std::min(i == 0 ? 0 : i - 1, f_hz_.size() - 1);
}

Eigen::VectorXd MeasuredSpectrum::Psd(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz) && f_hz > 0.0);
  const double f_first = lo_hz_;
  const double f_last = hi_hz_;
  if (f_hz < f_first || f_hz > f_last) {
    switch (options_.extrapolation) {
      case Extrapolation::kError:
        throw InputError("measured spectrum" +
                         (options_.origin.empty() ? std::string() : " '" + options_.origin + "'") +
                         ": frequency " + NumberText(f_hz) + " Hz is outside the data range " +
                         NumberText(f_first) + "-" + NumberText(f_last) +
                         " Hz (extrapolation: error); keep the frequency range inside the data or "
                         "choose extrapolation zero or hold");
      case Extrapolation::kZero: return Eigen::VectorXd::Zero(psd_.cols());
      case Extrapolation::kHold: return psd_.row(f_hz < f_first ? 0 : psd_.rows() - 1).transpose();
    }
  }
  if (options_.interpolation == SpectrumInterpolation::kBins)
    return psd_.row(static_cast<Eigen::Index>(BinOf(f_hz))).transpose();
  // Interval [f_hz_[i], f_hz_[i+1]] holding f; a data point returns its value.
  const auto above = std::upper_bound(f_hz_.begin(), f_hz_.end(), f_hz);
  const std::size_t i1 = std::min(static_cast<std::size_t>(above - f_hz_.begin()), f_hz_.size() - 1);
  const std::size_t i0 = i1 - 1;
  const auto r0 = static_cast<Eigen::Index>(i0);
  const auto r1 = static_cast<Eigen::Index>(i1);
  if (f_hz == f_hz_[i0]) return psd_.row(r0).transpose();
  if (f_hz == f_hz_[i1]) return psd_.row(r1).transpose();
  const double log_f = std::log(f_hz);
  Eigen::VectorXd out(psd_.cols());
  for (Eigen::Index c = 0; c < psd_.cols(); ++c) {
    out(c) = Interpolate(f_hz, log_f, f_hz_[i0], log_f_[i0], psd_(r0, c), f_hz_[i1], log_f_[i1], psd_(r1, c));
  }
  return out;
}

Eigen::MatrixXcd MeasuredSpectrum::Csd(double f_hz) const {
  return Psd(f_hz).cast<std::complex<double>>().asDiagonal();
}

std::vector<double> MeasuredSpectrum::BreakpointsHz() const {
  return options_.interpolation == SpectrumInterpolation::kBins ? edges_hz_ : f_hz_;
}

std::string MeasuredSpectrum::Describe() const {
  std::string names;
  for (const std::string& name : options_.channel_names) names += (names.empty() ? "" : ", ") + name;
  std::string text = "measured";
  if (!options_.origin.empty()) text += " '" + options_.origin + "'";
  text += ", " + std::to_string(psd_.cols()) + (psd_.cols() == 1 ? " channel (" : " channels (") + names +
          "), " + std::to_string(f_hz_.size()) + " points " + NumberText(f_hz_.front()) + "-" +
          NumberText(f_hz_.back()) + " Hz, " +
          (options_.interpolation == SpectrumInterpolation::kBins
               ? "constant over each bin (" + NumberText(lo_hz_) + "-" + NumberText(hi_hz_) + " Hz)"
               : std::string("log-log interpolation")) +
          ", extrapolation " +
          ToString(options_.extrapolation);
  if (!options_.unit.empty()) text += "; PSD in (" + options_.unit + ")^2/Hz";
  return text;
}

}  // namespace deb
