#include "tools/spectrum_command.h"


#include <algorithm>
#include <cerrno>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/core/output_dir.h"
#include "deb/report/figure/output_files.h"
#include "deb/report/figure/plot_files.h"
#include "deb/report/figure/report_options.h"
#include "deb/report/measurement/measurement_plots.h"
#include "deb/signal/frf_estimate.h"
#include "deb/signal/recording.h"
#include "deb/signal/self_noise.h"
#include "deb/signal/welch.h"
#include "deb/spectra/band_rms.h"
#include "deb/spectra/band_table.h"
#include "deb/spectra/building_criteria.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/spectra/spectrum_csv.h"
#include "deb/systems/frf_csv.h"
#include "deb/units/unit.h"

namespace deb::tools {

// Options shared by the commands that read a recording.
struct RecordingOptions {
  std::string file;
  double rate_hz = 0.0;
  std::string format = "csv";
  std::vector<std::string> file_channels;  // raw: names, or one count
  std::vector<std::string> columns;
  std::string unit;
  std::string window = "hann";
  int segment = 0;
  double overlap = 0.5;
  std::string detrend = "mean";
  std::string averaging = "mean";
  double confidence = 0.95;
  int threads = 0;
};

struct SpectrumCommand::Options {
  RecordingOptions rec;
  std::string out;
  bool bounds = false;
  std::string coherence_out;
  // bands
  std::string spectrum_file;
  std::string series = "base2_1hz";
  double lowest_hz = 0.0, highest_hz = 0.0;
  std::string criteria = "all";
  bool extend = false;
  std::string unit;
  // convert
  std::string to_unit;
  bool asd = false;
  bool from_bands = false;
  // selfnoise
  std::vector<std::string> sensors;
  // frf
  std::string input;
  std::vector<std::string> outputs;
  std::string frf_unit;
  std::string estimator = "h1";
  // reference
  std::string model;
  double points_per_decade = 50.0;
  // plots
  bool plots = true;
  std::string plot_file;                 // --plot: the main plot's file
  std::vector<PlotFormat> plot_formats;  // --plot-format; empty: --plot's extension, else png
  CLI::App *welch = nullptr, *bands = nullptr, *convert = nullptr, *selfnoise = nullptr, *frf = nullptr,
           *reference = nullptr;
};

namespace {

namespace fs = std::filesystem;


using Settings = SpectrumCommand::Options;

void AddRecordingOptions(CLI::App* c, RecordingOptions& r) {
  c->add_option("recording", r.file, "Time series: CSV (time column or '# rate_hz:') or raw little-endian floats")
      ->required()
      ->check(CLI::ExistingFile);
  c->add_option("--rate", r.rate_hz, "Sample rate, Hz (raw files; CSV files without one)")->check(CLI::PositiveNumber);
  c->add_option("--format", r.format, "csv, float32 or float64")->check(CLI::IsMember({"csv", "float32", "float64"}));
  c->add_option("--file-channels", r.file_channels, "Raw files: channel names, or their count")->delimiter(',');
  c->add_option("--columns", r.columns, "Channels to analyse (default: all)")->delimiter(',');
  c->add_option("--unit", r.unit, "Unit of the samples (if the file has no '# unit:')");
  c->add_option("--window", r.window, AllowedNames<WindowKind>());
  c->add_option("--segment", r.segment, "Samples per segment (default: largest power of two giving >= 8 segments)")
      ->check(CLI::Range(2, 1 << 30));
  c->add_option("--overlap", r.overlap, "Fraction of a segment shared with the next, [0, 1)");
  c->add_option("--detrend", r.detrend, AllowedNames<Detrend>() + " (per segment)");
  c->add_option("--average", r.averaging, "mean or median (bias-corrected)");
  c->add_option("--confidence", r.confidence, "Level of the chi-square bounds");
  c->add_option("--threads,-j", r.threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
}

TimeSeries ReadRecording(const RecordingOptions& r) {
  RecordingSpec spec;
  spec.file = r.file;
  if (r.format != "csv") spec.raw = ParseRawSampleFormat(r.format);
  if (r.rate_hz > 0.0 || spec.raw) spec.rate_hz = r.rate_hz;
  spec.unit = r.unit;
  if (r.file_channels.size() == 1 && std::isdigit(static_cast<unsigned char>(r.file_channels[0][0])))
    spec.file_channels = std::stoi(r.file_channels[0]);
  else
    spec.file_channel_names = r.file_channels;
  spec.columns = r.columns;
  return deb::ReadRecording(spec);
}

WelchOptions Welch(const RecordingOptions& r) {
  WelchOptions o;
  o.window = ParseWindowKind(r.window);
  o.segment_length = r.segment;
  o.overlap = r.overlap;
  o.detrend = ParseDetrend(r.detrend);
  o.averaging = ParseAveraging(r.averaging);
  o.confidence = r.confidence;
  o.threads = r.threads;
  return o;
}

// Where a plot goes: beside the file it shows, named after it.
struct PlotPlace {
  std::string directory, stem;
};

// The main plot goes to --plot if given, else beside the output file; a
// second plot (coherence) beside its own file. Output on standard output
// ("" or "-") has no plot unless --plot names one.
std::optional<PlotPlace> PlacePlot(const Settings& s, const std::string& out, bool main) {
  if (!s.plots) return std::nullopt;
  const std::string file = main && !s.plot_file.empty() ? s.plot_file : out;
  if (file.empty() || file == "-") return std::nullopt;
  const fs::path p(file);
  return PlotPlace{p.parent_path().string(), p.stem().string()};
}

// The plot formats: --plot-format, else the extension of --plot, else png.
std::vector<PlotFormat> PlotFormats(const Settings& s) {
  const std::string ext = s.plot_file.empty() ? "" : fs::path(s.plot_file).extension().string().substr(1);
  if (s.plot_formats.empty()) return {ext.empty() ? PlotFormat::kPng : ParsePlotFormat(ext)};
  if (!ext.empty() && std::find(s.plot_formats.begin(), s.plot_formats.end(), ParsePlotFormat(ext)) ==
                          s.plot_formats.end())
    throw InputError("--plot " + s.plot_file + " is a ." + ext + " file but --plot-format does not include " + ext);
  return s.plot_formats;
}

// Everything one command writes (report::OutputFiles), with the plot
// formats and notes of the command line.
class Outputs {
 public:
  explicit Outputs(const Settings& s)
      : settings_(s), files_("; name the plot with --plot, or give --no-plots") {}

  // path "" or "-": standard output.
  void Text(const std::string& path, std::string text, const std::string& what) {
    files_.Text(path, std::move(text), what);
  }
  // plot.name must be place.stem: its script reads the data by that name.
  void Plot(const PlotPlace& place, report::Plot plot) {
    DEB_DEMAND(plot.name == place.stem);
    files_.Plot(place.directory, std::move(plot));
  }
  const std::vector<std::string>& written() const { return written_; }

  void Write() {
    if (!files_.has_plots() && settings_.plots && !settings_.plot_formats.empty())
      std::fprintf(stderr, "deb: note: no plot: the CSV goes to standard output; name the plot with --plot\n");
    const std::vector<PlotFormat> formats = files_.has_plots() ? PlotFormats(settings_) : std::vector<PlotFormat>{};
    written_ = files_.Write(formats, std::cout, "", settings_.rec.threads);
  }

 private:
  const Settings& settings_;
  report::OutputFiles files_;
  std::vector<std::string> written_;
};

// "wrote psd.csv, psd.plot.csv, psd.gp, psd.png": on standard output, or on
// standard error when the CSV itself went to standard output.
void PrintWritten(const Outputs& outputs, const std::string& out) {
  if (outputs.written().empty()) return;
  std::string line = "wrote ";
  for (std::size_t i = 0; i < outputs.written().size(); ++i) line += (i ? ", " : "") + outputs.written()[i];
  std::fprintf(out.empty() || out == "-" ? stderr : stdout, "%s\n", line.c_str());
}

std::string SourceName(const std::string& path) { return fs::path(path).filename().string(); }

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

SpectrumQuantity Quantity(bool asd) { return asd ? SpectrumQuantity::kAsd : SpectrumQuantity::kPsd; }

std::vector<std::string> Provenance(const std::string& what, const PsdEstimate& e, const std::string& source) {
  std::vector<std::string> lines = {what + " of " + source};
  for (const std::string& l : e.provenance.Describe()) lines.push_back(l);
  lines.push_back("interpolation: bins");  // read back as the estimate's bins (measured_spectrum.h)
  return lines;
}

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
    std::ostringstream out;
    out << "# coherence |S_ab|^2/(S_aa S_bb) and CSD phase arg S_ab = arg <conj(X_a) X_b>, rad\n";
    for (const std::string& l : e.provenance.Describe()) out << "# " << l << "\n";
    out << "f_hz";
    // Coherence and phase of each pair over all bins, built once per pair.
    Eigen::MatrixXd columns(static_cast<Eigen::Index>(csd.f_hz.size()), csd.channels * (csd.channels - 1));
    Eigen::Index column = 0;
    for (int b = 0; b < csd.channels; ++b)
      for (int a = 0; a < b; ++a) {
        const std::string pair = csd.channel_names[static_cast<std::size_t>(a)] + "_" +
                                 csd.channel_names[static_cast<std::size_t>(b)];
        out << ", coherence_" << pair << ", phase_" << pair;
        columns.col(column++) = csd.Coherence(a, b);
        columns.col(column++) = csd.Cross(a, b).unaryExpr([](const std::complex<double>& s) { return std::arg(s); });
      }
    out << "\n";
    for (Eigen::Index k = 0; k < columns.rows(); ++k) {
      out << Number(csd.f_hz[static_cast<std::size_t>(k)]);
      for (Eigen::Index c = 0; c < columns.cols(); ++c) out << ", " << Number(columns(k, c));
      out << "\n";
    }
    outputs.Text(s.coherence_out, out.str(), "the coherence CSV (--coherence)");
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

int RunBands(const Settings& s) {
  const SpectrumCsv csv = ReadSpectrumCsv(s.spectrum_file);
  std::string unit = csv.unit.value_or("");
  if (!s.unit.empty()) {
    if (!unit.empty() && unit != s.unit)
      throw InputError(s.spectrum_file + ": the file declares '# unit: " + unit + "' but --unit " + s.unit +
                       " is given");
    unit = s.unit;
  }
  const bool classify = s.criteria != "none";
  const ThirdOctaveSeries series = ParseThirdOctaveSeries(s.series);
  SpectrumClassOptions options;
  options.classify_bands = classify;
  options.classify.series = series;
  options.classify.low_frequency_extension = s.extend;
  options.lowest_hz = s.lowest_hz;
  options.highest_hz = s.highest_hz;
  if (classify) {
    options.classify.set = ParseCriteriaSet(s.criteria);
    if (unit.empty())
      throw InputError(s.spectrum_file + ": classification needs the unit of the spectrum: give '# unit:' in the "
                       "file or --unit (any velocity, displacement or acceleration unit)");
  }
  // Criteria are band RMS velocities in um/s: convert (with (2 pi f)^2n for
  // displacement or acceleration) before integrating.
  const UnitConversion to_velocity = classify ? ConvertUnit(unit, "um/s") : UnitConversion{};
  if (classify) options.to_velocity_psd = [&to_velocity](double f_hz) { return to_velocity.PsdFactor(f_hz); };
  const std::string band_unit = classify ? "um/s" : unit;
  std::ostringstream out;
  out << "# one-third-octave band RMS (" << ToString(series) << " centres)"
      << (band_unit.empty() ? "" : " in " + band_unit) << " of " << s.spectrum_file << "\n";
  if (classify && !to_velocity.IsPureScale()) out << "# converted from " << unit << ": " << to_velocity.Describe() << "\n";
  if (!band_unit.empty()) out << "# unit: " << band_unit << "\n";  // for convert --from-bands
  const SpectrumClasses classes = ClassifySpectrum(csv.f_hz, csv.psd, csv.interpolation, options);
  const std::vector<std::vector<BandRms>>& per_channel = classes.bands;
  const std::vector<Classification>& verdicts = classes.classes;
  out << "centre_hz, lo_hz, hi_hz, points";
  for (const std::string& n : csv.channel_names) out << ", " << n << (classify ? ", " + n + "_class" : "");
  out << "\n";
  for (std::size_t i = 0; i < per_channel.front().size(); ++i) {
    const BandRms& b = per_channel.front()[i];
    out << Number(b.band.centre_hz) << ", " << Number(b.band.lo_hz) << ", " << Number(b.band.hi_hz) << ", " << b.points;
    for (std::size_t c = 0; c < per_channel.size(); ++c) {
      out << ", " << Number(per_channel[c][i].rms);
      if (classify) {
        const BandVerdict& v = verdicts[c].bands[i];
        out << ", " << (!v.assessed ? "-" : v.best ? verdicts[c].criteria[*v.best].name : "none");
      }
    }
    out << "\n";
  }
  Outputs outputs(s);
  outputs.Text(s.out, out.str(), "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true)) {
    outputs.Plot(*place, report::BandClassPlot(csv.channel_names, per_channel, verdicts, options.classify, band_unit,
                                               SourceName(s.spectrum_file), place->stem));
  }
  outputs.Write();
  if (!s.out.empty() && s.out != "-") {
    for (std::size_t c = 0; c < per_channel.size(); ++c) {
      std::printf("%s: %zu bands", csv.channel_names[c].c_str(), per_channel[c].size());
      if (classify) std::printf(", %s", verdicts[c].Summary().c_str());
      std::printf("\n");
    }
    // The channels share one frequency grid, so one count holds for all: said once.
    int coarse = 0;
    for (const BandRms& b : per_channel.front()) coarse += b.points < 5;
    if (coarse > 0)
      std::printf("warning: %d band(s) hold fewer than 5 spectral lines; use a longer segment to resolve them\n",
                  coarse);
    if (!csv.bound_names.empty())
      std::printf("(%zu confidence-bound column(s) of %s, not channels, are not classified)\n", csv.bound_names.size(),
                  s.spectrum_file.c_str());
  }
  PrintWritten(outputs, s.out);
  return 0;
}

int RunConvert(const Settings& s) {
  if (s.from_bands) {
    // A band table: centre_hz and one band-RMS column per channel.
    // The output of `deb spectrum bands` as it is, or a table by hand (band_table.h).
    const BandTable table = ReadBandTable(s.spectrum_file);
    const ThirdOctaveSeries series = ParseThirdOctaveSeries(s.series);
    std::vector<ThirdOctaveBand> bands;
    for (double f : table.centre_hz) bands.push_back(ThirdOctaveBandNear(f, series));
    std::vector<double> f_out;
    Eigen::MatrixXd psd;
    for (Eigen::Index c = 0; c < table.rms.cols(); ++c) {
      const Eigen::VectorXd col = table.rms.col(c);
      const PsdTable t = BandRmsToPsd(bands, std::vector<double>(col.data(), col.data() + col.size()));
      if (c == 0) {
        f_out = t.f_hz;
        psd.resize(static_cast<Eigen::Index>(t.f_hz.size()), table.rms.cols());
      }
      psd.col(c) = Eigen::Map<const Eigen::VectorXd>(t.psd.data(), static_cast<Eigen::Index>(t.psd.size()));
    }
    Outputs outputs(s);
    outputs.Text(s.out, SpectrumCsvText({"PSD from the one-third-octave band RMS table " + s.spectrum_file +
                                             " (constant in each band, " + ToString(series) + " edges)"},
                                        table.unit.value_or(""), Quantity(s.asd), f_out, psd, table.channel_names),
                 "the output CSV (-o)");
    if (const auto place = PlacePlot(s, s.out, true))
      outputs.Plot(*place, report::SpectrumTablePlot(
                               f_out, psd, table.channel_names, table.unit.value_or(""), s.asd,
                               std::string(s.asd ? "ASD" : "PSD") + " from the band RMS table " +
                                   SourceName(s.spectrum_file) + " (constant in each band)",
                               place->stem));
    outputs.Write();
    PrintWritten(outputs, s.out);
    return 0;
  }
  const SpectrumCsv csv = ReadSpectrumCsv(s.spectrum_file);
  const std::string from = csv.unit.value_or(s.unit);
  std::string to = s.to_unit.empty() ? from : s.to_unit;
  Eigen::MatrixXd psd = csv.psd;
  Eigen::MatrixXd bounds = csv.bounds;  // confidence bounds convert with their channels
  std::vector<std::string> comments = {"converted from " + s.spectrum_file};
  if (csv.interpolation == SpectrumInterpolation::kBins) comments.push_back("interpolation: bins");
  if (!s.to_unit.empty()) {
    if (from.empty())
      throw InputError(s.spectrum_file + ": --to needs the spectrum's unit: give '# unit:' in the file or --unit");
    const UnitConversion conv = ConvertUnit(from, to);
    for (std::size_t k = 0; k < csv.f_hz.size(); ++k) {
      psd.row(static_cast<Eigen::Index>(k)) *= conv.PsdFactor(csv.f_hz[k]);
      if (bounds.cols() > 0) bounds.row(static_cast<Eigen::Index>(k)) *= conv.PsdFactor(csv.f_hz[k]);
    }
    comments.push_back(from + " -> " + to + ": " + conv.Describe());
  }
  Outputs outputs(s);
  if (s.asd) bounds = bounds.cwiseSqrt();  // extra columns are written as they are
  outputs.Text(s.out,
               SpectrumCsvText(comments, to, Quantity(s.asd), csv.f_hz, psd, csv.channel_names,
                               bounds.cols() > 0 ? &bounds : nullptr, csv.bound_names),
               "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true)) {
    std::string title = std::string(s.asd ? "ASD" : "PSD") + " of " + SourceName(s.spectrum_file);
    if (!s.to_unit.empty()) title += ", converted from " + report::UnitText(from) + " to " + report::UnitText(to);
    outputs.Plot(*place, report::SpectrumTablePlot(csv.f_hz, psd, csv.channel_names, to, s.asd, title, place->stem));
  }
  outputs.Write();
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

int RunReference(const Settings& s) {
  const PetersonModel model = ParsePetersonModel(s.model);
  const std::string unit = s.to_unit.empty() ? PetersonSpectrum::kUnit : s.to_unit;
  const UnitConversion conv = ConvertUnit(PetersonSpectrum::kUnit, unit);
  if (!(s.points_per_decade >= 1.0 && s.points_per_decade <= limits::kMaxPointsPerDecade))
    throw InputError("--points-per-decade " + NumberText(s.points_per_decade) + " is invalid; it must be from 1 to " +
                     std::to_string(static_cast<long long>(limits::kMaxPointsPerDecade)));
  std::vector<double> f;
  const int n = static_cast<int>(std::ceil(6.0 * s.points_per_decade));
  for (int i = 0; i <= n; ++i) f.push_back(PetersonSpectrum::kMinHz * std::pow(10.0, 6.0 * i / n));
  f.back() = PetersonSpectrum::kMaxHz;
  Eigen::MatrixXd psd(static_cast<Eigen::Index>(f.size()), 1);
  for (std::size_t k = 0; k < f.size(); ++k)
    psd(static_cast<Eigen::Index>(k), 0) = PetersonAccelerationPsd(model, f[k]) * conv.PsdFactor(f[k]);
  Outputs outputs(s);
  outputs.Text(s.out, SpectrumCsvText({"Peterson (1993), USGS OFR 93-322, " + ToString(model) +
                                           ": vertical ground motion, converted from m/s^2: " + conv.Describe()},
                                      unit, Quantity(s.asd), f, psd, {ToString(model)}),
               "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true))
    outputs.Plot(*place, report::PetersonPlot(model, f, unit, s.asd, place->stem));
  outputs.Write();
  PrintWritten(outputs, s.out);
  return 0;
}

// --plot, --plot-format and --no-plots (recordings already take --format).
void AddPlotOptions(CLI::App* c, Settings& s) {
  CLI::Option* plot =
      c->add_option("--plot", s.plot_file,
                    "Plot file, .png, .svg or .pdf (default: beside -o, named after it: psd.csv -> psd.png, with "
                    "psd.gp and psd.plot.csv; none when the CSV goes to standard output)")
          ->check(CLI::Validator(
              [](std::string& file) -> std::string {
                const std::string ext = fs::path(file).extension().string();
                if (ext == ".png" || ext == ".svg" || ext == ".pdf") return "";
                return "the plot file must end in .png, .svg or .pdf: " + file;
              },
              "FILE.png|svg|pdf"));
  CLI::Option* formats =
      c->add_option_function<std::vector<std::string>>(
           "--plot-format",
           [&s](const std::vector<std::string>& names) {
             if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
               throw CLI::ValidationError("--plot-format", "a format is given twice");
             s.plot_formats.clear();
             for (const auto& n : names) s.plot_formats.push_back(ParsePlotFormat(n));
           },
           "Plot formats, comma-separated: png, pdf, svg (default: png, or the extension of --plot)")
          ->delimiter(',')
          ->check(CLI::IsMember({"png", "pdf", "svg"}));
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; }, "Write the CSV only; gnuplot is not needed")
      ->excludes(plot)
      ->excludes(formats);
}

}  // namespace

SpectrumCommand::SpectrumCommand() : options_(std::make_unique<Options>()) {}
SpectrumCommand::~SpectrumCommand() = default;

CLI::App* SpectrumCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* spectrum = app.add_subcommand("spectrum", "Measured data: Welch spectra, band RMS and VC/ISO classes, "
                                                      "conversions, sensor self-noise, reference spectra");
  spectrum->require_subcommand(1);

