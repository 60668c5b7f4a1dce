#include "deb/spectra/tabulated_csd.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

std::string Where(const TabulatedCsdOptions& options) {
  return "cross-spectral table" + (options.origin.empty() ? std::string() : " '" + options.origin + "'") + ": ";
}

std::string ComplexText(std::complex<double> z) {
  return NumberText(z.real()) + (z.imag() < 0.0 ? " - " : " + ") + NumberText(std::abs(z.imag())) + "j";
}

// The diagonal of the table, after the checks that must precede reading it.
MeasuredSpectrum AutoSpectra(std::vector<double> f_hz, int channels, const Eigen::MatrixXcd& csd,
                             const TabulatedCsdOptions& options) {
  const std::string where = Where(options);
  if (channels < 1) throw InputError(where + std::to_string(channels) + " channels; at least 1 is needed");
  const auto n = static_cast<Eigen::Index>(channels);
  if (csd.rows() != static_cast<Eigen::Index>(f_hz.size()) || csd.cols() != n * n)
    throw InputError(where + "table is " + std::to_string(csd.rows()) + " x " + std::to_string(csd.cols()) +
                     "; expected " + std::to_string(f_hz.size()) + " rows (one per frequency) and " +
                     std::to_string(n * n) + " columns (S_ab in column a + " + std::to_string(n) + " b)");
  Eigen::MatrixXd autos(csd.rows(), n);
  for (Eigen::Index i = 0; i < csd.rows(); ++i) {
    for (Eigen::Index a = 0; a < n; ++a) {
      const std::complex<double> s = csd(i, a + n * a);
      // Sign and finiteness are MeasuredSpectrum's checks; here only "real".
      if (std::isfinite(s.real()) && !(std::abs(s.imag()) <= TabulatedCsd::kTolerance * std::abs(s.real())))
        throw InputError(where + "the auto-PSD of channel " + std::to_string(a + 1) + " at " +
                         NumberText(f_hz[static_cast<std::size_t>(i)]) + " Hz is " + ComplexText(s) +
                         "; an auto-PSD must be real");
      autos(i, a) = s.real();
    }
  }
  MeasuredSpectrumOptions m;
  m.extrapolation = options.extrapolation;
  m.interpolation = options.interpolation;
  m.channel_names = options.channel_names;
  m.unit = options.unit;
  m.origin = options.origin;
  return MeasuredSpectrum(std::move(f_hz), std::move(autos), std::move(m));
}

}  // namespace

TabulatedCsd::TabulatedCsd(std::vector<double> f_hz, int channels, const Eigen::MatrixXcd& csd,
                           TabulatedCsdOptions options)
    : autos_(AutoSpectra(std::move(f_hz), channels, csd, options)), channels_(channels), options_(std::move(options)) {
  options_.channel_names = autos_.channel_names();
  const std::string where = Where(options_);
  const auto n = static_cast<Eigen::Index>(channels_);
  const std::vector<double>& f = autos_.f_hz();
  for (double v : f) log_f_.push_back(std::log(v));
  cross_.resize(csd.rows(), n * (n - 1) / 2);
  const Eigen::MatrixXd& s = autos_.psd_table();
  auto name = [this](int a, int b) {
    return "S(" + options_.channel_names[static_cast<std::size_t>(a)] + ", " +
           options_.channel_names[static_cast<std::size_t>(b)] + ")";
  };
  for (Eigen::Index i = 0; i < csd.rows(); ++i) {
    const std::string at = " at " + NumberText(f[static_cast<std::size_t>(i)]) + " Hz";
    for (int b = 1; b < channels_; ++b) {
      for (int a = 0; a < b; ++a) {
        const std::complex<double> upper = csd(i, a + n * b);
        const std::complex<double> lower = csd(i, b + n * a);
        if (!std::isfinite(upper.real()) || !std::isfinite(upper.imag()) || !std::isfinite(lower.real()) ||
            !std::isfinite(lower.imag()))
          throw InputError(where + name(a, b) + at + " is not finite");
        const double scale = std::sqrt(s(i, a) * s(i, b));
        if (std::abs(upper - std::conj(lower)) > kTolerance * scale)
          throw InputError(where + name(a, b) + " = " + ComplexText(upper) + " and " + name(b, a) + " = " +
                           ComplexText(lower) + at + "; the matrix must be Hermitian, S_ba = conj(S_ab)");
        cross_(i, Pair(a, b)) = upper;
      }
    }
    if (channels_ == 1) continue;
    // Positive semi-definite <=> so is the coherency matrix (a congruence by
    // diag(1/sqrt(S_aa)) where the autos are > 0; a channel with S_aa = 0
    // must have no cross term at all).
    Eigen::MatrixXcd c = Eigen::MatrixXcd::Identity(n, n);
    for (int b = 1; b < channels_; ++b) {
      for (int a = 0; a < b; ++a) {
        const std::complex<double> sab = cross_(i, Pair(a, b));
        if (s(i, a) == 0.0 || s(i, b) == 0.0) {
          if (sab != 0.0)
            throw InputError(where + name(a, b) + at + " is " + ComplexText(sab) +
                             " but a channel's PSD is 0 there; the matrix must be positive semi-definite");
          continue;
        }
        c(a, b) = Coherency(static_cast<std::size_t>(i), a, b);
        c(b, a) = std::conj(c(a, b));
      }
    }
    const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>(c, Eigen::EigenvaluesOnly)
                                .eigenvalues()
                                .minCoeff();
    if (smallest < -kTolerance) {
      std::string detail;
      if (channels_ == 2) detail = " (|coherency| = " + NumberText(std::abs(c(0, 1))) + " > 1)";
      throw InputError(where + "the matrix" + at + " is not positive semi-definite: its coherency matrix has "
                       "eigenvalue " + NumberText(smallest) + detail + "; a cross-spectral density cannot");
    }
  }
}

