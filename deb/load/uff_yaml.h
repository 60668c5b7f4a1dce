// Internal: not part of the public API.
// YAML -> measured data from a universal file (datasets 58 and 58b,
// deb/formats/uff58_file.h), for the `file:` of a `type: frf` path and of a
// `type: measured` source when the file is one (by its content: the
// delimiter line -1, then a dataset number).
//
// A path takes the FRFs (function type 4) and transmissibilities (5) of the
// file: `responses:` and `references:` list DOFs NODE:DIRECTION ("1:+Z"),
// the path's outputs and inputs; entry (i, j) is the dataset with response
// i and reference j, which must be there exactly once. A list left out is
// every DOF of that side the file's FRFs have, in file order. The channel
// names are the DOFs as written, unless `outputs:` / `inputs:` rename them.
// Each entry's unit (record 9 over record 10) is converted to the path's
// output unit over its input unit, by a scale and up to two time
// derivatives or integrals (accelerance m/s^2/N to compliance um/N:
// 1e6 / (j 2 pi f)^2); an entry without a unit (NONE) is taken in the
// path's units. Without output_unit / input_unit the path takes the file's
// numerator and denominator units.
//
// A source takes PSDs (function type 9) and auto spectra (2) whose unit is a
// density: X^2/Hz (a PSD) or X/sqrt(Hz) (an ASD, squared); an auto spectrum
// in another unit (a power or RMS spectrum) is refused, since it is no
// density. `responses:` (DOFs) or `datasets:` (positions in the file, 1-based)
// choose them, one channel each; without either the file must hold exactly
// one. The values are one-sided, real and converted from X to the source's
// unit (a scale, or a time derivative or integral).
//
// Both: the abscissa must be in Hz (or unitless with the data type 18,
// frequency); points at 0 Hz and below are left out; the datasets taken
// must share their frequencies.
#pragma once

#include <memory>
#include <string>

#include "deb/budget/path.h"
#include "deb/budget/source.h"
#include "deb/load/yaml_reader.h"
#include "deb/signal/time_series.h"
#include "deb/spectra/spectrum.h"

namespace deb::load {

// The keys a universal file adds to a `type: frf` path and a measured source's spectrum.
inline constexpr const char* kUffPathKeys[] = {"responses", "references"};
inline constexpr const char* kUffSourceKeys[] = {"responses", "datasets"};  // a spectrum's and a recording's

// Fills p.system (zero gains of the right size), p.measured, names and units
// from the universal file at `path` (`node`: the path's entry).
void ParseUffFrfPath(const YamlNode& node, const std::string& path, Path& p);

// The measured spectrum of a source whose `spectrum:` (`spec`) names the
// universal file at `path`; sets s->unit, s->channel_names and notes.
std::shared_ptr<const Spectrum> ParseUffSpectrum(const YamlNode& node, const YamlNode& spec, const std::string& path,
                                                 Source* s);

// The recording of a `type: timeseries` source (`spec`) whose file is the
// universal file at `path`: its time responses (function type 1, real,
// evenly spaced, abscissa in time) chosen by `responses:` or `datasets:` as
// for a spectrum, one channel each (named by its DOF), sharing their time
// step, length and unit (records 9 over 10; "" when NONE).
TimeSeries ReadUffRecording(const YamlNode& spec, const std::string& path);

}  // namespace deb::load
