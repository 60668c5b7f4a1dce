#include "tools/spectrum_subcommands.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "deb/core/error.h"
#include "deb/signal/recording.h"

namespace deb::tools {

namespace fs = std::filesystem;

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

namespace {

// The plot formats: --plot-format, else the extension of --plot, else png.
std::vector<PlotFormat> PlotFormats(const Settings& s) {
  const std::string ext = s.plot_file.empty() ? "" : fs::path(s.plot_file).extension().string().substr(1);
  if (s.plot_formats.empty()) return {ext.empty() ? PlotFormat::kPng : ParsePlotFormat(ext)};
  if (!ext.empty() && std::find(s.plot_formats.begin(), s.plot_formats.end(), ParsePlotFormat(ext)) ==
                          s.plot_formats.end())
    throw InputError("--plot " + s.plot_file + " is a ." + ext + " file but --plot-format does not include " + ext);
  return s.plot_formats;
}

}  // namespace

std::optional<PlotPlace> PlacePlot(const Settings& s, const std::string& out, bool main) {
  if (!s.plots) return std::nullopt;
  const std::string file = main && !s.plot_file.empty() ? s.plot_file : out;
  if (file.empty() || file == "-") return std::nullopt;
  const fs::path p(file);
  return PlotPlace{p.parent_path().string(), p.stem().string()};
}

void Outputs::Write() {
  if (!files_.has_plots() && settings_.plots && !settings_.plot_formats.empty())
    std::fprintf(stderr, "deb: note: no plot: the CSV goes to standard output; name the plot with --plot\n");
  const std::vector<PlotFormat> formats = files_.has_plots() ? PlotFormats(settings_) : std::vector<PlotFormat>{};
  written_ = files_.Write(formats, std::cout, "", settings_.rec.threads);
}

void PrintWritten(const Outputs& outputs, const std::string& out) {
  if (outputs.written().empty()) return;
  std::string line = "wrote ";
  for (std::size_t i = 0; i < outputs.written().size(); ++i) line += (i ? ", " : "") + outputs.written()[i];
  std::fprintf(out.empty() || out == "-" ? stderr : stdout, "%s\n", line.c_str());
}

std::string SourceName(const std::string& path) { return fs::path(path).filename().string(); }

SpectrumQuantity Quantity(bool asd) { return asd ? SpectrumQuantity::kAsd : SpectrumQuantity::kPsd; }

std::vector<std::string> Provenance(const std::string& what, const PsdEstimate& e, const std::string& source) {
  std::vector<std::string> lines = {what + " of " + source};
  for (const std::string& l : e.provenance.Describe()) lines.push_back(l);
  lines.push_back("interpolation: bins");  // read back as the estimate's bins (measured_spectrum.h)
  return lines;
}

}  // namespace deb::tools
