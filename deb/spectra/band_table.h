// A table of one-third-octave band RMS values: what `deb spectrum bands`
// writes and `deb spectrum convert --from-bands` reads, so that the two
// chain. One row per band:
//
//   # unit: um/s                       unit of the RMS values (optional)
//   centre_hz, lo_hz, hi_hz, points, x, x_class, y, y_class
//   1, 0.89, 1.12, 3, 0.52, VC-D, 0.48, VC-D
//
// The first column is the band's centre frequency; columns named lo_hz,
// hi_hz, points or ending in _class (the verdicts of bands) are read past;
// every other column is one channel's band RMS. A table written by hand may
// be just centre_hz and RMS columns, with or without the header row. Errors
// quote file:line:column.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "deb/spectra/building_criteria.h"
#include "deb/spectra/third_octave.h"

namespace deb {

struct BandTable {
  std::string path;
  std::vector<double> centre_hz;           // > 0, strictly increasing
  std::vector<std::string> channel_names;  // from the header row, else "ch1", ...
  Eigen::MatrixXd rms;                     // rows = bands, cols = channels; >= 0
  std::optional<std::string> unit;         // from "# unit:"
};

// True for a column a band table carries beside the channels (lo_hz, hi_hz,
// points, <channel>_class).
bool IsBandTableExtraColumn(const std::string& name);

// @throws InputError at file:line:column for a cell that is not a number in a
//   channel column, a centre <= 0 or not increasing, a negative RMS, fewer than
//   one channel or one row, a '# quantity:' or '# sides:' line (band RMS has neither).
BandTable ReadBandTable(const std::string& path);
BandTable ParseBandTable(const std::string& text, const std::string& name);

// The table of `classes` (ClassifySpectrum: every channel on the same
// bands), as `deb spectrum bands` writes it: each comment as a '#' line,
// then '# unit:' unless `unit` is empty, the header row, and a row per band
// with its centre, edges, points and per channel the RMS (10 significant
// digits) and, when the channels were classified, the best criterion met
// ("none" if none, "-" for a band not assessed).
std::string BandTableText(const std::vector<std::string>& comments, const std::string& unit,
                          const std::vector<std::string>& channel_names, const SpectrumClasses& classes);

// The PSD constant in each band whose band integral is the table's RMS
// (BandRmsToPsd), per channel; the bands are those of `series` nearest the
// table's centres.
// @throws InputError as ThirdOctaveBandNear and BandRmsToPsd.
struct BandTablePsd {
  std::vector<double> f_hz;
  Eigen::MatrixXd psd;  // rows f_hz, one column per channel of the table
};
BandTablePsd PsdOfBandTable(const BandTable& table, ThirdOctaveSeries series);

}  // namespace deb
