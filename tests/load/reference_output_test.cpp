// Measured references of an output: converted to the output's unit, on the
// grid, compared band by band with the budget, never summed; against the
// closed form of a flat spectrum and of the budget itself.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"

namespace deb {
namespace {

std::string WithReference(const std::string& reference) {
  return R"(name: ref
grid: {type: auto, min_hz: 1, max_hz: 1000}
sources:
  - {name: noise, unit: nm, spectrum: {type: flat, level: 4}}
paths:
  - {name: g, type: gain, gain: [[1]], input_unit: nm, output_unit: nm, outputs: [x]}
contributors:
  - {name: c, source: noise, path: g}
outputs:
  - name: x
    unit: nm
    references:
)" + reference + "bands: [[1, 10], [10, 100], [100, 1000]]\n";
}

}  // namespace

TEST_CASE("a flat reference in another unit integrates to its closed form in the output's unit, and is not summed") {
  // 1e-5 um^2/Hz = 10 nm^2/Hz between 10 and 100 Hz: variance 900 nm^2; the budget is 4 nm^2/Hz over 1-1000 Hz.
  const BudgetResult r = Evaluate(LoadBudgetText(
      WithReference("      - {name: m, unit: um, spectrum: {type: flat, level: 1.0e-5, lo_hz: 10, hi_hz: 100}}\n"),
      "r.yaml"));
  const OutputResult& o = r.outputs[0];
  REQUIRE(o.references.size() == 1);
  const ReferenceResult& m = o.references[0];
  CHECK(std::abs(m.variance / 900.0 - 1.0) < 1e-9);
  CHECK(std::abs(o.variance / (4.0 * 999.0) - 1.0) < 1e-9);  // the budget alone
  REQUIRE(m.band_variance.size() == 3);
  CHECK(std::abs(*m.band_variance[0]) < 1e-9 * 900.0);  // the grid steps just either side of an edge
  CHECK(std::abs(*m.band_variance[1] / 900.0 - 1.0) < 1e-9);
  CHECK(std::abs(*m.band_variance[2]) < 1e-9 * 900.0);
}

TEST_CASE("a reference in velocity is integrated to the output's displacement; one outside the grid covers part of it") {
  // 1 (nm/s)^2/Hz of velocity is 1 / (2 pi f)^2 nm^2/Hz: over 1-1000 Hz, (1 - 1/1000) / (4 pi^2) nm^2.
  const BudgetResult r = Evaluate(LoadBudgetText(
      WithReference("      - {name: v, unit: nm/s, spectrum: {type: flat, level: 1}}\n"), "r.yaml"));
  CHECK(std::abs(r.outputs[0].references[0].variance / ((1.0 - 1e-3) / (4 * M_PI * M_PI)) - 1.0) < 1e-6);
}

TEST_CASE("the shipped wafer stage explains its measurement above 10 Hz and not below") {
  const BudgetResult r = Evaluate(LoadBudgetFile(std::string(DEB_SOURCE_DIR) + "/budgets/wafer_stage.yaml"));
  const OutputResult& o = r.outputs[0];
  REQUIRE(o.references.size() == 1);
  const ReferenceResult& m = o.references[0];
  // measured = budget x (1 + (2 Hz / f)^2), read between 226 points: 1-10 Hz well above, 10-100 Hz within 1 %.
  for (std::size_t b = 0; b < o.bands.size(); ++b) {
    if (!m.band_variance[b]) continue;
    const double ratio = std::sqrt(*m.band_variance[b] / o.bands[b].variance);
    if (o.bands[b].band.lo_hz == 1.0) CHECK(ratio > 1.3);
    if (o.bands[b].band.lo_hz == 10.0) CHECK(std::abs(ratio - 1.0) < 0.01);
  }
  CHECK_FALSE(m.band_variance[0].has_value());  // 0.1-1 Hz reaches below the measurement's 0.216 Hz
}

TEST_CASE("a reference in a unit that is not the output's quantity, or with several channels, is a located error") {
  try {
    LoadBudgetText(WithReference("      - {name: m, unit: N, spectrum: {type: flat, level: 1}}\n"), "r.yaml");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("r.yaml:13:") != std::string::npos);
    CHECK(std::string(e.what()).find("cannot convert 'N' to 'nm'") != std::string::npos);
  }
  CHECK_THROWS_AS(
      LoadBudgetText(WithReference("      - {name: m, unit: nm, channels: 2, spectrum: {type: flat, level: 1}}\n"),
                     "r.yaml"),
      InputError);
}

}  // namespace deb
