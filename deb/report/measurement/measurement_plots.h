// Internal: not part of the public API.
// Plots of measured data, one per `deb spectrum` command, in the style of a
// budget report: log frequency in Hz, the unit on the y axis, channels in
// the contributor colours (plot_style.h), the key beside the plot. Each
// function returns the plot as data and script (plot.h); its script reads
// StandaloneDataFile(name) (plot_files.h), so that the files stand beside
// the CSV the command wrote. `source` names the input in the title, e.g.
// the recording's file name. The spectra plots throw InputError if fewer
// than 2 frequencies lie above 0 Hz (a log axis needs two).
#pragma once

#include <string>
#include <vector>

#include "deb/report/figure/plot.h"
#include "deb/signal/frf_estimate.h"
#include "deb/signal/self_noise.h"
#include "deb/signal/spectral_estimate.h"
#include "deb/spectra/building_criteria.h"
#include "deb/spectra/peterson_noise_model.h"

namespace deb::report {

// Welch PSD of every channel (log-log). With `bounds`, each channel's
// chi-square confidence interval is shaded. The title states window,
// segment, overlap, averages, resolution and sample rate.
Plot WelchPsdPlot(const PsdEstimate& estimate, const std::string& source, bool bounds, const std::string& name);

// Magnitude-squared coherence of every channel pair (linear 0..1, log f),
// with the level a zero true coherence stays under at the estimate's
// confidence: 1 - (1 - p)^(1 / (n - 1)), n = nu / 2 independent averages
// (Carter, Knapp & Nuttall 1973). DEB_DEMANDs at least two channels.
Plot CoherencePlot(const CsdEstimate& csd, const std::string& source, const std::string& name);

// A frequency response estimate: |H1| of every output (log-log, in `unit`,
// "output unit/input unit", "" when not known) above its coherence gamma^2
// (linear, 0..1), which says where the estimate can be trusted.
Plot FrfPlot(const FrfEstimate& estimate, const std::string& unit, const std::string& source, const std::string& name);

// Each sensor's PSD (solid) and its self-noise estimate (dashed, darker).
// DEB_DEMANDs the sensors and the noise on the same bins and channels.
Plot SelfNoisePlot(const PsdEstimate& sensors, const SelfNoiseEstimate& noise, const std::string& source,
                   const std::string& name);

// A spectrum as `deb spectrum convert` writes it: one-sided PSD per channel
// (rows f_hz, columns channels) in `unit` ("" undeclared), drawn as an ASD
// when `asd`. `title` says what was converted.
Plot SpectrumTablePlot(const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                       const std::vector<std::string>& channel_names, const std::string& unit, bool asd,
                       const std::string& title, const std::string& name);

// Peterson's NLNM and NHNM on f_hz (within 1e-5..10 Hz) in `unit`, PSD or
// ASD: the model written in black, the other in grey for context.
// @throws InputError if `unit` is not a displacement, velocity or acceleration.
Plot PetersonPlot(PetersonModel written, const std::vector<double>& f_hz, const std::string& unit, bool asd,
                  const std::string& name);

// One-third-octave band RMS of every channel as steps across each band,
// a point at each centre (open where a band holds fewer than 5 spectral
// lines). With `verdicts` (one per channel, from Classify with `options`),
// the criteria as horizontal lines over the bands they cover, named on the
// right axis, the overall class of each channel solid and red, the others
// dashed grey; the limiting band ringed; the title states class and
// limiting band. `unit` is that of the band RMS (um/s when classified).
Plot BandClassPlot(const std::vector<std::string>& channel_names, const std::vector<std::vector<BandRms>>& bands,
                   const std::vector<Classification>& verdicts, const ClassifyOptions& options,
                   const std::string& unit, const std::string& source, const std::string& name);

}  // namespace deb::report
