#include "deb/signal/recording.h"

#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "deb/core/error.h"
#include "deb/signal/spectral_estimate.h"
#include "signal_test_support.h"

namespace deb {
namespace {

namespace fs = std::filesystem;

// Two channels a, b = 0.5 a + noise, 1 kHz, 8192 samples.
TimeSeries TwoChannels(const std::string& unit) {
  Eigen::MatrixXd x(8192, 2);
  x.col(0) = test::WhiteNoise(8192, 1.0, 3);
  x.col(1) = 0.5 * x.col(0) + test::WhiteNoise(8192, 0.1, 4);
  return TimeSeries(1000.0, x, {"a", "b"}, unit);
}

RecordingSpectrumOptions Options() {
  RecordingSpectrumOptions o;
  o.welch.segment_length = 1024;
  return o;
}

TEST_CASE("a recording's spectrum is its Welch PSD scaled by the unit factor squared") {
  const TimeSeries one = TwoChannels("um/s").Select({"a"});
  RecordingSpectrumOptions o = Options();
  o.unit = "nm/s";
  const RecordingSpectrum r = SpectrumFromRecording(one, o);
  CHECK(r.unit == "nm/s");
  CHECK(r.channel_names == std::vector<std::string>{"a"});
  const std::shared_ptr<const MeasuredSpectrum> direct = ToMeasuredSpectrum(WelchPsd(one, o.welch));
  for (double f : {3.0, 50.0, 311.0})
    CHECK(r.spectrum->Psd(f)(0) == doctest::Approx(1e6 * direct->Psd(f)(0)).epsilon(1e-12));
  // Without a wanted unit the recording's is kept.
  CHECK(SpectrumFromRecording(one, Options()).unit == "um/s");
}

TEST_CASE("a multi-channel recording keeps its cross-spectra unless told not to") {
  const TimeSeries two = TwoChannels("m");
  const RecordingSpectrum full = SpectrumFromRecording(two, Options());
  CHECK_FALSE(full.spectrum->IsDiagonal());
  // |S_ab| / S_aa is the gain 0.5 of b on a, to the estimate's scatter.
  const Eigen::MatrixXcd s = full.spectrum->Csd(100.0);
  CHECK(std::abs(s(0, 1)) / std::real(s(0, 0)) == doctest::Approx(0.5).epsilon(0.1));
  RecordingSpectrumOptions none = Options();
  none.cross_spectra = false;
  CHECK(SpectrumFromRecording(two, none).spectrum->IsDiagonal());
}

TEST_CASE("median averaging of cross-spectra and units of another quantity are refused at their key paths") {
  RecordingSpectrumOptions o = Options();
  o.welch.averaging = Averaging::kMedian;
  o.averaging_key_path = "sources[0].spectrum.averaging";
  try {
    SpectrumFromRecording(TwoChannels("m"), o);
    FAIL("median cross-spectra must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "sources[0].spectrum.averaging");
    CHECK(e.message().find("median averaging does not give a positive semi-definite") == 0);
  }
  o = Options();
  o.unit = "m/s";
  o.unit_key_path = "sources[0].unit";
  try {
    SpectrumFromRecording(TwoChannels("m"), o);
    FAIL("m to m/s must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "sources[0].unit");
    CHECK(e.message() == "the file's unit 'm' and 'm/s' are not the same quantity");
  }
  o = Options();
  o.welch.segment_length = 1 << 14;
  o.key_path = "sources[0].spectrum";
  try {
    SpectrumFromRecording(TwoChannels("m"), o);
    FAIL("a segment longer than the recording must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "sources[0].spectrum");
  }
}

TEST_CASE("a recording is read from a CSV or raw floats and its columns selected") {
  const fs::path dir = fs::temp_directory_path() / ("deb_recording_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "r.csv");
    csv << "# unit: mm\nx, y\n1, 2\n3, 4\n5, 6\n";
    std::ofstream raw(dir / "r.raw", std::ios::binary);
    for (double v : {1.0, 2.0, 3.0, 4.0}) raw.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  RecordingSpec csv;
  csv.file = (dir / "r.csv").string();
  csv.rate_hz = 10.0;
  csv.columns = {"y"};
  const TimeSeries c = ReadRecording(csv);
  CHECK(c.channel_names() == std::vector<std::string>{"y"});
  CHECK(c.samples()(2, 0) == 6.0);
  CHECK(c.unit() == "mm");
  RecordingSpec raw;
  raw.file = (dir / "r.raw").string();
  raw.raw = RawSampleFormat::kFloat64;
  raw.rate_hz = 10.0;
  raw.file_channel_names = {"p", "q"};
  raw.unit = "N";
  const TimeSeries r = ReadRecording(raw);
  CHECK(r.channels() == 2);
  CHECK(r.samples()(1, 1) == 4.0);
  CHECK(r.unit() == "N");
  raw.file_channel_names.clear();
  raw.file_channels = 4;
  CHECK(ReadRecording(raw).channels() == 4);
  csv.columns = {"z"};
  CHECK_THROWS_WITH_AS(ReadRecording(csv), doctest::Contains("no channel 'z'"), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace deb
