// Budgets written with parameters and expressions (budget_yaml.h,
// deb/parameters): the same figures as their literal twin, and every bad
// expression located at its file, line and the column where it goes wrong.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/sweep_yaml.h"
#include "tests/support/contains.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using test::Contains;

const char* kLiteral = R"(name: twin
grid: {type: log, min_hz: 0.1, max_hz: 100, points: 200}
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
bands:
  - [1, 10]
)";

// The same budget in parameters: tau = 1 / (2 pi f_c) written as 10 ms, the
// grid from 100 mHz to 0.1 kHz, the band edges as products.
const char* kParametric = R"(name: twin
parameters:
  tau: {value: 10 ms, description: time constant of the sensor's low-pass}
  level: 4/2
  f_lo: 100 mHz
  decade: 10
grid: {type: log, min_hz: f_lo, max_hz: 0.1 kHz, points: 200}
sources:
  - name: noise
    unit: um/s
    spectrum: {type: flat, level: level}
paths:
  - name: lowpass
    type: transfer_function
    num: [1]
    den: [tau/(1 s), 1]
    input_unit: um/s
    output_unit: um/s
    outputs: [v]
contributors:
  - {name: sensor, source: noise, path: lowpass}
outputs:
  - {name: velocity, signal: v, unit: um/s}
bands:
  - [f_lo*decade/(1 Hz), decade^2/10]
)";

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { LoadBudgetText(text, "b.yaml"); });
}

TEST_CASE("a parametric budget and its literal twin give identical figures") {
  const Budget literal = LoadBudgetText(kLiteral, "literal.yaml");
  const Budget parametric = LoadBudgetText(kParametric, "parametric.yaml");
  const BudgetResult a = Evaluate(literal), b = Evaluate(parametric);
  REQUIRE(a.outputs.size() == 1);
  REQUIRE(b.outputs.size() == 1);
  // 10 ms / 1 s and 100 mHz are exact in binary only to rounding: the
  // figures agree to 1e-15 relative, not bit for bit.
  CHECK(b.outputs[0].rms() == doctest::Approx(a.outputs[0].rms()).epsilon(1e-15));
  CHECK(a.outputs[0].rms() > 0.0);
}

TEST_CASE("a parameter can be changed by its key path, as any value") {
  const std::string changed = Replace(kParametric, "  level: 4/2", "  level: 8");
  const BudgetResult a = Evaluate(LoadBudgetText(kParametric, "b.yaml"));
  const BudgetResult b = Evaluate(LoadBudgetText(changed, "b.yaml"));
  // The PSD level 4x: the rms 2x.
  CHECK(b.outputs[0].rms() == doctest::Approx(2.0 * a.outputs[0].rms()).epsilon(1e-14));
}

// The budget written to a file of its own, removed at the end of the test.
struct BudgetFile {
  explicit BudgetFile(const std::string& text)
      : path((std::filesystem::temp_directory_path() / ("deb_parameters_" + std::to_string(getpid()) + ".yaml"))
                 .string()) {
    std::ofstream(path) << text;
  }
  ~BudgetFile() { std::filesystem::remove(path); }
  std::string path;
};

double TimeConstantCoefficient(const Budget& b) {
  // den = [tau/(1 s), 1]: the path's pole is at -1/tau.
  return -1.0 / b.paths[0].system.Poles()(0).real();
}

