// Fuzzes the recording readers: the input, written to a private temp file,
// is read as a CSV recording and as raw float64 and float32 samples with 1
// to 3 interleaved channels at a fixed rate.
#include "deb/signal/time_series_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("recording", data, size);
  deb_fuzz::ExpectOnlyInputError("ReadTimeSeriesCsv", [&] { deb::ReadTimeSeriesCsv(path); });
  for (const deb::RawSampleFormat format : {deb::RawSampleFormat::kFloat64, deb::RawSampleFormat::kFloat32}) {
    for (int channels = 1; channels <= 3; ++channels) {
      deb::RawTimeSeriesOptions options;
      options.format = format;
      options.channels = channels;
      options.rate_hz = 1000.0;
      deb_fuzz::ExpectOnlyInputError("ReadRawTimeSeries", [&] { deb::ReadRawTimeSeries(path, options); });
    }
  }
  return 0;
}
