#include "tools/spectrum_command.h"

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "deb/signal/welch.h"
#include "deb/signal/window.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/spectra/third_octave.h"
#include "tools/spectrum_subcommands.h"

namespace deb::tools {

namespace {

namespace fs = std::filesystem;

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
