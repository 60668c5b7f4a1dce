// A recording as a budget source: where it is and how to read it
// (RecordingSpec, ReadRecording: a CSV or raw little-endian floats,
// time_series_file.h), and its Welch estimate as a measured spectrum
// (SpectrumFromRecording): one PSD per channel, or the cross-spectral matrix
// that keeps the channels' coherence and phase, in the wanted unit.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/extrapolation.h"
#include "deb/signal/time_series.h"
#include "deb/signal/time_series_file.h"
#include "deb/signal/welch.h"
#include "deb/spectra/spectrum.h"

namespace deb {

struct RecordingSpec {
  std::string file;
  std::optional<RawSampleFormat> raw;  // nullopt: a CSV
  std::optional<double> rate_hz;       // required for raw files; CSV: when the file has none
  // Raw files: the channel names, or (when empty) their count.
  std::vector<std::string> file_channel_names;
  int file_channels = 1;
  std::vector<std::string> columns;  // the channels kept, in this order; empty: all
  std::string unit;                  // of the samples when the file gives none ('# unit:')
};

// @throws InputError as ReadTimeSeriesCsv / ReadRawTimeSeries, or for a
//   column the recording does not have.
TimeSeries ReadRecording(const RecordingSpec& spec);

struct RecordingSpectrumOptions {
  WelchOptions welch;
  // A multi-channel recording keeps its Welch cross-spectral matrix (true) or
  // only the auto-PSDs, its channels then independent.
  bool cross_spectra = true;
  Extrapolation extrapolation = Extrapolation::kError;
  std::string unit;  // the spectrum's unit; empty: the recording's
  // Where the caller described the estimate, the recording's file, the
  // averaging and the unit, for errors (empty: none).
  std::string key_path, file_key_path, averaging_key_path, unit_key_path;
};

struct RecordingSpectrum {
  std::shared_ptr<const Spectrum> spectrum;  // one-sided
  std::vector<std::string> channel_names;    // the recording's
  std::string unit;                          // options.unit, else the recording's ("" if neither has one)
};

// The one-sided Welch PSD (one channel, or cross_spectra false) or
// cross-spectral matrix of `series`, scaled by s^2 from the recording's unit
// to options.unit (a recording without a unit is taken as in options.unit).
// @throws InputError for median averaging with cross-spectra (not positive
//   semi-definite), a Welch error (welch.h), or units that differ by more
//   than a scale.
RecordingSpectrum SpectrumFromRecording(const TimeSeries& series, const RecordingSpectrumOptions& options);

}  // namespace deb
