#include "deb/signal/spectral_estimate.h"

#include <cstdio>

#include "deb/core/error.h"
#include "deb/spectra/number_text.h"

namespace deb {

std::string ToString(Detrend detrend) {
  switch (detrend) {
    case Detrend::kNone: return "none";
    case Detrend::kMean: return "mean";
    case Detrend::kLinear: return "linear";
  }
  DEB_DEMAND(false);
  return {};
}

Detrend ParseDetrend(const std::string& text) {
  if (text == "constant") return Detrend::kMean;
  for (Detrend d : {Detrend::kNone, Detrend::kMean, Detrend::kLinear}) {
    if (text == ToString(d)) return d;
  }
  throw InputError("unknown detrend '" + text + "'; allowed: none, mean, linear");
}

std::string ToString(Averaging averaging) {
  switch (averaging) {
    case Averaging::kMean: return "mean";
    case Averaging::kMedian: return "median";
  }
  DEB_DEMAND(false);
  return {};
}

Averaging ParseAveraging(const std::string& text) {
  for (Averaging a : {Averaging::kMean, Averaging::kMedian}) {
    if (text == ToString(a)) return a;
  }
  throw InputError("unknown averaging '" + text + "'; allowed: mean, median");
}

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

std::shared_ptr<const MeasuredSpectrum> ToMeasuredSpectrum(const PsdEstimate& estimate, Extrapolation extrapolation) {
  std::size_t first = 0;
  while (first < estimate.f_hz.size() && !(estimate.f_hz[first] > 0.0)) ++first;
  const std::size_t n = estimate.f_hz.size() - first;
  if (n < 2)
    throw InputError("spectral estimate has " + std::to_string(n) +
                     " bins above 0 Hz; a spectrum needs at least 2 (use a longer segment)");
  MeasuredSpectrumOptions options;
  options.extrapolation = extrapolation;
  options.channel_names = estimate.channel_names;
  options.unit = estimate.unit;
  options.origin = "Welch estimate (" + ToString(estimate.provenance.window) + ", " +
                   std::to_string(estimate.provenance.segment_length) + " samples, " +
                   std::to_string(estimate.provenance.segments) + " averages, resolution " +
                   NumberText(estimate.provenance.resolution_hz) + " Hz)";
  return std::make_shared<MeasuredSpectrum>(
      std::vector<double>(estimate.f_hz.begin() + static_cast<std::ptrdiff_t>(first), estimate.f_hz.end()),
      estimate.psd.bottomRows(static_cast<Eigen::Index>(n)), options);
}

}  // namespace deb
