// Internal to the `deb spectrum` command (spectrum_command.h): its options,
// and what its subcommands share: reading a recording with the command
// line's Welch settings, placing each plot beside the file it shows, and
// writing everything at once (report::OutputFiles).
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/report/figure/output_files.h"
#include "deb/report/figure/plot.h"
#include "deb/report/figure/report_options.h"
#include "deb/signal/spectral_estimate.h"
#include "deb/signal/time_series.h"
#include "deb/signal/welch.h"
#include "deb/spectra/spectrum_csv.h"
#include "tools/spectrum_command.h"

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

using Settings = SpectrumCommand::Options;

// The recording of the command line (--format, --rate, --columns, ...).
// @throws InputError as deb::ReadRecording.
TimeSeries ReadRecording(const RecordingOptions& r);
// The Welch settings of the command line.
WelchOptions Welch(const RecordingOptions& r);

// Where a plot goes: beside the file it shows, named after it.
struct PlotPlace {
  std::string directory, stem;
};

// The main plot goes to --plot if given, else beside the output file; a
// second plot (coherence) beside its own file. Output on standard output
// ("" or "-") has no plot unless --plot names one.
std::optional<PlotPlace> PlacePlot(const Settings& s, const std::string& out, bool main);

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

  // @throws WriteError as report::OutputFiles::Write; InputError for a
  //         --plot whose extension --plot-format leaves out.
  void Write();

 private:
  const Settings& settings_;
  report::OutputFiles files_;
  std::vector<std::string> written_;
};

// "wrote psd.csv, psd.plot.csv, psd.gp, psd.png": on standard output, or on
// standard error when the CSV itself went to standard output.
void PrintWritten(const Outputs& outputs, const std::string& out);

// The file name of `path`, as plot titles name their source.
std::string SourceName(const std::string& path);

SpectrumQuantity Quantity(bool asd);

// The header lines of an estimate's CSV: `what` of `source`, the Welch
// settings, and the interpolation of bins.
std::vector<std::string> Provenance(const std::string& what, const PsdEstimate& e, const std::string& source);

// The subcommands; each returns the exit code.
int RunWelch(const Settings& s);
int RunSelfNoise(const Settings& s);
int RunFrf(const Settings& s);
int RunBands(const Settings& s);
int RunConvert(const Settings& s);
int RunReference(const Settings& s);

}  // namespace deb::tools
