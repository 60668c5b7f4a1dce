// `deb spectrum ...`: measured-data tools on the command line. Welch spectra
// of recordings, third-octave band RMS and VC/ISO classification, unit and
// PSD/ASD conversion, sensor self-noise, and Peterson's reference models.
// Every command writes a spectrum CSV that `type: measured` budget sources
// read back (deb/spectra/spectrum_csv.h), and a plot of it beside the CSV
// (deb/report/measurement/measurement_plots.h, plot_files.h) unless --no-plots.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class SpectrumCommand {
 public:
  SpectrumCommand();
  ~SpectrumCommand();
  SpectrumCommand(const SpectrumCommand&) = delete;
  SpectrumCommand& operator=(const SpectrumCommand&) = delete;

  // Registers `spectrum` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for bad input, WriteError for output that cannot be written.
  int Run() const;

  struct Options;  // the command line's values (spectrum_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
