// deb/budget/budget_outline.h: the outline keeps what a report says of a
// budget (names, units, channels, contributors, weightings) and no model;
// Evaluate puts it into the result.
#include "deb/budget/budget_outline.h"

#include <doctest/doctest.h>

#include <memory>
#include <string>

#include "deb/budget/engine.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

Budget Weighted() {
  Budget b;
  b.name = "outlined";
  b.description = "one source, one path, a weighted output";
  b.grid.kind = GridKind::kLog;
  b.bands = {{1.0, 10.0}, {10.0, 100.0}};
  Source s;
  s.name = "floor";
  s.description = "a white force";
  s.unit = "N";
  s.channel_names = {"u"};
  s.spectrum = std::make_shared<FlatSpectrum>(1e-3);
  b.sources = {s};
  Path p;
  p.name = "plant";
  p.system = ToStateSpace(TransferFunction({100.0}, {1.0, 2.0, 100.0}));
  p.input_names = {"u"};
  p.output_names = {"y"};
  p.input_units = {"N"};
  p.output_units = {"um"};
  b.paths = {p};
  b.contributors = {{"c", "floor", "plant", ExactVariance::kOff, {}, "stage", true}};
  Output o;
  o.name = "y";
  o.signal = "y";
  o.unit = "um";
  Weighting w;
  w.unit = "1";
  w.description = "a unit gain";
  o.weighting = w;
  b.outputs = {o};
  return b;
}

TEST_CASE("the outline of a budget keeps its names, units, channels and contributors") {
  const Budget budget = Weighted();
  const BudgetOutline outline = OutlineOf(budget);
  CHECK(outline.name == "outlined");
  CHECK(outline.description == budget.description);
  CHECK(outline.grid_kind == GridKind::kLog);
  REQUIRE(outline.bands.size() == 2);
  CHECK(outline.bands[1].hi_hz == 100.0);
  REQUIRE(outline.sources.size() == 1);
  CHECK(outline.sources[0].unit == "N");
  CHECK(outline.sources[0].channels == std::vector<std::string>{"u"});
  REQUIRE(outline.contributors.size() == 1);
  CHECK(outline.contributors[0].group == "stage");
  CHECK(outline.contributors[0].breakdown_channels);
  CHECK(&outline.SourceOf(outline.contributors[0]) == &outline.sources[0]);
  REQUIRE(outline.outputs.size() == 1);
  REQUIRE(outline.outputs[0].weighting.has_value());
  CHECK(outline.outputs[0].weighting->description == "a unit gain");
}

TEST_CASE("Evaluate puts the budget's outline into the result") {
  const BudgetResult result = Evaluate(Weighted());
  CHECK(result.outline.name == "outlined");
  REQUIRE(result.outline.outputs.size() == result.outputs.size());
  REQUIRE(result.outline.contributors.size() == result.outputs[0].contributors.size());
  CHECK(result.outline.contributors[0].name == result.outputs[0].contributors[0].name);
}

}  // namespace
}  // namespace deb