  s.welch = spectrum->add_subcommand("welch", "One-sided Welch PSD of a recording, as a spectrum CSV");
  AddRecordingOptions(s.welch, s.rec);
  s.welch->add_option("--out,-o", s.out, "Output spectrum CSV (default: standard output)");
  s.welch->add_flag("--bounds", s.bounds, "Add <channel>_lo/_hi columns: the chi-square confidence bounds");
  s.welch->add_option("--coherence", s.coherence_out, "Also write coherence and CSD phase of every pair to this CSV "
                                                      "(and its plot beside it, as for -o)");
  AddPlotOptions(s.welch, s);

  s.bands = spectrum->add_subcommand("bands", "One-third-octave band RMS of a spectrum CSV and its VC/ISO class");
  s.bands->add_option("spectrum", s.spectrum_file, "Spectrum CSV")->required()->check(CLI::ExistingFile);
  s.bands->add_option("--series", s.series, AllowedNames<ThirdOctaveSeries>());
  s.bands->add_option("--lowest", s.lowest_hz, "Nominal centre of the lowest band (default: all bands in the data)");
  s.bands->add_option("--highest", s.highest_hz, "Nominal centre of the highest band")->needs("--lowest");
  s.bands->add_option("--criteria", s.criteria, "vc, iso, all, or none (band RMS only, in the file's unit)")
      ->check(CLI::IsMember({"vc", "iso", "all", "none"}));
  s.bands->add_flag("--extend", s.extend, "Continue the VC curves' constant velocity below 8 Hz (thesis' modified VC)");
  s.bands->add_option("--unit", s.unit, "Unit of the spectrum's signal, if the file has no '# unit:'");
  s.bands->add_option("--out,-o", s.out, "Output CSV (default: standard output)");
  AddPlotOptions(s.bands, s);

