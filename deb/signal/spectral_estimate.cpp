#include "deb/signal/spectral_estimate.h"

#include <cstdio>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {

std::vector<std::string> WelchProvenance::Describe() const {
  char line[256];
  std::vector<std::string> lines;
  std::snprintf(line, sizeof line, "welch: window %s, segment %d samples, overlap %d samples, %d averages (%s), detrend %s",
                ToString(window).c_str(), segment_length, overlap_samples, segments, ToString(averaging).c_str(),
                ToString(detrend).c_str());
  lines.emplace_back(line);
  std::snprintf(line, sizeof line, "sample rate %.10g Hz, resolution %.6g Hz, equivalent noise bandwidth %.6g Hz",
                rate_hz, resolution_hz, enbw_hz);
  lines.emplace_back(line);
  std::snprintf(line, sizeof line,
                "chi-square: %.4g degrees of freedom; %.4g %% confidence: %.4g P <= S <= %.4g P", degrees_of_freedom,
                100.0 * confidence, lower_factor, upper_factor);
  lines.emplace_back(line);
  lines.emplace_back("one-sided PSD (variance = integral over f >= 0), unit^2/Hz");
  return lines;
}

Eigen::VectorXd CsdEstimate::Coherence(int i, int j) const {
  const Eigen::VectorXd sii = Auto(i), sjj = Auto(j);
  const Eigen::VectorXcd sij = Cross(i, j);
  Eigen::VectorXd gamma2(sij.size());
  for (Eigen::Index k = 0; k < sij.size(); ++k) {
    const double denominator = sii(k) * sjj(k);
    gamma2(k) = denominator > 0.0 ? std::min(1.0, std::norm(sij(k)) / denominator) : 0.0;
  }
  return gamma2;
}

PsdEstimate CsdEstimate::AutoSpectra() const {
  PsdEstimate e;
  e.f_hz = f_hz;
  e.psd.resize(csd.rows(), channels);
  for (int i = 0; i < channels; ++i) e.psd.col(i) = Auto(i);
  e.channel_names = channel_names;
  e.unit = unit;
  e.provenance = provenance;
  return e;
}

namespace {

// First bin above 0 Hz; @throws InputError if fewer than 2 bins remain.
std::size_t FirstPositiveBin(const std::vector<double>& f_hz) {
  std::size_t first = 0;
  while (first < f_hz.size() && !(f_hz[first] > 0.0)) ++first;
  const std::size_t n = f_hz.size() - first;
  if (n < 2)
    throw InputError("spectral estimate has " + std::to_string(n) +
                     " bins above 0 Hz; a spectrum needs at least 2 (use a longer segment)");
  return first;
}

std::string Origin(const WelchProvenance& p) {
  return "Welch estimate (" + ToString(p.window) + ", " + std::to_string(p.segment_length) + " samples, " +
         std::to_string(p.segments) + " averages, resolution " + NumberText(p.resolution_hz) + " Hz)";
}

}  // namespace

std::shared_ptr<const MeasuredSpectrum> ToMeasuredSpectrum(const PsdEstimate& estimate, Extrapolation extrapolation) {
  const std::size_t first = FirstPositiveBin(estimate.f_hz);
  const std::size_t n = estimate.f_hz.size() - first;
  MeasuredSpectrumOptions options;
  options.extrapolation = extrapolation;
  options.interpolation = SpectrumInterpolation::kBins;  // Welch bins: keep Parseval's sum
  options.channel_names = estimate.channel_names;
  options.unit = estimate.unit;
  options.origin = Origin(estimate.provenance);
  return std::make_shared<MeasuredSpectrum>(
      std::vector<double>(estimate.f_hz.begin() + static_cast<std::ptrdiff_t>(first), estimate.f_hz.end()),
      estimate.psd.bottomRows(static_cast<Eigen::Index>(n)), options);
}

std::shared_ptr<const TabulatedCsd> ToTabulatedCsd(const CsdEstimate& estimate, Extrapolation extrapolation) {
  if (estimate.provenance.averaging == Averaging::kMedian && estimate.channels > 1)
    throw InputError("a median-averaged cross-spectral matrix need not be positive semi-definite (real and "
                     "imaginary parts are medianed apart); use mean averaging for cross-spectra");
  const std::size_t first = FirstPositiveBin(estimate.f_hz);
  const auto n = static_cast<Eigen::Index>(estimate.f_hz.size() - first);
  const int c = estimate.channels;
  // Welch pairs conj(X_a) X_b in column a + c b; deb's S_ab is E[U_a U_b^*],
  // its conjugate, which for a Hermitian matrix is the transpose.
  Eigen::MatrixXcd csd(n, estimate.csd.cols());
  for (int b = 0; b < c; ++b)
    for (int a = 0; a < c; ++a) csd.col(a + c * b) = estimate.csd.col(b + c * a).bottomRows(n);
  TabulatedCsdOptions options;
  options.extrapolation = extrapolation;
  options.interpolation = SpectrumInterpolation::kBins;
  options.channel_names = estimate.channel_names;
  options.unit = estimate.unit;
  options.origin = Origin(estimate.provenance);
  return std::make_shared<TabulatedCsd>(
      std::vector<double>(estimate.f_hz.begin() + static_cast<std::ptrdiff_t>(first), estimate.f_hz.end()), c, csd,
      options);
}

}  // namespace deb
