// Budget sources of `type: timeseries`: a recording estimated at load.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/signal/time_series_file.h"
#include "deb/signal/welch.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

const char* kBudget = R"(name: recorded
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - name: floor
    unit: um/s
    spectrum:
      type: timeseries
      file: floor.csv
      columns: [z]
      segment_length: 1024
      window: hann
paths:
  - {name: g, type: gain, gain: 1, input_unit: um/s, output_unit: um/s, outputs: [v]}
contributors:
  - {name: floor, source: floor, path: g}
outputs:
  - {name: velocity, signal: v, unit: um/s}
)";

// A directory with floor.csv: white noise in m/s on x, y, z at 400 Hz.
class RecordingDir {
 public:
  explicit RecordingDir(const std::string& header, int samples = 1 << 14)
      : dir_(std::filesystem::temp_directory_path() / ("deb_ts_budget_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    std::ofstream out(dir_ / "floor.csv");
    out << header << "x, y, z\n";
    std::mt19937_64 rng(3);
    std::normal_distribution<double> normal(0.0, 1e-6);
    for (int i = 0; i < samples; ++i) out << normal(rng) << ", " << normal(rng) << ", " << normal(rng) << "\n";
  }
  ~RecordingDir() { std::filesystem::remove_all(dir_); }
  std::string path() const { return dir_.string(); }
  std::string csv() const { return (dir_ / "floor.csv").string(); }

 private:
  std::filesystem::path dir_;
};

using test::Replace;

std::string ErrorOf(const std::string& text, const std::string& dir) {
  return test::InputErrorOf([&] { LoadBudgetText(text, "b.yaml", dir); });
}

TEST_CASE("a timeseries source is the Welch PSD of the selected column, scaled to the budget unit (rel 1e-12)") {
  const RecordingDir dir("# rate_hz: 400\n# unit: m/s\n");
  const Budget b = LoadBudgetText(kBudget, "b.yaml", dir.path());
  REQUIRE(b.sources.size() == 1);
  const Source& s = b.sources[0];
  CHECK(s.unit == "um/s");
  CHECK(s.channel_names == std::vector<std::string>{"z"});
  CHECK(s.spectrum->Describe().find("Welch estimate (hann, 1024 samples") != std::string::npos);
  WelchOptions o;
  o.segment_length = 1024;
  const PsdEstimate direct = WelchPsd(ReadTimeSeriesCsv(dir.csv()).Select({"z"}), o);
  for (int k : {3, 100, 511}) {
    CHECK(s.spectrum->Psd(direct.f_hz[static_cast<std::size_t>(k)])(0) ==
          doctest::Approx(1e12 * direct.psd(k, 0)).epsilon(1e-12));
  }
}

TEST_CASE("timeseries sources report a missing rate, too few samples, a bad column and raw files without a rate") {
  const RecordingDir norate("# unit: m/s\n");
  const std::string missing = ErrorOf(kBudget, norate.path());
  CHECK(missing.find("b.yaml:8:13: sources[0].spectrum.file: ") == 0);
  CHECK(missing.find("missing sample rate") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "columns: [z]", "columns: [z]\n      rate_hz: 400"), norate.path()) == "(no error)");

  const RecordingDir shorter("# rate_hz: 400\n# unit: m/s\n", 1000);
  CHECK(ErrorOf(kBudget, shorter.path()).find("too few samples: 1000 samples are fewer than one segment of 1024") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "columns: [z]", "columns: [w]"), shorter.path()).find("no channel 'w'") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "file: floor.csv", "file: floor.csv\n      format: float32\n      file_channels: 3"),
                shorter.path())
            .find("missing 'rate_hz'") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "window: hann", "window: kaiser"), shorter.path()).find("allowed: rectangular") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "window: hann", "nfft: 10"), shorter.path()).find("nfft") != std::string::npos);
  const std::string short_segment = ErrorOf(Replace(kBudget, "segment_length: 1024", "segment_length: 8"), shorter.path());
  CHECK(short_segment.find("b.yaml:10:23: sources[0].spectrum.segment_length: segment_length must be >= 16") == 0);
}


TEST_CASE("a recorded tone is not stepped over by the automatic grid") {
  // A sine of amplitude 1 um/s at 37.3 Hz (variance 0.5 (um/s)^2) plus white
  // noise of variance 1e-6, 400 Hz, Hann segments of 1024 samples. The Welch
  // bins carry the tone's variance in a few bins 0.39 Hz apart; a grid that
  // does not hold every bin (the 200-per-decade base grid is 0.43 Hz apart
  // there) misses most of the peak: RMS 0.42 instead of 0.71 before every
  // bin edge became a grid breakpoint.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("deb_ts_tone_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "floor.csv");
    out << "# rate_hz: 400\n# unit: um/s\nz\n";
    std::mt19937_64 rng(5);
    std::normal_distribution<double> normal(0.0, 1e-3);
    for (int i = 0; i < 1 << 15; ++i) out << std::sin(2.0 * M_PI * 37.3 * i / 400.0) + normal(rng) << "\n";
  }
  std::string text = Replace(kBudget, "grid: {type: log, min_hz: 1, max_hz: 100, points: 50}",
                             "grid: {type: auto, min_hz: 1, max_hz: 100}");
  const BudgetResult r = Evaluate(LoadBudgetText(text, "b.yaml", dir.string()));
  std::filesystem::remove_all(dir);
  const double rms = r.outputs[0].rms();
  MESSAGE("tone RMS through the budget: " << rms << " (true 0.7071)");
  // The bins are held constant over their width, so the budget integrates
  // Parseval's sum of the estimate: the tone's 0.5 (um/s)^2 (log-log
  // interpolation between the bins of the Hann peak gave 0.62).
  CHECK(rms == doctest::Approx(std::sqrt(0.5 + 1e-6 * 99.0 / 200.0)).epsilon(2e-3));
}

}  // namespace
}  // namespace deb
