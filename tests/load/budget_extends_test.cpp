// `extends: base.yaml`: a budget written as the changes to another. The
// merged budget equals the one written out in full; errors are located in
// the file that gave the key; relative data files stay with their file.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/sweep_yaml.h"
#include "tests/support/cli_harness.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using test::WriteFile;

const std::string kBudgets = std::string(DEB_SOURCE_DIR) + "/budgets/";

// A small budget: one flat source through a first-order low-pass.
const char* kBase = R"(name: base
grid: {type: log, min_hz: 0.1, max_hz: 100, points: 400}
sources:
  - {name: noise, unit: um/s, spectrum: {type: flat, level: 2}}
paths:
  - {name: lowpass, type: transfer_function, num: [1], den: [0.01, 1], input_unit: um/s, output_unit: um/s, outputs: [v]}
contributors:
  - {name: sensor, source: noise, path: lowpass}
outputs:
  - {name: velocity, signal: v, unit: um/s, rms_max: 10}
bands: [[0.1, 1], [1, 100]]
)";

std::string ErrorOf(const fs::path& file) {
  return test::InputErrorOf([&] { LoadBudgetFile(file.string()); });
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("maps merge key by key, lists and values replace, null removes: as the budget written in full") {
  const fs::path dir = test::TempDir("extends");
  fs::create_directories(dir / "lib");
  WriteFile(dir / "lib" / "base.yaml", kBase);
  WriteFile(dir / "derived.yaml", R"(extends: lib/base.yaml
name: derived
grid: {points: 800}
sources:
  - {name: noise, unit: um/s, spectrum: {type: flat, level: 8}}
bands: null
)");
  std::string full = kBase;
  full.replace(full.find("name: base"), 10, "name: derived");
  full.replace(full.find("points: 400"), 11, "points: 800");
  full.replace(full.find("level: 2"), 8, "level: 8");
  full.erase(full.find("bands:"));
  WriteFile(dir / "full.yaml", full);
  const Budget merged = LoadBudgetFile((dir / "derived.yaml").string());
  CHECK(merged.name == "derived");
  CHECK(merged.bands.empty());
  const BudgetResult a = Evaluate(merged);
  const BudgetResult b = Evaluate(LoadBudgetFile((dir / "full.yaml").string()));
  REQUIRE(a.grid.size() == b.grid.size());
  CHECK(a.outputs[0].variance == b.outputs[0].variance);  // the same budget: bitwise
  // A chain of two: the middle file's keys, then the last file's.
  WriteFile(dir / "last.yaml", "extends: derived.yaml\nname: last\noutputs:\n  - {name: velocity, signal: v, unit: nm/s}\n");
  const Budget last = LoadBudgetFile((dir / "last.yaml").string());
  CHECK(last.name == "last");
  CHECK(last.outputs[0].unit == "nm/s");
  CHECK(last.sources[0].name == "noise");
  CHECK(std::abs(Evaluate(last).outputs[0].variance / a.outputs[0].variance - 1e6) < 1e-6);
  // --set applies after the chain is merged; a sweep reads it too.
  CHECK(LoadBudgetFile((dir / "last.yaml").string(), {{"name", "again"}}).name == "again");
}

TEST_CASE("the thesis budget at h = 0, written as the changes to h = 210 mm, gives the thesis' figures") {
  // Table 5-4/5-5 at h = 0: sensor-noise RMS 11.2137 um/s (z velocity) and 1.8972 um (z position).
  const BudgetResult r = Evaluate(LoadBudgetFile(kBudgets + "nizamoglu2015_h0.yaml"));
  REQUIRE(r.outputs.size() >= 2);
  for (const auto& [output, expected] : {std::pair<std::size_t, double>{0, 11.2137}, {1, 1.8972}}) {
    const auto& contributors = r.outputs[output].contributors;
    bool found = false;
    for (const auto& c : contributors)
      if (c.name == "sensor_noise") {
        found = true;
        CHECK(std::abs(std::sqrt(c.variance) - expected) < 1e-4);
      }
    CHECK(found);
  }
}

TEST_CASE("errors are located in the file that gave the key; cycles, missing bases and deep chains are refused") {
  const fs::path dir = test::TempDir("extends_errors");
  WriteFile(dir / "base.yaml", kBase);
  WriteFile(dir / "bad_value.yaml", "extends: base.yaml\ngrid:\n  min_hz: -3\n");
  CHECK(Has(ErrorOf(dir / "bad_value.yaml"), "bad_value.yaml:3:11: grid.min_hz:"));
  std::string broken = kBase;
  broken.replace(broken.find("level: 2"), 8, "level: -2");
  WriteFile(dir / "broken_base.yaml", broken);
  WriteFile(dir / "uses_broken.yaml", "extends: broken_base.yaml\nname: fine\n");
  CHECK(Has(ErrorOf(dir / "uses_broken.yaml"), "broken_base.yaml:4:"));
  CHECK(Has(ErrorOf(dir / "uses_broken.yaml"), "sources[0].spectrum.level"));
  WriteFile(dir / "a.yaml", "extends: b.yaml\nname: a\n");
  WriteFile(dir / "b.yaml", "extends: a.yaml\nname: b\n");
  const std::string cycle = ErrorOf(dir / "a.yaml");
  CHECK(Has(cycle, "closes a cycle"));
  CHECK(Has(cycle, "a.yaml -> "));
  WriteFile(dir / "self.yaml", "extends: self.yaml\n");
  CHECK(Has(ErrorOf(dir / "self.yaml"), "closes a cycle"));
  WriteFile(dir / "missing.yaml", "extends: nothere.yaml\n");
  CHECK(Has(ErrorOf(dir / "missing.yaml"), "missing.yaml:1:10: extends:"));
  CHECK(Has(ErrorOf(dir / "missing.yaml"), "nothere.yaml"));
  WriteFile(dir / "list.yaml", "extends: [base.yaml]\n");
  CHECK(Has(ErrorOf(dir / "list.yaml"), "extends names one budget file"));
  WriteFile(dir / "not_map.yaml", "- 1\n- 2\n");
  WriteFile(dir / "on_list.yaml", "extends: not_map.yaml\n");
  CHECK(Has(ErrorOf(dir / "on_list.yaml"), "is not a YAML map"));
  // A chain of 20 files, each extending the next: more than 16 is refused.
  for (int i = 0; i < 20; ++i)
    WriteFile(dir / ("c" + std::to_string(i) + ".yaml"), "extends: c" + std::to_string(i + 1) + ".yaml\n");
  WriteFile(dir / "c20.yaml", kBase);
  CHECK(Has(ErrorOf(dir / "c0.yaml"), "more than 16 budget files"));
  CHECK(Has(ErrorOf(dir / "c10.yaml"), "(no error)"));
}

TEST_CASE("a base's relative data files are read from the base's directory") {
  const fs::path dir = test::TempDir("extends_data");
  fs::create_directories(dir / "stage");
  fs::copy_file(kBudgets + "measured_stage.yaml", dir / "stage" / "measured_stage.yaml");
  fs::copy_file(kBudgets + "measured_stage_frf.csv", dir / "stage" / "measured_stage_frf.csv");
  WriteFile(dir / "variant.yaml", "extends: stage/measured_stage.yaml\nname: variant\n");
  const BudgetResult a = Evaluate(LoadBudgetFile((dir / "variant.yaml").string()));
  const BudgetResult b = Evaluate(LoadBudgetFile(kBudgets + "measured_stage.yaml"));
  REQUIRE(a.outputs.size() == b.outputs.size());
  for (std::size_t o = 0; o < a.outputs.size(); ++o) CHECK(a.outputs[o].variance == b.outputs[o].variance);
}

}  // namespace deb
