#include "deb/load/sweep_yaml.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

// A budget with a sweep over a source level and a path coefficient.
const char* kSweep = R"(name: sweep_test
grid: {type: log, min_hz: 0.1, max_hz: 100, points: 400}
sources:
  - name: noise
    unit: um/s
    spectrum: {type: flat, level: 2}
paths:
  - name: lowpass
    type: transfer_function
    num: [1]
    den: [0.01, 1]
    input_unit: um/s
    output_unit: um/s
    outputs: [v]
contributors:
  - {name: sensor, source: noise, path: lowpass}
outputs:
  - {name: velocity, signal: v, unit: um/s}
sweep:
  mode: grid
  parameters:
    - {path: "sources[0].spectrum.level", values: [1, 4]}
    - {path: "paths[0].den[0]", log: {from: 0.001, to: 0.1, count: 3}}
)";

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { LoadSweepVariants(LoadSweepText(text, "s.yaml"), 1); });
}

}  // namespace

TEST_CASE("every sweep variant gives the figures of the budget written out by hand with its values") {
  const SweepBudget sweep = LoadSweepText(kSweep, "s.yaml");
  REQUIRE(sweep.variant_count == 6);  // 2 x 3, the last parameter fastest
  const auto rows = sweep.spec.Variants();
  CHECK(rows[1] == std::vector<double>{1.0, sweep.spec.parameters[1].values[1]});
  CHECK(sweep.spec.parameters[1].values[1] == doctest::Approx(0.01).epsilon(1e-15));
  const auto results = EvaluateSweep(sweep.spec, sweep.variant, 2);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    CAPTURE(i);
    char den[64];
    std::snprintf(den, sizeof den, "den: [%.17g, 1]", rows[i][1]);
    std::string text = Replace(kSweep, "level: 2", "level: " + std::to_string(static_cast<int>(rows[i][0])));
    text = Replace(text, "den: [0.01, 1]", den);
    text = text.substr(0, text.find("sweep:"));
    const BudgetResult single = Evaluate(LoadBudgetText(text, "b.yaml"));
    CHECK(results[i].outputs[0].variance == doctest::Approx(single.outputs[0].variance).epsilon(1e-14));
    // White noise through 1/(tau s + 1): variance S0 / (4 tau) minus what lies outside 0.1-100 Hz.
    CHECK(results[i].outputs[0].variance < rows[i][0] / (4.0 * rows[i][1]));
  }
  const std::string csv = SweepCsv(sweep.spec, results);
  CHECK(csv.rfind("sources[0].spectrum.level,paths[0].den[0],velocity.rms,velocity.sensor.rms\n", 0) == 0);
  // Each variant is loaded and evaluated by whichever thread is free: the
  // same table, bit for bit, on 1, 2 (above), 4 and 5 threads, and from
  // variants loaded beforehand.
  CHECK(SweepCsv(sweep.spec, EvaluateSweep(sweep.spec, sweep.variant, 1)) == csv);
  CHECK(SweepCsv(sweep.spec, EvaluateSweep(sweep.spec, sweep.variant, 4)) == csv);
  CHECK(SweepCsv(sweep.spec, EvaluateSweep(sweep.spec, sweep.variant, 5)) == csv);
  CHECK(SweepCsv(sweep.spec, EvaluateSweep(sweep.spec, LoadSweepVariants(sweep, 2), 2)) == csv);
}

