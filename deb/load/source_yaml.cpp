#include "deb/load/source_yaml.h"

#include <cmath>
#include <complex>
#include <filesystem>
#include <optional>

#include "deb/core/limits.h"
#include "deb/core/math_constants.h"
#include "deb/formats/uff58_file.h"
#include "deb/load/uff_yaml.h"
#include "deb/signal/recording.h"
#include "deb/spectra/channel_set.h"
#include "deb/spectra/converted_spectrum.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/spectra/scaled_spectrum.h"
#include "deb/spectra/spectrum_csv.h"
#include "deb/spectra/tone_spectrum.h"
#include "deb/spectra/vc_curve.h"
#include "deb/units/unit.h"

namespace deb::load {
namespace {

// Channel names from `channels:` (a count or a list); `fallback` for none.
std::vector<std::string> ChannelNames(const YamlNode& source, const std::string& fallback_name, int fallback_count) {
  if (auto c = source.Optional("channels")) {
    if (c->IsScalar()) {
      const int n = c->AsInt();
      if (n < 1) c->Fail("channels must be >= 1, got " + std::to_string(n));
      if (n > limits::kMaxChannels)
        c->Fail(std::to_string(n) + " channels is more than the " + std::to_string(limits::kMaxChannels) +
                " a source may have");
      std::vector<std::string> names;
      for (int i = 1; i <= n; ++i) names.push_back(fallback_name + std::to_string(i));
      return names;
    }
    auto names = c->AsStrings();
    if (names.empty()) c->Fail("at least one channel is needed");
    return names;
  }
  if (fallback_count == 1) return {fallback_name};
  std::vector<std::string> names;
  for (int i = 1; i <= fallback_count; ++i) names.push_back(fallback_name + std::to_string(i));
  return names;
}

std::shared_ptr<const Spectrum> Repeat(std::shared_ptr<const Spectrum> one, std::size_t count) {
  if (count == 1) return one;
  return std::make_shared<IndependentChannels>(std::vector<std::shared_ptr<const Spectrum>>(count, one));
}

// Factor from the declared convention to one-sided PSD.
double ConventionFactor(const YamlNode& source) {
  const auto c = source.Optional("convention");
  if (!c) return 1.0;
  const std::string text = c->AsString();
  if (text == "one-sided") return 1.0;
  if (text == "two-sided") return 2.0;  // S_one(f) = 2 S_two(f) for f > 0
  c->Fail("unknown convention '" + text + "'; allowed: one-sided, two-sided");
}

// What a multi-channel recording keeps of its channels' relation.
enum class CrossSpectra {
  kFull,  // the Welch cross-spectral matrix: coherence and phase between channels
  kNone,  // auto-PSDs only: channels independent (diagonal S_u)
};

std::string ToString(CrossSpectra c) { return c == CrossSpectra::kFull ? "full" : "none"; }

CrossSpectra ParseCrossSpectra(const std::string& text) {
  for (CrossSpectra c : {CrossSpectra::kFull, CrossSpectra::kNone})
    if (text == ToString(c)) return c;
  throw InputError("unknown cross_spectra '" + text + "'; allowed: full, none");
}

// `type: timeseries`: a recording, turned into a Welch PSD (one channel, or
// cross_spectra: none) or a Welch cross-spectral matrix at load.
std::shared_ptr<const Spectrum> TimeSeriesSpectrum(const YamlNode& node, const YamlNode& spec,
                                                   const std::string& base_dir, Source* s) {
  spec.AllowOnly({"type", "file", "format", "rate_hz", "file_channels", "columns", "window", "segment_length",
                  "overlap", "detrend", "averaging", "extrapolation", "cross_spectra", "responses", "datasets"});
  CrossSpectra cross = CrossSpectra::kFull;
  if (auto c = spec.Optional("cross_spectra"))
    cross = AtNode(*c, [&] { return ParseCrossSpectra(c->AsString()); });
  if (node.Has("convention"))
    node.Required("convention").Fail("a time series gives a one-sided PSD by construction; remove 'convention'");
  const YamlNode file = spec.Required("file");
  std::filesystem::path p(file.AsString());
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  const bool uff = formats::FileLooksLikeUff(p.string());
  if (!uff)
    for (const char* key : {"responses", "datasets"})
      if (spec.Has(key))
        spec.Required(key).Fail(std::string("'") + key + "' chooses the datasets of a universal file (UFF 58); " +
                                p.string() + " is none");
  RecordingSpec recording;
  recording.file = p.string();
  const std::string format = spec.Optional("format") ? spec.Required("format").AsString() : "csv";
  const auto rate = spec.Optional("rate_hz");
  const auto unit_node = node.Optional("unit");
  if (uff) {
    // A universal file gives its sample rate and channels (ReadUffRecording).
  } else if (format == "csv") {
    if (spec.Has("file_channels"))
      spec.Required("file_channels").Fail("file_channels is for raw files; a CSV names its columns in its header");
    if (rate) recording.rate_hz = rate->AsPositive();
  } else {
    const YamlNode format_node = spec.Required("format");
    if (format != "float32" && format != "float64")
      format_node.Fail("unknown format '" + format + "'; allowed: csv, float32, float64");
    recording.raw = ParseRawSampleFormat(format);
    if (!rate) spec.Fail("missing 'rate_hz': a raw " + format + " file carries no sample rate");
    recording.rate_hz = rate->AsPositive();
    const YamlNode channels = spec.Required("file_channels");
    if (channels.IsScalar()) {
      recording.file_channels = channels.AsInt();
      if (recording.file_channels > limits::kMaxChannels)
        channels.Fail(std::to_string(recording.file_channels) + " channels is more than the " +
                      std::to_string(limits::kMaxChannels) + " a recording may have");
    } else {
      recording.file_channel_names = channels.AsStrings();
    }
  }
  TimeSeries series = uff ? ReadUffRecording(spec, p.string()) : AtNode(file, [&] { return ReadRecording(recording); });
  if (auto cols = spec.Optional("columns")) series = AtNode(*cols, [&] { return series.Select(cols->AsStrings()); });

  RecordingSpectrumOptions options;
  options.cross_spectra = cross == CrossSpectra::kFull;
  WelchOptions& welch = options.welch;
  if (auto v = spec.Optional("window")) welch.window = AtNode(*v, [&] { return ParseWindowKind(v->AsString()); });
  if (auto v = spec.Optional("segment_length")) {
    welch.segment_length = v->AsInt();
    if (welch.segment_length < WelchOptions::kMinSegmentLength)
      v->Fail("segment_length must be >= " + std::to_string(WelchOptions::kMinSegmentLength) +
              " samples (8 bins above 0 Hz), got " + std::to_string(welch.segment_length));
  }
  if (auto v = spec.Optional("overlap")) welch.overlap = v->AsNonNegative();
  if (auto v = spec.Optional("detrend")) welch.detrend = AtNode(*v, [&] { return ParseDetrend(v->AsString()); });
  if (auto v = spec.Optional("averaging")) welch.averaging = AtNode(*v, [&] { return ParseAveraging(v->AsString()); });
  if (auto e = spec.Optional("extrapolation"))
    options.extrapolation = AtNode(*e, [&] { return ParseExtrapolation(e->AsString()); });
  if (unit_node) options.unit = unit_node->AsString();
  options.key_path = spec.key();
  options.file_key_path = file.key();
  std::vector<YamlNode> located = {spec, file};
  if (auto v = spec.Optional("averaging")) {
    located.push_back(*v);
    options.averaging_key_path = v->key();
  }
  if (unit_node) {
    located.push_back(*unit_node);
    options.unit_key_path = unit_node->key();
  }
  RecordingSpectrum estimate = AtNodes(node, located, [&] { return SpectrumFromRecording(series, options); });
  if (!unit_node && series.unit().empty())
    node.Fail("missing 'unit': neither the budget nor " + p.string() +
              (uff ? " (records 9 and 10)" : " ('# unit:')") + " gives one");
  s->unit = estimate.unit;
  const std::shared_ptr<const Spectrum> m = estimate.spectrum;
  const std::vector<std::string>& estimate_names = estimate.channel_names;
  s->channel_names = node.Has("channels") ? ChannelNames(node, s->name, m->channels()) : estimate_names;
  if (static_cast<int>(s->channel_names.size()) != m->channels())
    node.Required("channels").Fail("the recording gives " + std::to_string(m->channels()) + " channel(s) but " +
                                   std::to_string(s->channel_names.size()) + " channel names are listed");
  return m;
}

// `type: reference`: Peterson's NLNM / NHNM, a vertical ground acceleration
// PSD, in the source's unit (um/s gives velocity: / (2 pi f)^2, as
// `deb spectrum reference --to` does). Extrapolation acts on the model's
// acceleration, so the physics does not depend on the unit chosen.
std::shared_ptr<const Spectrum> ReferenceSpectrum(const YamlNode& node, const YamlNode& spec, Source* s) {
  spec.AllowOnly({"type", "model", "extrapolation"});
  if (node.Has("convention"))
    node.Required("convention").Fail("a reference model is a one-sided PSD by definition; remove 'convention'");
  const YamlNode model_node = spec.Required("model");
  const PetersonModel model = AtNode(model_node, [&] { return ParsePetersonModel(model_node.AsString()); });
  Extrapolation extrapolation = Extrapolation::kError;
  if (auto e = spec.Optional("extrapolation"))
    extrapolation = AtNode(*e, [&] { return ParseExtrapolation(e->AsString()); });
  const auto unit_node = node.Optional("unit");
  s->unit = unit_node ? unit_node->AsString() : PetersonSpectrum::kUnit;
  const UnitConversion conv =
      AtNode(unit_node ? *unit_node : node, [&] { return ConvertUnit(PetersonSpectrum::kUnit, s->unit); });
  std::shared_ptr<const Spectrum> one = std::make_shared<PetersonSpectrum>(model, extrapolation);
  if (!conv.IsPureScale() || conv.scale != 1.0)
    one = std::make_shared<ConvertedSpectrum>(one, conv.scale, conv.derivative_order, s->unit);
  s->channel_names = ChannelNames(node, s->name, 1);
  return Repeat(one, s->channel_names.size());
}

}  // namespace

// `type: tones`: sinusoids, each an RMS (or peak) amplitude per channel (one
// number: the same on every channel) and optional phases in degrees.
static std::shared_ptr<const Spectrum> ToneSource(const YamlNode& node, const YamlNode& spec, Source* s) {
  spec.AllowOnly({"type", "tones"});
  const auto unit_node = node.Optional("unit");
  if (!unit_node) node.Fail("missing required key 'unit' (the unit of the tones' amplitudes)");
  s->unit = unit_node->AsString();
  if (node.Has("convention"))
    node.Required("convention").Fail("tones are amplitudes (rms or peak), not densities: remove 'convention'");
  s->channel_names = ChannelNames(node, s->name, 1);
  const std::size_t n = s->channel_names.size();
  const YamlNode list = spec.Required("tones");
  std::vector<SpectralLine> lines;
  for (const YamlNode& t : list.Elements()) {
    t.AllowOnly({"f_hz", "rms", "peak", "phase_deg"});
    if (t.Has("rms") == t.Has("peak")) t.Fail("give the tone's amplitude as rms or as peak (one of them)");
    const YamlNode a = t.Required(t.Has("rms") ? "rms" : "peak");
    const auto per_channel = [&](const YamlNode& v, const char* what) {
      std::vector<double> x = v.IsSequence() ? v.AsDoubles() : std::vector<double>(n, v.AsDouble());
      if (x.size() != n)
        v.Fail(std::string(what) + " has " + std::to_string(x.size()) + " value(s) for " + std::to_string(n) +
               " channel(s): give one number (every channel) or one per channel");
      return x;
    };
    const std::vector<double> amplitude = per_channel(a, "the amplitude");
    for (double x : amplitude)
      if (!(std::isfinite(x) && x >= 0.0)) a.Fail("an amplitude must be finite and >= 0");
    const std::vector<double> phase =
        t.Has("phase_deg") ? per_channel(t.Required("phase_deg"), "phase_deg") : std::vector<double>(n, 0.0);
    SpectralLine line;
    line.f_hz = t.Required("f_hz").AsPositive();
    line.rms.resize(static_cast<Eigen::Index>(n));
    const double to_rms = t.Has("peak") ? 1.0 / std::sqrt(2.0) : 1.0;
    for (std::size_t j = 0; j < n; ++j)
      line.rms(static_cast<Eigen::Index>(j)) = std::polar(amplitude[j] * to_rms, phase[j] * kPi / 180.0);
    lines.push_back(std::move(line));
  }
  return AtNode(list, [&] { return std::make_shared<ToneSpectrum>(std::move(lines), static_cast<int>(n)); });
}

// A flat spectrum: `level` in unit^2/Hz (or an ASD with quantity: asd), optionally band-limited.
static std::shared_ptr<const Spectrum> FlatSource(const YamlNode& node, const YamlNode& spec, Source* s) {
  const auto unit_node = node.Optional("unit");
  spec.AllowOnly({"type", "level", "quantity", "lo_hz", "hi_hz"});
  if (!unit_node) node.Fail("missing required key 'unit' (the unit of the signal; the level is in unit^2/Hz)");
  s->unit = unit_node->AsString();
  double level = spec.Required("level").AsNonNegative();
  if (auto q = spec.Optional("quantity")) {
    const auto quantity = AtNode(*q, [&] { return ParseSpectrumQuantity(q->AsString()); });
    if (quantity == SpectrumQuantity::kAsd) level *= level;
  } else {
    // As a measured file without '# quantity:': an ASD read as a PSD is
    // off by its own value in power (a level of 2e-4 by 5000x).
    s->notes.push_back("the flat level " + spec.Required("level").AsString() + " has no 'quantity:', so it is read as a PSD in " +
                       PsdUnitLabel(s->unit) + "; if it is an ASD in " + AsdUnitLabel(s->unit) +
                       ", add 'quantity: asd' (or 'quantity: psd' to confirm)");
  }
  level *= ConventionFactor(node);
  s->channel_names = ChannelNames(node, s->name, 1);
  const auto lo = spec.Optional("lo_hz"), hi = spec.Optional("hi_hz");
  std::shared_ptr<const Spectrum> one;
  if (lo || hi) {
    const double lo_hz = lo ? lo->AsNonNegative() : 0.0;
    const double hi_hz = hi ? hi->AsPositive() : std::numeric_limits<double>::infinity();
    one = AtNode(spec, [&] { return std::make_shared<FlatSpectrum>(level, lo_hz, hi_hz); });
  } else {
    one = AtNode(spec, [&] { return std::make_shared<FlatSpectrum>(level); });
  }
  return Repeat(one, s->channel_names.size());
}

// A vibration-criteria curve, in its velocity unit or one the budget converts it to.
static std::shared_ptr<const Spectrum> VcSource(const YamlNode& node, const YamlNode& spec, Source* s) {
  const auto unit_node = node.Optional("unit");
  spec.AllowOnly(
      {"type", "class", "velocity", "lowest_band_hz", "highest_band_hz", "low_frequency_extension", "series"});
  if (spec.Has("class") == spec.Has("velocity"))
    spec.Fail(std::string(spec.Has("class") ? "both 'class' and 'velocity'" : "neither 'class' nor 'velocity'") +
              ": give the criterion as a class (class: VC-D) or as its band RMS velocity (velocity: 6.25 um/s)");
  std::optional<VcClass> vc_class;
  if (auto cls = spec.Optional("class")) vc_class = AtNode(*cls, [&] { return ParseVcClass(cls->AsString()); });
  VcOptions options;
  if (auto v = spec.Optional("lowest_band_hz")) options.lowest_band_hz = v->AsPositive();
  if (auto v = spec.Optional("highest_band_hz")) options.highest_band_hz = v->AsPositive();
  if (auto v = spec.Optional("low_frequency_extension")) options.low_frequency_extension = v->AsBool();
  if (auto v = spec.Optional("series"))
    options.series = AtNode(*v, [&] { return ParseThirdOctaveSeries(v->AsString()); });
  s->unit = unit_node ? unit_node->AsString() : VcSpectrum::kUnit;
  const UnitConversion conv =
      AtNode(unit_node ? *unit_node : node, [&] { return ConvertUnit(VcSpectrum::kUnit, s->unit); });
  if (!conv.IsPureScale())
    unit_node->Fail("a VC curve is a velocity; unit '" + s->unit + "' is not a velocity unit");
  std::shared_ptr<const Spectrum> one;
  if (vc_class) {
    one = AtNode(spec, [&] { return std::make_shared<VcSpectrum>(*vc_class, options); });
  } else {
    // In the source's unit when a plain number (as the curve's), then in um/s.
    const double velocity_um_s = spec.Required("velocity").AsPositiveIn(s->unit) / conv.scale;
    one = AtNode(spec, [&] { return std::make_shared<VcSpectrum>(velocity_um_s, options); });
  }
  const double factor = conv.scale * conv.scale * ConventionFactor(node);
  if (factor != 1.0) one = std::make_shared<ScaledSpectrum>(one, factor);
  s->channel_names = ChannelNames(node, s->name, 1);
  return Repeat(one, s->channel_names.size());
}

// A measured spectrum read from a CSV file (relative to `base_dir`), its
// columns picked by name, or from a universal file (deb/load/uff_yaml.h).
static std::shared_ptr<const Spectrum> MeasuredSource(const YamlNode& node, const YamlNode& spec,
                                                      const std::string& base_dir, Source* s) {
  const auto unit_node = node.Optional("unit");
  const YamlNode file = spec.Required("file");
  std::filesystem::path p(file.AsString());
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  if (formats::FileLooksLikeUff(p.string())) {
    spec.AllowOnly({"type", "file", "columns", "extrapolation", kUffSourceKeys[0], kUffSourceKeys[1]});
    if (node.Has("convention"))
      node.Required("convention").Fail("a universal file's PSDs are one-sided; remove 'convention'");
    return ParseUffSpectrum(node, spec, p.string(), s);
  }
  for (const char* key : kUffSourceKeys)
    if (spec.Has(key))
      spec.Required(key).Fail(std::string("'") + key + "' chooses datasets of a universal file (UFF 58); " +
                              p.string() + " is a table: choose its columns with 'columns'");
  spec.AllowOnly({"type", "file", "columns", "extrapolation"});
  if (node.Has("convention"))
    node.Required("convention").Fail("a measured spectrum declares its convention in the file ('# sides: one|two')");
  SpectrumCsv csv = AtNode(file, [&] { return ReadSpectrumCsv(p.string()); });
  if (auto cols = spec.Optional("columns")) {
    const auto wanted = cols->AsStrings();
    Eigen::MatrixXd picked(csv.psd.rows(), static_cast<Eigen::Index>(wanted.size()));
    for (std::size_t j = 0; j < wanted.size(); ++j) {
      const auto it = std::find(csv.channel_names.begin(), csv.channel_names.end(), wanted[j]);
      // A confidence bound (x_hi: a conservative source) may be picked by name too.
      const auto bound = std::find(csv.bound_names.begin(), csv.bound_names.end(), wanted[j]);
      if (it == csv.channel_names.end() && bound == csv.bound_names.end()) {
        std::string have;
        for (const auto& n : csv.channel_names) have += (have.empty() ? "" : ", ") + n;
        for (const auto& n : csv.bound_names) have += (have.empty() ? "" : ", ") + n;
        cols->Fail("column '" + wanted[j] + "' is not in " + p.string() + " (columns: " + have + ")");
      }
      picked.col(static_cast<Eigen::Index>(j)) = it != csv.channel_names.end()
                                                     ? Eigen::VectorXd(csv.psd.col(it - csv.channel_names.begin()))
                                                     : Eigen::VectorXd(csv.bounds.col(bound - csv.bound_names.begin()));
    }
    csv.psd = picked;
    csv.channel_names = wanted;
  }
  Extrapolation extrapolation = Extrapolation::kError;
  if (auto e = spec.Optional("extrapolation"))
    extrapolation = AtNode(*e, [&] { return ParseExtrapolation(e->AsString()); });
  if (!unit_node && !csv.unit) node.Fail("missing 'unit': neither the budget nor " + p.string() + " ('# unit:') gives one");
  s->unit = unit_node ? unit_node->AsString() : *csv.unit;
  if (!csv.quantity_declared) {
    const std::string u = csv.unit.value_or(s->unit);
    s->notes.push_back(p.string() + " has no '# quantity:' line, so its values are read as a PSD in " +
                       PsdUnitLabel(u) + "; if they are an ASD in " + AsdUnitLabel(u) +
                       ", add the line '# quantity: asd' (or '# quantity: psd' to confirm)");
  }
  double factor = 1.0;
  if (csv.unit) {
    const UnitConversion conv = AtNode(unit_node ? *unit_node : node, [&] { return ConvertUnit(*csv.unit, s->unit); });
    if (!conv.IsPureScale())
      unit_node->Fail("the file's unit '" + *csv.unit + "' and '" + s->unit + "' are not the same quantity");
    factor = conv.scale * conv.scale;
  }
  std::shared_ptr<const Spectrum> m = AtNode(file, [&] { return MakeMeasuredSpectrum(csv, extrapolation); });
  if (factor != 1.0) m = std::make_shared<ScaledSpectrum>(m, factor);
  s->channel_names = node.Has("channels") ? ChannelNames(node, s->name, m->channels()) : csv.channel_names;
  if (static_cast<int>(s->channel_names.size()) != m->channels())
    node.Required("channels").Fail("the file gives " + std::to_string(m->channels()) + " column(s) but " +
                                   std::to_string(s->channel_names.size()) + " channel names are listed");
  return m;
}

// `spectrum` with the channels correlated as `c` says: one coefficient for every pair, or the matrix.
static std::shared_ptr<const Spectrum> Correlated(const YamlNode& c, const std::string& type,
                                                  std::shared_ptr<const Spectrum> spectrum) {
  if (type == "tones")
    c.Fail("tones on several channels are coherent: their phases (phase_deg) relate them; remove 'correlation'");
  if (type == "timeseries" && !spectrum->IsDiagonal())
    c.Fail("the recording's cross-spectra already give the channels' correlation; remove 'correlation', or "
           "set cross_spectra: none to impose one on independent channels");
  const int n = spectrum->channels();
  Eigen::MatrixXd rho;
  if (c.IsScalar()) {
    rho = Eigen::MatrixXd::Constant(n, n, c.AsDouble());
    rho.diagonal().setOnes();
  } else {
    rho = c.AsMatrix();
  }
  if (rho.rows() != n || rho.cols() != n)
    c.Fail("correlation must be a number or a " + std::to_string(n) + "x" + std::to_string(n) + " matrix, got " +
           std::to_string(rho.rows()) + "x" + std::to_string(rho.cols()));
  return AtNode(c, [&] { return std::make_shared<CorrelatedChannels>(spectrum, rho); });
}

Source ParseSource(const YamlNode& node, const std::string& base_dir) {
  node.AllowOnly({"name", "description", "unit", "channels", "convention", "spectrum", "correlation"});
  Source s;
  s.name = node.Required("name").AsString();
  if (auto d = node.Optional("description")) s.description = d->AsString();
  const YamlNode spec = node.Required("spectrum");
  const std::string type = spec.Required("type").AsString();
  const auto unit_node = node.Optional("unit");
  std::shared_ptr<const Spectrum> spectrum;

  if (type == "flat") {
    spectrum = FlatSource(node, spec, &s);
  } else if (type == "vc") {
    spectrum = VcSource(node, spec, &s);
  } else if (type == "measured") {
    spectrum = MeasuredSource(node, spec, base_dir, &s);
  } else if (type == "tones") {
    spectrum = ToneSource(node, spec, &s);
  } else if (type == "timeseries") {
    spectrum = TimeSeriesSpectrum(node, spec, base_dir, &s);
  } else if (type == "reference") {
    spectrum = ReferenceSpectrum(node, spec, &s);
  } else {
    spec.Required("type").Fail("unknown spectrum type '" + type +
                               "'; allowed: flat, vc, measured, timeseries, reference, tones");
  }

  if (auto c = node.Optional("correlation")) spectrum = Correlated(*c, type, spectrum);
  AtNode(unit_node ? *unit_node : node, [&] { ValidateUnit(s.unit); });
  s.spectrum = spectrum;
  return s;
}

}  // namespace deb::load
