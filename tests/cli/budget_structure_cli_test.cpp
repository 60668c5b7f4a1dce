// A full report (plots, report.pdf, index.html) of a budget that uses every
// structure feature at once: a contributor on named inputs of a MIMO path,
// tones, a channel breakdown, groups, and --set. The figures are checked
// elsewhere; here every writer must take them.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;

TEST_CASE("deb run writes the whole report of a budget with inputs, tones, a breakdown and groups") {
  const fs::path dir = deb::test::TempDir("structure_cli");
  deb::test::WriteFile(dir / "b.yaml", R"(name: structure
grid: {type: auto, min_hz: 0.5, max_hz: 500}
sources:
  - {name: force, unit: N, channels: [fx, fy], spectrum: {type: flat, level: 1.0e-4}}
  - {name: amplifier, unit: V, spectrum: {type: flat, level: 4.0e-6}}
  - name: hum
    unit: V
    spectrum: {type: tones, tones: [{f_hz: 50, rms: 1.0e-3}, {f_hz: 150, peak: 2.0e-4}]}
paths:
  - name: stage
    type: state_space
    A: [[0, 1], [-986.96044, -1.2566371]]
    B: [[0, 0, 0], [1, 0.5, 3]]
    C: [[1.0e6, 0]]
    D: [[0, 0, 0]]
    inputs: [dx, dy, n]
    input_units: [N, N, V]
    outputs: [x]
    output_unit: um
contributors:
  - {name: disturbance, source: force, path: stage, inputs: [dx, dy], breakdown: channels, group: environment}
  - {name: amplifier, source: amplifier, path: stage, inputs: [n], group: electronics/amplifier}
  - {name: hum, source: hum, path: stage, inputs: [n], group: electronics/amplifier}
outputs:
  - {name: position, signal: x, unit: um, rms_max: 1}
)");
  const auto r = deb::test::RunDeb("run \"" + (dir / "b.yaml").string() + "\" -q --format png,pdf --out \"" +
                                   (dir / "r").string() + "\" --set outputs[0].rms_max=2");
  REQUIRE(r.exit_code == 0);
  for (const char* f : {"summary.json", "index.html", "report.pdf", "report.md", "plots/position_cps.png"})
    CHECK_MESSAGE(fs::exists(dir / "r" / f), f);
  const auto j = nlohmann::json::parse(deb::test::ReadAll(dir / "r" / "summary.json"));
  const auto& o = j["outputs"][0];
  CHECK(o["requirement"]["rms_max"].get<double>() == 2.0);
  CHECK(o["contributors"][0]["inputs"].size() == 2);
  CHECK(o["contributors"][0]["breakdown"]["channels"].size() == 2);
  CHECK(o["contributors"][2]["tones"].size() == 2);
  CHECK(o["groups"].size() == 3);  // environment, electronics, electronics/amplifier
}
