#include <algorithm>
#include <cstdio>

#include "deb/core/error.h"
#include "deb/report/measurement/measurement_plots.h"
#include "deb/signal/coherence_csv.h"
#include "deb/signal/frf_estimate.h"
#include "deb/signal/self_noise.h"
#include "deb/systems/frf_csv.h"
#include "tools/spectrum_subcommands.h"

// The subcommands that read recordings: welch, selfnoise and frf.
namespace deb::tools {

int RunWelch(const Settings& s) {
  const TimeSeries series = ReadRecording(s.rec);
  const WelchOptions o = Welch(s.rec);
  const bool cross = !s.coherence_out.empty();
  const CsdEstimate csd = cross ? WelchCsd(series, o) : CsdEstimate{};
  const PsdEstimate e = cross ? csd.AutoSpectra() : WelchPsd(series, o);
  Eigen::MatrixXd bounds;
  std::vector<std::string> bound_names;
  if (s.bounds) {
    bounds.resize(e.psd.rows(), 2 * e.psd.cols());
    for (Eigen::Index c = 0; c < e.psd.cols(); ++c) {
      bounds.col(2 * c) = e.psd.col(c) * e.provenance.lower_factor;
      bounds.col(2 * c + 1) = e.psd.col(c) * e.provenance.upper_factor;
      bound_names.push_back(e.channel_names[static_cast<std::size_t>(c)] + "_lo");
      bound_names.push_back(e.channel_names[static_cast<std::size_t>(c)] + "_hi");
    }
  }
  Outputs outputs(s);
  outputs.Text(s.out, SpectrumCsvText(Provenance("Welch PSD", e, s.rec.file), e.unit, SpectrumQuantity::kPsd, e.f_hz, e.psd,
                                      e.channel_names, s.bounds ? &bounds : nullptr, bound_names),
               "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true))
    outputs.Plot(*place, report::WelchPsdPlot(e, SourceName(s.rec.file), s.bounds, place->stem));
  if (cross) {
    outputs.Text(s.coherence_out, CoherenceCsvText(csd), "the coherence CSV (--coherence)");
    // A single channel has no pair: its coherence CSV holds frequencies only.
    if (const auto place = PlacePlot(s, s.coherence_out, false); place && csd.channels >= 2)
      outputs.Plot(*place, report::CoherencePlot(csd, SourceName(s.rec.file), place->stem));
  }
  outputs.Write();
  if (!s.out.empty() && s.out != "-") {
    std::printf("%s: %zu channel(s), %lld samples at %g Hz\n", s.rec.file.c_str(), e.channel_names.size(),
                static_cast<long long>(series.size()), series.rate_hz());
    for (const std::string& l : e.provenance.Describe()) std::printf("  %s\n", l.c_str());
  }
  PrintWritten(outputs, s.out);
  return 0;
}

int RunSelfNoise(const Settings& s) {
  if (s.sensors.size() != 2 && s.sensors.size() != 3)
    throw InputError("--sensors: give 2 (Holcomb, identical sensors) or 3 (Sleeman) channel names, got " +
                     std::to_string(s.sensors.size()));
  RecordingOptions r = s.rec;
  r.columns = s.sensors;
  const TimeSeries series = ReadRecording(r);
  const CsdEstimate csd = WelchCsd(series, Welch(r));
  const SelfNoiseEstimate n = s.sensors.size() == 2 ? TwoSensorSelfNoise(csd, 0, 1) : ThreeSensorSelfNoise(csd, 0, 1, 2);
  std::vector<std::string> comments = Provenance("sensor self-noise", n.noise, s.rec.file);
  comments.insert(comments.begin() + 1, n.method);
  for (std::size_t c = 0; c < n.clamped_bins.size(); ++c)
    if (n.clamped_bins[c] > 0)
      comments.push_back(n.noise.channel_names[c] + ": " + std::to_string(n.clamped_bins[c]) +
                         " bins estimated below zero, set to 0");
  Outputs outputs(s);
  outputs.Text(s.out, SpectrumCsvText(comments, n.noise.unit, SpectrumQuantity::kPsd, n.noise.f_hz, n.noise.psd, n.noise.channel_names),
               "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true))
    outputs.Plot(*place, report::SelfNoisePlot(csd.AutoSpectra(), n, SourceName(s.rec.file), place->stem));
  outputs.Write();
  if (!s.out.empty() && s.out != "-") {
    std::printf("%s\n", n.method.c_str());
    for (std::size_t c = 0; c < n.clamped_bins.size(); ++c)
      std::printf("  %s: median noise PSD %.4g %s^2/Hz; %d bins clamped at 0\n", n.noise.channel_names[c].c_str(),
                  [&] {
                    std::vector<double> v(n.noise.psd.col(static_cast<Eigen::Index>(c)).data() + 1,
                                          n.noise.psd.col(static_cast<Eigen::Index>(c)).data() + n.noise.psd.rows());
                    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
                    return v[v.size() / 2];
                  }(),
                  n.noise.unit.empty() ? "unit" : ("(" + n.noise.unit + ")").c_str(), n.clamped_bins[c]);
  }
  PrintWritten(outputs, s.out);
  return 0;
}

int RunFrf(const Settings& s) {
  RecordingOptions r = s.rec;
  r.columns = {s.input};
  r.columns.insert(r.columns.end(), s.outputs.begin(), s.outputs.end());
  const TimeSeries series = ReadRecording(r);
  const CsdEstimate csd = WelchCsd(series, Welch(r));
  const FrfEstimate e = EstimateFrf(csd, s.input, s.outputs, ParseFrfEstimator(s.estimator));
  const std::string formula = e.estimator == FrfEstimator::kH1 ? "H1 = S_xy / S_xx" : "H2 = S_yy / S_yx";
  std::vector<std::string> comments = {"frequency response " + formula + " from " + s.input + " of " +
                                       SourceName(s.rec.file) + "; coherence |S_xy|^2 / (S_xx S_yy)"};
  for (const std::string& l : e.provenance.Describe())
    if (l.rfind("one-sided", 0) != 0) comments.push_back(l);
  if (!s.frf_unit.empty()) comments.push_back("unit of H: " + s.frf_unit);
  if (e.empty_bins > 0) comments.push_back(std::to_string(e.empty_bins) + " bins without input power: H set to 0");
  Outputs outputs(s);
  outputs.Text(s.out, FrfCsvText(comments, e.f_hz, e.input, e.outputs, e.h, e.coherence), "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true))
    outputs.Plot(*place, report::FrfPlot(e, s.frf_unit, SourceName(s.rec.file), place->stem));
  outputs.Write();
  PrintWritten(outputs, s.out);
  return 0;
}

}  // namespace deb::tools
