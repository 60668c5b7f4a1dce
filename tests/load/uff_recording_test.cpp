// Recordings from universal files (deb/load/uff_yaml.h, ReadUffRecording):
// a microphone's time response that test-rig software wrote (pyuff's
// sample, tests/data/uff, MIT licence beside it), as ASCII (58) and binary
// (58b), as a `type: timeseries` source, against the same samples given as
// a CSV recording; and the rules, each a located error.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "deb/core/error.h"
#include "deb/formats/uff58_file.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

const std::string kData = std::string(DEB_TEST_DATA_DIR) + "/uff/";

std::string Budget(const std::string& spectrum) {
  return R"(name: mic
grid: {type: log, min_hz: 20, max_hz: 20000, points: 400}
sources:
  - name: mic
    unit: mPa
    spectrum: )" + spectrum + R"(
paths:
  - {name: p, type: gain, gain: 1, inputs: [u], outputs: [y], input_unit: mPa, output_unit: mPa}
contributors:
  - {name: c, source: mic, path: p}
outputs:
  - {name: y, signal: y, unit: mPa}
)";
}

std::string ErrorOf(const std::string& text, const std::string& dir) {
  try {
    LoadBudgetText(text, "b.yaml", dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST_CASE("a time response from a universal file is the recording of a timeseries source, as its samples in CSV") {
  const std::vector<formats::Uff58Record> records = formats::ReadUff58(kData + "Sample_UFF58_ascii.uff");
  REQUIRE(records.size() == 1);
  const formats::Uff58Record& r = records[0];
  REQUIRE(r.function == formats::UffFunction::kTimeResponse);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("deb_uff_recording_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    // The same samples in a CSV recording, at the rate the file states, in Pa.
    std::ofstream csv(dir / "mic.csv");
    char line[64];
    std::snprintf(line, sizeof(line), "# rate_hz: %.17g\n# unit: Pa\n", 1.0 / r.abscissa_increment);
    csv << line << "mic\n";
    for (const auto& v : r.y) {
      std::snprintf(line, sizeof(line), "%.17g\n", v.real());
      csv << line;
    }
  }
  const std::string welch = ", segment_length: 4096}";
  const deb::Budget csv = LoadBudgetText(Budget("{type: timeseries, file: mic.csv" + welch), "b.yaml", dir.string());
  const deb::Budget ascii = LoadBudgetText(
      Budget("{type: timeseries, file: " + kData + "Sample_UFF58_ascii.uff" + welch), "b.yaml", dir.string());
  const deb::Budget binary = LoadBudgetText(
      Budget("{type: timeseries, file: " + kData + "Sample_UFF58b_bin.uff, responses: ['0:+X']" + welch), "b.yaml",
      dir.string());
  CHECK(ascii.sources[0].channel_names == std::vector<std::string>{"0:+X"});
  CHECK(ascii.sources[0].unit == "mPa");  // the file's Pa, converted
  double worst_ascii = 0.0, worst_binary = 0.0, peak = 0.0;
  for (double f = 20.0; f <= 20000.0; f *= 1.07) {
    const double c = csv.sources[0].spectrum->Psd(f)(0);
    peak = std::max(peak, c);
    worst_ascii = std::max(worst_ascii, std::abs(ascii.sources[0].spectrum->Psd(f)(0) - c) / c);
    worst_binary = std::max(worst_binary, std::abs(binary.sources[0].spectrum->Psd(f)(0) - c) / c);
  }
  MESSAGE("Welch PSD of the universal file against the CSV of its samples: ASCII " << worst_ascii << ", binary "
                                                                                  << worst_binary << " at worst");
  CHECK(peak > 0.0);
  // ASCII: the same numbers by two routes: 1e-12. Binary: the float32
  // samples the ASCII file prints to 7 digits (the readers' own test bounds
  // them by half a printed digit): 1e-5 of the PSD (measured 3.3e-6).
  CHECK(worst_ascii <= 1e-12);
  CHECK(worst_binary <= 1e-5);

  // The rules.
  const std::string file = "{type: timeseries, file: " + kData + "Sample_UFF58_ascii.uff";
  CHECK(test::Contains(ErrorOf(Budget(file + ", rate_hz: 100}"), dir.string()),
                       "sources[0].spectrum.rate_hz: not with a universal file, which gives its sample "
                       "rate (record 7)"));
  CHECK(test::Contains(ErrorOf(Budget(file + ", responses: ['1:+Z']}"), dir.string()),
                       "holds no time response of response 1:+Z; its time responses: #1"));
  CHECK(test::Contains(ErrorOf(Budget("{type: timeseries, file: " + kData + "sample_dataset58_psd.uff}"), dir.string()),
                       "sample_dataset58_psd.uff holds 0 time responses; choose with 'responses'"));
  CHECK(test::Contains(ErrorOf(Budget("{type: timeseries, file: mic.csv, datasets: [1]}"), dir.string()),
                       "sources[0].spectrum.datasets: 'datasets' chooses the datasets of a universal file (UFF 58)"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace deb