TEST_CASE("zipped parameters pair their values; a [*] path sets every element") {
  std::string text = Replace(kSweep, "mode: grid", "mode: zip");
  text = Replace(text, "log: {from: 0.001, to: 0.1, count: 3}", "values: [0.02, 0.03]");
  text = Replace(text, "\"paths[0].den[0]\"", "\"paths[0].den[*]\"");
  const SweepBudget sweep = LoadSweepText(text, "s.yaml");
  REQUIRE(sweep.variant_count == 2);
  // den [0.03, 0.03]: 0.03 / (0.03 s + 0.03) has the DC gain 1.
  const Budget second = sweep.variant(1);
  const StateSpace& sys = second.paths[0].system;
  CHECK(-sys.A()(0, 0) == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("bad key paths, empty ranges and unequal zipped lists are errors at their position") {
  CHECK(ErrorOf(Replace(kSweep, "sources[0].spectrum.level", "sources[0].spectrum.lvl"))
            .rfind("s.yaml:22:14: sweep.parameters[0].path: key path 'sources[0].spectrum.lvl' does not reach a "
                   "number: sources[0].spectrum has no key 'lvl'",
                   0) == 0);
  CHECK(ErrorOf(Replace(kSweep, "sources[0].spectrum.level", "sources[0].spectrum.levle"))
            .find("sources[0].spectrum has no key 'levle' (did you mean 'level'?) (it has: type, level)") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "sources[0].spectrum.level", "sourcs[0].spectrum.level"))
            .find("the budget has no key 'sourcs' (did you mean 'sources'?)") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "sources[0].spectrum.level", "sources[3].spectrum.level"))
            .find("sources has 1 element(s), so no [3]") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "sources[0].spectrum.level", "sources[0].spectrum"))
            .find("is not a number or a list of numbers") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "sources[0].spectrum.level", "sources[0.spectrum"))
            .find("'[' without ']'") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "values: [1, 4]", "values: []")).find("sweep.parameters[0].values: the list of values is empty") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "count: 3", "count: 0")).find("sweep.parameters[1].log.count: count 0 gives an empty range") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "mode: grid", "mode: zip")).find("equally many values") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "mode: grid", "mode: all")).find("allowed: grid, zip") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, "    - {path: \"sources[0].spectrum.level\", values: [1, 4]}\n", ""))
            .find("(no error)") != std::string::npos);  // one parameter is a sweep too
}

TEST_CASE("a budget with a sweep section runs as written") {
  const Budget b = LoadBudgetText(kSweep, "s.yaml");
  CHECK(b.sources[0].spectrum->Psd(1.0)(0) == 2.0);
}

TEST_CASE("a scaled parameter multiplies every number its key path reaches; a bad path names why") {
  const std::string file = std::string(DEB_SOURCE_DIR) + "/budgets/single_axis_isolator.yaml";
  const Budget nominal = LoadBudgetFile(file);
  const Budget scaled = LoadBudgetWithScaledParameter(file, "paths[0].den[*]", 2.0);
  // Every coefficient doubled: the same poles.
  CHECK(scaled.paths[0].system.Poles()(0).real() == doctest::Approx(nominal.paths[0].system.Poles()(0).real()));
  const Budget louder = LoadBudgetWithScaledParameter(file, "sources[1].spectrum.level", 3.0);
  CHECK(louder.sources[1].spectrum->Psd(1.0)(0) == doctest::Approx(9.0 * nominal.sources[1].spectrum->Psd(1.0)(0)));
  CHECK_THROWS_WITH_AS(LoadBudgetWithScaledParameter(file, "paths[9].den", 2.0),
                       doctest::Contains(("does not reach a number in " + file + ": paths has 2 element(s), so no [9]").c_str()), InputError);
  CHECK_THROWS_WITH_AS(LoadBudgetWithScaledParameter(file, "sources[1].spectrum.levle", 2.0),
                       doctest::Contains("has no key 'levle' (did you mean 'level'?)"), InputError);
}

TEST_CASE("a parameter with a distribution and bounds scales by its name: the variant is a point") {
  // The thesis budget with tolerances: k_h carries a truncated normal and
  // Kv bounds; scaled by 1.001 each is a plain value (no study keys left to
  // refuse it), and the variance of the geophone noise, linear in s_geo,
  // scales with it.
  const std::string file = std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_tolerances.yaml";
  const BudgetResult nominal = Evaluate(LoadBudgetFile(file));
  for (const char* name : {"k_h", "Kv", "h", "c_iso"}) {
    CAPTURE(name);
    CHECK_NOTHROW(LoadBudgetWithScaledParameter(file, name, 1.001));
  }
  const BudgetResult noisier = Evaluate(LoadBudgetWithScaledParameter(file, "s_geo", 1.25));
  const auto variance = [](const BudgetResult& r, const std::string& contributor) {
    for (const ContributorResult& c : r.outputs[0].contributors)
      if (c.name == contributor) return c.variance;
    FAIL("no contributor " << contributor);
    return 0.0;
  };
  CHECK(variance(noisier, "sensor_noise") == doctest::Approx(1.25 * variance(nominal, "sensor_noise")).epsilon(1e-12));
  CHECK(variance(noisier, "floor") == variance(nominal, "floor"));
  CHECK(ParameterValues(file, "k_h") == std::vector<double>{12.0});
}

