#include "deb/signal/time_series_file.h"

#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

// A file in the temporary directory, removed at the end of the test.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& content)
      : path_((std::filesystem::temp_directory_path() / ("deb_ts_" + std::to_string(::getpid()) + "_" + name)).string()) {
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

TEST_CASE("a CSV with '# rate_hz:' and a header reads channels, names, unit and rate") {
  const TempFile f("rate.csv", "# recorded on the floor\n# rate_hz: 200\n# unit: m/s^2\nx, z\n1, 2\n3, 4\n5, 6\n");
  const TimeSeries s = ReadTimeSeriesCsv(f.path());
  CHECK(s.rate_hz() == 200.0);
  CHECK(s.unit() == "m/s^2");
  CHECK(s.channel_names() == std::vector<std::string>{"x", "z"});
  REQUIRE(s.size() == 3);
  CHECK(s.samples()(2, 1) == 6.0);
  CHECK(s.Select({"z"}).samples().col(0).sum() == 12.0);
  CHECK(InputErrorText([&] { s.ChannelIndex("y"); }).find("no channel 'y' (channels: x, z)") != std::string::npos);
}

TEST_CASE("a time column gives the rate; printed stamps rounded to 1e-4 of a step pass") {
  std::string text = "time, geo\n";
  for (int i = 0; i < 100; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.6f, %d\n", i / 3000.0, i);  // dt = 333.33 us, printed to 1 us
    text += line;
  }
  const TempFile f("time.csv", text);
  const TimeSeries s = ReadTimeSeriesCsv(f.path());
  CHECK(s.rate_hz() == doctest::Approx(3000.0).epsilon(1e-4));
  CHECK(s.channels() == 1);
  CHECK(s.channel_names().front() == "geo");
}

TEST_CASE("bad input: missing rate, non-uniform time stamps, NaN cell, ragged row, rates that disagree") {
  const TempFile none("none.csv", "x\n1\n2\n3\n");
  const std::string missing = InputErrorText([&] { ReadTimeSeriesCsv(none.path()); });
  CHECK(missing.find("missing sample rate") != std::string::npos);
  CHECK(ReadTimeSeriesCsv(none.path(), {100.0, ""}).rate_hz() == 100.0);

  const TempFile gap("gap.csv", "t, x\n0, 1\n0.01, 2\n0.02, 3\n0.04, 4\n0.05, 5\n");
  const std::string uneven = InputErrorText([&] { ReadTimeSeriesCsv(gap.path()); });
  CHECK(uneven.find("gap.csv:3:1: non-uniform time stamps: time 0.01 s is off the uniform grid t0 + i dt = 0.0125 s") != std::string::npos);

  const TempFile back("back.csv", "t, x\n0, 1\n0.01, 2\n0.005, 3\n");
  CHECK(InputErrorText([&] { ReadTimeSeriesCsv(back.path()); }).find("time stamps must increase") != std::string::npos);

  const TempFile nan("nan.csv", "# rate_hz: 10\nx, y\n1, 2\n3, nan\n");
  const std::string nan_text = InputErrorText([&] { ReadTimeSeriesCsv(nan.path()); });
  CHECK(nan_text.find("nan.csv:4:4: channel 'y': 'nan' is not finite") != std::string::npos);

  const TempFile ragged("ragged.csv", "# rate_hz: 10\n1, 2\n3\n");
  CHECK(InputErrorText([&] { ReadTimeSeriesCsv(ragged.path()); }).find("ragged.csv:3:2: row has 1 cells; expected 2") !=
        std::string::npos);

  const TempFile rated("rated.csv", "# rate_hz: 10\n1\n2\n");
  CHECK(InputErrorText([&] { ReadTimeSeriesCsv(rated.path(), {20.0, ""}); }).find("they must agree") != std::string::npos);
  CHECK(InputErrorText([&] { ReadTimeSeriesCsv("/nonexistent/x.csv"); }).find("cannot open") != std::string::npos);
}

TEST_CASE("raw little-endian float32 and float64 files read frame by frame; a partial frame is an error") {
  const float f32[] = {1.5f, -2.0f, 3.0f, 4.25f, 5.0f, 6.0f};
  std::string bytes32(reinterpret_cast<const char*>(f32), sizeof f32);  // this machine is little-endian
  const TempFile a("a.f32", bytes32);
  RawTimeSeriesOptions o;
  o.format = ParseRawSampleFormat("f32");
  o.channels = 2;
  o.rate_hz = 50.0;
  o.channel_names = {"n", "e"};
  const TimeSeries s = ReadRawTimeSeries(a.path(), o);
  REQUIRE(s.size() == 3);
  CHECK(s.samples()(1, 1) == 4.25);
  CHECK(s.samples()(2, 0) == 5.0);

  const double f64[] = {0.1, 0.2, 0.3};
  const TempFile b("b.f64", std::string(reinterpret_cast<const char*>(f64), sizeof f64));
  RawTimeSeriesOptions o64;
  o64.rate_hz = 10.0;
  CHECK(ReadRawTimeSeries(b.path(), o64).samples()(2, 0) == 0.3);
  o64.channels = 2;
  CHECK(InputErrorText([&] { ReadRawTimeSeries(b.path(), o64); }).find("24 bytes is not a whole number of frames") !=
        std::string::npos);
  o64.rate_hz = 0.0;
  CHECK(InputErrorText([&] { ReadRawTimeSeries(b.path(), o64); }).find("missing sample rate") != std::string::npos);

  const double with_nan[] = {0.1, std::nan(""), 0.3};
  const TempFile c("c.f64", std::string(reinterpret_cast<const char*>(with_nan), sizeof with_nan));
  RawTimeSeriesOptions oc;
  oc.rate_hz = 1.0;
  CHECK(InputErrorText([&] { ReadRawTimeSeries(c.path(), oc); }).find("sample 1 (t = 1 s) is nan") != std::string::npos);
  CHECK(InputErrorText([] { ParseRawSampleFormat("int16"); }).find("allowed: float32, float64") != std::string::npos);
}

}  // namespace
}  // namespace deb
