// --set KEY.PATH=VALUE: the key-path editor and LoadBudgetFile with
// overrides, checked against the same budgets changed by other routes
// (a sweep variant, the closed form of a flat source's level).
#include <doctest/doctest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "deb/budget/engine.h"
#include "deb/budget/sweep.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/key_path.h"
#include "deb/load/sweep_yaml.h"
#include "tests/support/file_bytes.h"

namespace deb {
namespace {

const std::string kIsolator = std::string(DEB_SOURCE_DIR) + "/budgets/single_axis_isolator.yaml";
const std::string kThesisSweep = std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_sweep.yaml";

std::string ErrorOf(const std::string& file, const std::vector<BudgetOverride>& overrides) {
  try {
    LoadBudgetFile(file, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

bool Contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("an override is KEY.PATH=VALUE split at the first '='; malformed ones are refused") {
  const BudgetOverride o = ParseBudgetOverride("sources[0].description=a=b");
  CHECK(o.key_path == "sources[0].description");
  CHECK(o.value == "a=b");
  CHECK_THROWS_AS(ParseBudgetOverride("sources[0].level"), InputError);  // no '='
  CHECK_THROWS_AS(ParseBudgetOverride("=2"), InputError);
  CHECK_THROWS_AS(ParseBudgetOverride("grid.points= "), InputError);
  CHECK_THROWS_AS(ParseBudgetOverride("sources[x].level=2"), InputError);
  CHECK_THROWS_AS(ParseBudgetOverride("sources..level=2"), InputError);
}

TEST_CASE("the key-path editor replaces, sets and scales what the path reaches, an alias once") {
  YAML::Node doc = YAML::Load("a: {b: [1, 2, 3], c: &x {v: 2}, d: *x}\nlist: [{k: 1}, {k: 2}]\n");
  CHECK(load::ScaleNumbersAt(doc, load::ParseKeyPath("a.b"), [](double x) { return 10 * x; }).empty());
  CHECK(doc["a"]["b"][2].as<double>() == 30.0);
  // c and d are one node: scaled once, not twice.
  CHECK(load::ScaleNumbersAt(doc, load::ParseKeyPath("a.c.v"), [](double x) { return 3 * x; }).empty());
  CHECK(load::ScaleNumbersAt(doc, load::ParseKeyPath("a.d.v"), [](double x) { return x; }).empty());
  CHECK(doc["a"]["c"]["v"].as<double>() == 6.0);
  CHECK(load::SetTextAt(doc, load::ParseKeyPath("list[*].k"), "seven").empty());
  CHECK(doc["list"][1]["k"].as<std::string>() == "seven");
  CHECK(load::ReplaceAt(doc, load::ParseKeyPath("list[0]"), YAML::Load("{k: 5, extra: [1]}")).empty());
  CHECK(doc["list"][0]["extra"][0].as<int>() == 1);
  CHECK(doc["list"][1]["k"].as<std::string>() == "seven");
  // What a path cannot reach is said, with the nearest key.
  CHECK(Contains(load::ReplaceAt(doc, load::ParseKeyPath("a.cc"), YAML::Load("1")), "did you mean 'c'"));
  CHECK(Contains(load::ReplaceAt(doc, load::ParseKeyPath("list[5]"), YAML::Load("1")), "list has 2 element(s), so no [5]"));
  CHECK(Contains(load::ReplaceAt(doc, load::ParseKeyPath("a.b.c"), YAML::Load("1")), "a.b is not a map"));
  CHECK(Contains(load::SetTextAt(doc, load::ParseKeyPath("a.b"), "x"), "a.b is not a single value"));
}

TEST_CASE("--set of a flat source's level scales its contributor's variance by the ratio of levels") {
  // geophone_noise: flat ASD 0.01; as ASD 0.03 its variance is 9 times larger, the other contributor unchanged.
  const BudgetResult nominal = Evaluate(LoadBudgetFile(kIsolator));
  const BudgetResult changed = Evaluate(LoadBudgetFile(kIsolator, {{"sources[1].spectrum.level", "0.03"}}));
  REQUIRE(nominal.outputs.size() == changed.outputs.size());
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const auto& a = nominal.outputs[o].contributors;
    const auto& b = changed.outputs[o].contributors;
    REQUIRE(a.size() == b.size());
    for (std::size_t c = 0; c < a.size(); ++c) {
      const double expected = a[c].source == "geophone_noise" ? 9.0 : 1.0;
      CHECK(std::abs(b[c].variance / a[c].variance - expected) < 1e-12);
    }
  }
  // A whole map as the value, in YAML flow syntax: the same source as a PSD of 0.03^2.
  const BudgetResult as_map = Evaluate(LoadBudgetFile(
      kIsolator, {{"sources[1].spectrum", "{type: flat, quantity: psd, level: 9.0e-4}"}}));
  CHECK(std::abs(as_map.outputs[0].variance / changed.outputs[0].variance - 1.0) < 1e-12);
}

TEST_CASE("later overrides win: the same key set twice, and a key inside a value an earlier override set") {
  // geophone_noise: flat ASD 0.01. The last value counts: 0.03 gives 9 times the variance, 0.02 four times.
  const BudgetResult nominal = Evaluate(LoadBudgetFile(kIsolator));
  const auto ratio = [&](const BudgetResult& r) {
    for (std::size_t c = 0; c < r.outputs[0].contributors.size(); ++c)
      if (r.outputs[0].contributors[c].source == "geophone_noise")
        return r.outputs[0].contributors[c].variance / nominal.outputs[0].contributors[c].variance;
    return 0.0;
  };
  CHECK(ratio(Evaluate(LoadBudgetFile(
            kIsolator, {{"sources[1].spectrum.level", "0.02"}, {"sources[1].spectrum.level", "0.03"}}))) ==
        doctest::Approx(9.0).epsilon(1e-12));
  CHECK(ratio(Evaluate(LoadBudgetFile(
            kIsolator, {{"sources[1].spectrum.level", "0.03"}, {"sources[1].spectrum.level", "0.02"}}))) ==
        doctest::Approx(4.0).epsilon(1e-12));
  CHECK(ratio(Evaluate(LoadBudgetFile(kIsolator, {{"sources[1].spectrum", "{type: flat, quantity: asd, level: 0.01}"},
                                                  {"sources[1].spectrum.level", "0.03"}}))) ==
        doctest::Approx(9.0).epsilon(1e-12));
  // Three in a row: the third wins.
  CHECK(ratio(Evaluate(LoadBudgetFile(kIsolator, {{"sources[1].spectrum.level", "0.05"},
                                                  {"sources[1].spectrum.level", "0.04"},
                                                  {"sources[1].spectrum.level", "0.02"}}))) ==
        doctest::Approx(4.0).epsilon(1e-12));
}

TEST_CASE("a --set value of several YAML documents is refused, not cut to its first") {
  try {
    (void)LoadBudgetFile(kIsolator, {{"sources[1].spectrum.level", "0.02\n---\n0.03"}});
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("the value holds 2 YAML documents ('---' starts each); give one value") !=
          std::string::npos);
  }
}

TEST_CASE("--set on every element ([*]) gives the sweep's variant with the same values, bitwise") {
  // Sweep variant (K_v = 25, h = 100 mm) against the budget with those values set by --set.
  const SweepBudget sweep = LoadSweepFile(kThesisSweep);
  const auto rows = sweep.spec.Variants();
  std::size_t index = rows.size();
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i][0] == 25.0 && rows[i][1] == -100.0) index = i;
  REQUIRE(index < rows.size());
  const BudgetResult from_sweep = Evaluate(sweep.variant(index));
  const BudgetResult from_set = Evaluate(LoadBudgetFile(
      kThesisSweep, {{"paths[0].control.gains", "25"}, {"paths[0].isolators[*].position[2]", "-100"}}));
  REQUIRE(from_sweep.outputs.size() == from_set.outputs.size());
  for (std::size_t o = 0; o < from_set.outputs.size(); ++o) CHECK(from_set.outputs[o].variance == from_sweep.outputs[o].variance);
  // Overrides apply to the budget under a sweep too.
  const SweepBudget louder = LoadSweepFile(kThesisSweep, {{"sources[1].spectrum.level", "80"}});
  const BudgetResult loud = Evaluate(louder.variant(index));
  CHECK(loud.outputs[0].variance > from_sweep.outputs[0].variance);
  CHECK_THROWS_AS(LoadSweepFile(kThesisSweep, {{"sweep.mode", "zip"}}), InputError);
}

TEST_CASE("a bad override is an error naming it: a missing key, a value the loader refuses, text that is not YAML") {
  const std::string missing = ErrorOf(kIsolator, {{"sources[1].spectrum.levle", "2"}});
  CHECK(Contains(missing, "--set sources[1].spectrum.levle=2"));
  CHECK(Contains(missing, "did you mean 'level'"));
  CHECK(Contains(ErrorOf(kIsolator, {{"sources[9].unit", "nm"}}), "sources has 2 element(s), so no [9]"));
  // The loader's own rule, located at the key's line and column in the user's file.
  const std::string refused = ErrorOf(kIsolator, {{"sources[1].spectrum.level", "-1"}});
  CHECK(Contains(refused, "single_axis_isolator.yaml:39:"));
  CHECK(Contains(refused, "sources[1].spectrum.level"));
  CHECK(Contains(refused, "--set sources[1].spectrum.level=-1"));
  CHECK(Contains(ErrorOf(kIsolator, {{"sources[1].spectrum.level", "[1,"}}), "the value is not YAML"));
  // Later overrides see earlier ones.
  CHECK(ErrorOf(kIsolator, {{"sources[1].spectrum", "{type: flat, level: 1}"}, {"sources[1].spectrum.level", "2"}}) ==
        "(no error)");
}

TEST_CASE("LoadBudgetText with overrides equals LoadBudgetFile with them, and locates its errors in the text") {
  // The Python module's deb.load(text, set=...): the same budget as the file's, the same rule at the same place.
  const std::string text = test::ReadAll(kIsolator);
  const std::vector<BudgetOverride> overrides{{"sources[1].spectrum.level", "0.03"}};
  const BudgetResult from_file = Evaluate(LoadBudgetFile(kIsolator, overrides));
  const BudgetResult from_text = Evaluate(LoadBudgetText(text, "isolator.yaml", DEB_SOURCE_DIR "/budgets", overrides));
  REQUIRE(from_text.outputs.size() == from_file.outputs.size());
  for (std::size_t o = 0; o < from_file.outputs.size(); ++o)
    CHECK(from_text.outputs[o].variance == from_file.outputs[o].variance);
  CHECK(from_text.outputs[0].variance != Evaluate(LoadBudgetFile(kIsolator)).outputs[0].variance);
  try {
    LoadBudgetText(text, "isolator.yaml", ".", {{"sources[1].spectrum.level", "-1"}});
    FAIL("a negative level was accepted");
  } catch (const InputError& e) {
    CHECK(e.file() == "isolator.yaml");
    CHECK(e.line() == 39);
    CHECK(e.key_path() == "sources[1].spectrum.level");
    CHECK(Contains(e.what(), "--set sources[1].spectrum.level=-1"));
  }
}

}  // namespace deb
