// `deb spectrum ...`: measured-data tools on the command line. Welch spectra
// of recordings, third-octave band RMS and VC/ISO classification, unit and
// PSD/ASD conversion, sensor self-noise, and Peterson's reference models.
// Every command writes a spectrum CSV that `type: measured` budget sources
// read back (deb/spectra/spectrum_csv.h), and a plot of it beside the CSV
// (deb/report/measurement_plots.h, plot_files.h) unless --no-plots.
#pragma once

#include <CLI/CLI.hpp>

namespace deb::tools {

// Registers `spectrum` and its subcommands on app.
CLI::App* AddSpectrumCommand(CLI::App& app);

// Runs the chosen subcommand of `spectrum` (after parsing).
// @throws InputError for bad input, an output that cannot be written, or a
//   missing or failing gnuplot; nothing is written then.
int RunSpectrumCommand(const CLI::App& spectrum);

}  // namespace deb::tools