TEST_CASE("parameters are handles by name: --set, sensitivity scaling, nominal values and sweeps") {
  const BudgetFile file(kParametric);
  CHECK(TimeConstantCoefficient(LoadBudgetFile(file.path)) == doctest::Approx(0.01).epsilon(1e-14));
  // --set NAME=VALUE, as editing the file; tau is given as a map: its value.
  const Budget set = LoadBudgetFile(file.path, {{"tau", "20 ms"}, {"level", "8"}});
  CHECK(TimeConstantCoefficient(set) == doctest::Approx(0.02).epsilon(1e-14));
  CHECK(set.sources[0].spectrum->Psd(1.0)(0) == 8.0);
  // A top-level key keeps its meaning.
  CHECK(LoadBudgetFile(file.path, {{"name", "other"}}).name == "other");
  // Scaling an expression scales its value: (10 ms)*2.
  const Budget scaled = LoadBudgetWithScaledParameter(file.path, "tau", 2.0);
  CHECK(TimeConstantCoefficient(scaled) == doctest::Approx(0.02).epsilon(1e-14));
  REQUIRE(ParameterValues(file.path, "tau").size() == 1);
  CHECK(ParameterValues(file.path, "tau")[0] == doctest::Approx(10.0).epsilon(1e-15));  // in ms, as written
  CHECK(ParameterValues(file.path, "level") == std::vector<double>{2.0});  // 4/2
  CHECK(ParameterValues(file.path, "decade") == std::vector<double>{10.0});
  // A sweep of a parameter by name: each value in the parameter's unit.
  const SweepBudget sweep = LoadSweepText(std::string(kParametric) + "sweep:\n  parameters:\n    - {path: tau, values: [5, 20]}\n",
                                          "s.yaml");
  const std::vector<Budget> variants = LoadSweepVariants(sweep, 1);
  REQUIRE(variants.size() == 2);
  CHECK(TimeConstantCoefficient(variants[0]) == doctest::Approx(0.005).epsilon(1e-14));
  CHECK(TimeConstantCoefficient(variants[1]) == doctest::Approx(0.02).epsilon(1e-14));
  CHECK(sweep.spec.parameters[0].unit == "ms");
}

TEST_CASE("bad parameters and expressions: file, line, column, key path and the rule") {
  // The column is the value's plus where in it the expression goes wrong.
  CHECK(ErrorOf(Replace(kParametric, "  level: 4/2", "  level: 4/0")) ==
        "b.yaml:4:11: parameters.level: expression '4/0', column 2: division by zero");
  CHECK(ErrorOf(Replace(kParametric, "  decade: 10", "  decade: '10 + tau'")) ==
        "b.yaml:6:15: parameters.decade: expression '10 + tau', column 4: cannot add 1 and s (10, 0.01 s)");
  CHECK(Contains(ErrorOf(Replace(kParametric, "  decade: 10", "  decade: dekade")),
                 "parameters.decade: expression 'dekade', column 1: unknown name 'dekade' (did you mean 'decade'?)"));
  CHECK(Contains(ErrorOf(Replace(kParametric, "  decade: 10", "  decade: 10*f_lo/f_lo*decade")),
                 "b.yaml:6:11: parameters.decade: parameters refer to each other in a cycle: decade -> decade"));
  CHECK(Contains(ErrorOf(Replace(kParametric, "  decade: 10", "  decade: [10]")),
                 "parameters.decade: a parameter's value is a number with its unit or an expression"));
  CHECK(Contains(ErrorOf(Replace(kParametric, "  decade: 10", "  decade: {value: 10, units: m}")),
                 "unknown key 'units'"));
  // A unit to show it in that its value is not in: located at `unit`.
  CHECK(Contains(ErrorOf(Replace(kParametric, "  decade: 10", "  decade: {value: 10, unit: m}")),
                 ":6:29: parameters.decade.unit: 'decade' is 10, not a quantity in 'm'"));
  // In a field: a unit where the field takes a plain number, a unit of the
  // wrong kind, rad/s for Hz, an unknown name.
  CHECK(ErrorOf(Replace(kParametric, "den: [tau/(1 s), 1]", "den: [tau, 1]")) ==
        "b.yaml:16:11: paths[0].den[0]: 'tau' is a quantity in s; this value is a plain number (a unit is taken "
        "where the key names it: _hz, _s, _deg)");
  CHECK(ErrorOf(Replace(kParametric, "max_hz: 0.1 kHz", "max_hz: 2 m")) ==
        "b.yaml:7:41: grid.max_hz: '2 m' is a quantity in m; this value is in Hz");
  CHECK(Contains(ErrorOf(Replace(kParametric, "max_hz: 0.1 kHz", "max_hz: 600 rad/s")),
                 "b.yaml:7:41: grid.max_hz: '600 rad/s': give frequencies in Hz, not rad/s"));
  CHECK(ErrorOf(Replace(kParametric, "level: level}", "level: 2*levl}")) ==
        "b.yaml:11:37: sources[0].spectrum.level: expected a number, got '2*levl': unknown name 'levl' (did you "
        "mean 'level'?)");
  CHECK(ErrorOf(Replace(kLiteral, "den: [0.01, 1]", "den: [0.01, one]")) ==
        "b.yaml:11:17: paths[0].den[1]: expected a number, got 'one': unknown name 'one' (no parameters are "
        "defined)");
}

}  // namespace
}  // namespace deb