TEST_CASE("a variant that breaks a rule is reported at the swept value's position in the user's file") {
  const std::string e = ErrorOf(Replace(kSweep, "values: [1, 4]", "values: [1, -4]"));
  CHECK(e.rfind("s.yaml:6:35: sources[0].spectrum.level: sweep variant 4: sources[0].spectrum.level = -4, "
                "paths[0].den[0] = 0.001: value -4 must be >= 0",
                0) == 0);
}

TEST_CASE("a list of words sweeps a textual parameter such as a VC class") {
  std::string text = Replace(kSweep, "spectrum: {type: flat, level: 2}",
                             "spectrum: {type: vc, class: VC-D, lowest_band_hz: 8, highest_band_hz: 80}");
  text = Replace(text, "{path: \"sources[0].spectrum.level\", values: [1, 4]}",
                 "{path: \"sources[0].spectrum.class\", values: [VC-C, VC-D]}");
  text = Replace(text, "log: {from: 0.001, to: 0.1, count: 3}", "values: [0.01]");
  const SweepBudget sweep = LoadSweepText(text, "s.yaml");
  REQUIRE(sweep.variant_count == 2);
  CHECK(sweep.spec.parameters[0].texts == std::vector<std::string>{"VC-C", "VC-D"});
  const auto results = EvaluateSweep(sweep.spec, sweep.variant, 1);
  // VC-C is 12.5 um/s per band, VC-D 6.25: every RMS halves.
  CHECK(results[0].outputs[0].rms() == doctest::Approx(2.0 * results[1].outputs[0].rms()).epsilon(1e-12));
  const std::string csv = SweepCsv(sweep.spec, results);
  CHECK(csv.find("\nVC-C,0.01,") != std::string::npos);
  CHECK(ErrorOf(Replace(text, "sources[0].spectrum.class", "sources[0].spectrum")).find("does not reach a value") !=
        std::string::npos);
}

TEST_CASE("an error the engine finds in a sweep variant is located in the user's file, naming the variant") {
  const SweepBudget sweep = LoadSweepText(
      Replace(Replace(kSweep, "den: [0.01, 1]", "den: [0.01, -1]"), "path: lowpass}", "path: lowpass, exact: required}"),
      "s.yaml");
  std::string what = "(no error)";
  try {
    EvaluateSweep(sweep.spec, sweep.variant, 1);
  } catch (const InputError& e) {
    what = e.what();
  }
  CHECK(what.rfind("s.yaml:16:41: contributors[0].path: sweep variant 1 (sources[0].spectrum.level = 1, ", 0) == 0);
  CHECK(what.find("unstable") != std::string::npos);
}

}  // namespace deb

namespace deb {

TEST_CASE("a sweep parameter's label and unit name it on axes; without them the key path does") {
  const SweepBudget sweep = LoadSweepText(
      Replace(kSweep, R"({path: "paths[0].den[0]", log:)", R"({path: "paths[0].den[0]", label: "time constant", unit: s, log:)"),
      "s.yaml");
  const SweepParameter& level = sweep.spec.parameters[0];
  const SweepParameter& tau = sweep.spec.parameters[1];
  CHECK(level.AxisTitle() == "sources[0].spectrum.level");
  CHECK(tau.label == "time constant");
  CHECK(tau.unit == "s");
  CHECK(tau.AxisTitle() == "time constant [s]");
  CHECK(tau.Setting(0.01) == "time constant = 0.01 s");
}

TEST_CASE("a sweep label that is empty or multi-line, and a unit UDUNITS-2 does not know, are located errors") {
  const std::string at = R"({path: "sources[0].spectrum.level", )";
  CHECK(ErrorOf(Replace(kSweep, at, at + R"(label: "  ", )")) ==
        std::string("s.yaml:22:50: sweep.parameters[0].label: the label is empty; name the parameter, e.g. 'isolator height h'"));
  CHECK(ErrorOf(Replace(kSweep, at, at + R"(label: "a\nb", )"))
            .find("sweep.parameters[0].label: the label holds a control character") != std::string::npos);
  const std::string unit = ErrorOf(Replace(kSweep, at, at + R"(unit: umm, )"));
  CHECK(unit.find("s.yaml:22:") == 0);
  CHECK(unit.find("sweep.parameters[0].unit: ") != std::string::npos);
  CHECK(unit.find("umm") != std::string::npos);
  CHECK(ErrorOf(Replace(kSweep, at, at + R"(lable: x, )")).find("lable") != std::string::npos);
}

}  // namespace deb