  s.convert = spectrum->add_subcommand("convert", "Convert a spectrum CSV: unit (displacement, velocity, "
                                                  "acceleration), PSD or ASD, band RMS table to PSD");
  s.convert->add_option("spectrum", s.spectrum_file, "Spectrum CSV (or band table with --from-bands)")
      ->required()
      ->check(CLI::ExistingFile);
  s.convert->add_option("--to", s.to_unit, "Target unit, e.g. um/s, nm, m/s^2");
  s.convert->add_option("--unit", s.unit, "Unit of the input, if the file has no '# unit:'");
  s.convert->add_flag("--asd", s.asd, "Write an ASD (unit/sqrt(Hz)) instead of a PSD");
  s.convert->add_flag("--from-bands", s.from_bands,
                      "Input rows are band centres and band RMS values: write the PSD constant in each band");
  s.convert->add_option("--series", s.series, "Band series for --from-bands: " + AllowedNames<ThirdOctaveSeries>());
  s.convert->add_option("--out,-o", s.out, "Output spectrum CSV (default: standard output)");
  AddPlotOptions(s.convert, s);

  s.selfnoise = spectrum->add_subcommand("selfnoise", "Sensor self-noise from co-located recordings: two sensors "
                                                      "(Holcomb, identical sensors) or three (Sleeman)");
  AddRecordingOptions(s.selfnoise, s.rec);
  s.selfnoise->add_option("--sensors", s.sensors, "2 or 3 channel names")->required()->delimiter(',');
  s.selfnoise->add_option("--out,-o", s.out, "Output noise spectrum CSV (default: standard output)");
  AddPlotOptions(s.selfnoise, s);

