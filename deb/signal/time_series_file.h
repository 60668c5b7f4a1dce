// Reads recordings into a TimeSeries: text (CSV) with a time column or a
// declared sample rate, and raw little-endian float32/float64 (what data
// acquisition systems dump), channels interleaved sample by sample.
//
// Text format:
//   # rate_hz: 1000      sample rate (optional when there is a time column)
//   # unit: m/s^2        unit of every channel (optional)
//   t, x, y, z           optional header; a first column named t, time or
//   0.000, 1e-3, ...     time_s holds time stamps in seconds
// Cells are separated by commas or whitespace; '#' starts a comment. Time
// stamps must increase and lie on a uniform grid: |t_i - t_0 - i dt| <= 0.01 dt
// with dt = (t_last - t_0)/(n - 1) (rounding of printed stamps passes; a gap
// or a change of rate does not). Errors quote file:line:column, the text and
// the rule broken.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/signal/time_series.h"

namespace deb {

struct TimeSeriesCsvOptions {
  // Sample rate when the file has none; if the file declares one too, or has
  // a time column, they must agree (relative 1e-6 for '# rate_hz:', the time
  // grid rule above for stamps).
  std::optional<double> rate_hz;
  // Unit when the file has no '# unit:'; if both are given they must be equal.
  std::string unit;
};

// @throws InputError if the file cannot be read, a cell is not a finite
//   number, rows differ in length, no rate can be found ("missing sample
//   rate"), time stamps are not uniform or not increasing, or rates disagree.
TimeSeries ReadTimeSeriesCsv(const std::string& path, const TimeSeriesCsvOptions& options = {});

enum class RawSampleFormat { kFloat32, kFloat64 };
inline constexpr EnumName<RawSampleFormat> kRawSampleFormatNames[] = {
    {RawSampleFormat::kFloat32, "float32"}, {RawSampleFormat::kFloat64, "float64"},
    {RawSampleFormat::kFloat32, "f32", kAlias}, {RawSampleFormat::kFloat64, "f64", kAlias}};
constexpr EnumNames<RawSampleFormat> NamesOf(RawSampleFormat) { return kRawSampleFormatNames; }
// @throws InputError listing the allowed values.
inline RawSampleFormat ParseRawSampleFormat(const std::string& text) {
  return ParseEnum<RawSampleFormat>(text, "raw sample format");
}

struct RawTimeSeriesOptions {
  RawSampleFormat format = RawSampleFormat::kFloat64;
  int channels = 1;
  double rate_hz = 0.0;  // required: a raw file carries no rate
  std::vector<std::string> channel_names;  // empty: ch1, ch2, ...
  std::string unit;
};

// Little-endian samples, frame after frame of `channels` values.
// @throws InputError if the file cannot be read, its size is not a whole
//   number of frames, the rate is missing (0) or invalid, channels < 1, or a
//   sample is not finite (TimeSeries).
TimeSeries ReadRawTimeSeries(const std::string& path, const RawTimeSeriesOptions& options);

}  // namespace deb