Eigen::Index TabulatedCsd::Pair(int a, int b) const {
  DEB_DEMAND(0 <= a && a < b && b < channels_);
  return static_cast<Eigen::Index>(b) * (b - 1) / 2 + a;
}

std::complex<double> TabulatedCsd::Coherency(std::size_t i, int a, int b) const {
  const auto r = static_cast<Eigen::Index>(i);
  const double scale = std::sqrt(autos_.psd_table()(r, a) * autos_.psd_table()(r, b));
  return scale > 0.0 ? cross_(r, Pair(a, b)) / scale : std::complex<double>(0.0);
}

Eigen::MatrixXcd TabulatedCsd::Node(std::size_t i) const {
  const auto r = static_cast<Eigen::Index>(i);
  Eigen::MatrixXcd m(channels_, channels_);
  for (int b = 0; b < channels_; ++b) {
    m(b, b) = autos_.psd_table()(r, b);
    for (int a = 0; a < b; ++a) {
      m(a, b) = cross_(r, Pair(a, b));
      m(b, a) = std::conj(m(a, b));
    }
  }
  return m;
}

Eigen::VectorXd TabulatedCsd::Psd(double f_hz) const { return autos_.Psd(f_hz); }

Eigen::MatrixXcd TabulatedCsd::Csd(double f_hz) const {
  // The autos first: outside the data they throw (kError) or give the policy.
  const Eigen::VectorXd d = autos_.Psd(f_hz);
  const std::vector<double>& f = autos_.f_hz();
  if (f_hz < autos_.lo_hz() || f_hz > autos_.hi_hz()) {
    if (options_.extrapolation == Extrapolation::kHold) return Node(f_hz < autos_.lo_hz() ? 0 : f.size() - 1);
    return Eigen::MatrixXcd::Zero(channels_, channels_);
  }
  if (options_.interpolation == SpectrumInterpolation::kBins) return Node(autos_.BinOf(f_hz));
  const auto above = std::upper_bound(f.begin(), f.end(), f_hz);
  const std::size_t i1 = std::min(static_cast<std::size_t>(above - f.begin()), f.size() - 1);
  const std::size_t i0 = i1 - 1;
  if (f_hz == f[i0]) return Node(i0);
  if (f_hz == f[i1]) return Node(i1);
  const double t = (std::log(f_hz) - log_f_[i0]) / (log_f_[i1] - log_f_[i0]);
  Eigen::MatrixXcd m(channels_, channels_);
  for (int b = 0; b < channels_; ++b) {
    m(b, b) = d(b);
    for (int a = 0; a < b; ++a) {
      const std::complex<double> c = (1.0 - t) * Coherency(i0, a, b) + t * Coherency(i1, a, b);
      m(a, b) = std::sqrt(d(a) * d(b)) * c;
      m(b, a) = std::conj(m(a, b));
    }
  }
  return m;
}

std::vector<double> TabulatedCsd::BreakpointsHz() const { return autos_.BreakpointsHz(); }

std::string TabulatedCsd::Describe() const {
  std::string names;
  for (const std::string& name : options_.channel_names) names += (names.empty() ? "" : ", ") + name;
  const std::vector<double>& f = autos_.f_hz();
  std::string text = "cross-spectral";
  if (!options_.origin.empty()) text += " '" + options_.origin + "'";
  text += ", " + std::to_string(channels_) + (channels_ == 1 ? " channel (" : " channels (") + names + "), " +
          std::to_string(f.size()) + " points " + NumberText(f.front()) + "-" + NumberText(f.back()) +
          " Hz, " +
          (options_.interpolation == SpectrumInterpolation::kBins
               ? "constant over each bin (" + NumberText(autos_.lo_hz()) + "-" + NumberText(autos_.hi_hz()) + " Hz)"
               : std::string("auto-PSDs log-log, coherency linear in log f")) +
          ", extrapolation " +
          ToString(options_.extrapolation);
  if (!options_.unit.empty()) text += "; CSD in (" + options_.unit + ")^2/Hz";
  return text;
}

}  // namespace deb