  s.frf = spectrum->add_subcommand("frf", "Frequency response (H1 = S_xy/S_xx) and coherence from recordings of "
                                          "an input and outputs, as a file a `type: frf` path reads");
  AddRecordingOptions(s.frf, s.rec);
  s.frf->add_option("--input", s.input, "The input channel (e.g. the shaker force)")->required();
  s.frf->add_option("--outputs", s.outputs, "Output channels, comma-separated")->required()->delimiter(',');
  s.frf->add_option("--frf-unit", s.frf_unit, "Unit of H (output unit/input unit) for the file's note and the plot");
  s.frf->add_option("--estimator", s.estimator,
                    "h1 (S_xy/S_xx: noise on the outputs) or h2 (S_yy/S_yx: noise on the input); default h1")
      ->check(CLI::IsMember({"h1", "h2"}));
  s.frf->add_option("--out,-o", s.out, "Output FRF CSV (default: standard output)");
  AddPlotOptions(s.frf, s);

  s.reference = spectrum->add_subcommand("reference", "Peterson's New Low/High Noise Model as a spectrum CSV");
  s.reference->add_option("model", s.model, AllowedNames<PetersonModel>())->required();
  s.reference->add_option("--to", s.to_unit, "Unit (default m/s^2; e.g. um/s, nm)");
  s.reference->add_option("--points-per-decade", s.points_per_decade, "Frequencies per decade, 1e-5-10 Hz");
  s.reference->add_flag("--asd", s.asd, "Write an ASD instead of a PSD");
  s.reference->add_option("--out,-o", s.out, "Output spectrum CSV (default: standard output)");
  AddPlotOptions(s.reference, s);
  return spectrum;
}

int SpectrumCommand::Run() const {
  const Options& s = *options_;
  if (*s.welch) return RunWelch(s);
  if (*s.bands) return RunBands(s);
  if (*s.convert) return RunConvert(s);
  if (*s.selfnoise) return RunSelfNoise(s);
  if (*s.frf) return RunFrf(s);
  if (*s.reference) return RunReference(s);
  return 2;
}

}  // namespace deb::tools
