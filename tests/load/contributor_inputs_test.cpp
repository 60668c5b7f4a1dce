// A contributor's `inputs:`: a source driving some inputs of a MIMO path
// gives the figures of the same source through a path with only those
// input columns written by hand; bad names are located errors.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

// A lightly damped mass (1 kg, 5 Hz, zeta 0.02) with two force inputs: a
// disturbance d (N) and an actuator noise n entering through a gain of 3 N/V.
const char* kBudget = R"(name: inputs_test
grid: {type: auto, min_hz: 0.1, max_hz: 200}
sources:
  - {name: force, unit: N, spectrum: {type: flat, level: 1.0e-4}}
  - {name: amplifier, unit: V, spectrum: {type: flat, level: 4.0e-6}}
paths:
  - name: stage
    type: state_space
    A: [[0, 1], [-986.96044, -1.2566371]]
    B: [[0, 0], [1, 3]]
    C: [[1.0e6, 0]]
    D: [[0, 0]]
    inputs: [d, n]
    input_units: [N, V]
    outputs: [x]
    output_unit: um
  - name: stage_d
    type: state_space
    A: [[0, 1], [-986.96044, -1.2566371]]
    B: [[0], [1]]
    C: [[1.0e6, 0]]
    D: [[0]]
    input_unit: N
    outputs: [x]
    output_unit: um
  - name: stage_n
    type: state_space
    A: [[0, 1], [-986.96044, -1.2566371]]
    B: [[0], [3]]
    C: [[1.0e6, 0]]
    D: [[0]]
    input_unit: V
    outputs: [x]
    output_unit: um
contributors:
  - {name: disturbance, source: force, path: stage, inputs: [d]}
  - {name: amplifier, source: amplifier, path: stage, inputs: n}
  - {name: disturbance_by_hand, source: force, path: stage_d}
  - {name: amplifier_by_hand, source: amplifier, path: stage_n}
outputs:
  - {name: position, signal: x, unit: um}
)";

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { Evaluate(LoadBudgetText(text, "b.yaml")); });
}

}  // namespace

TEST_CASE("a source on named inputs equals the same source through those columns written by hand") {
  const BudgetResult r = Evaluate(LoadBudgetText(kBudget, "b.yaml"));
  const auto& c = r.outputs[0].contributors;
  REQUIRE(c.size() == 4);
  // The grid depends on every path's poles, which are the same: the PSDs agree point by point.
  for (std::size_t k : {0, 1}) {
    CHECK(std::abs(c[k].variance / c[k + 2].variance - 1.0) < 1e-12);
    REQUIRE(c[k].exact_variance.has_value());
    CHECK(std::abs(*c[k].exact_variance / *c[k + 2].exact_variance - 1.0) < 1e-12);
  }
  // Closed form of the first: a white force S (one-sided, N^2/Hz) on m x'' + c x' + k x = f gives
  // var x = S / (4 c k) [m^2] with m = 1; here in um^2.
  const double k = 986.96044, damping = 1.2566371, s = 1.0e-4;
  CHECK(std::abs(*c[0].exact_variance / (s / (4 * damping * k) * 1e12) - 1.0) < 1e-9);
}

TEST_CASE("inputs that the path does not have, name twice, or that do not match the channels are located errors") {
  const std::string unknown = ErrorOf(Replace(kBudget, "inputs: [d]}", "inputs: [dd]}"));
  CHECK(unknown.find("b.yaml:36:") != std::string::npos);
  CHECK(unknown.find("contributors[0].inputs") != std::string::npos);
  CHECK(unknown.find("has no input 'dd' (did you mean 'd'?)") != std::string::npos);
  const std::string two = ErrorOf(Replace(kBudget, "inputs: [d]}", "inputs: [d, n]}"));
  CHECK(two.find("source 'force' has 1 channel(s) but 'inputs' names 2 input(s) of path 'stage'") != std::string::npos);
  const std::string none = ErrorOf(Replace(kBudget, ", inputs: [d]}", "}"));
  CHECK(none.find("name the inputs it drives: inputs: [...]") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "inputs: [d]}", "inputs: []}")).find("name at least one input") != std::string::npos);
  // A unit that does not convert to the selected input's unit is caught as for any path.
  CHECK(ErrorOf(Replace(kBudget, "inputs: n}", "inputs: d}")).find("contributors[1]") != std::string::npos);
}

}  // namespace deb
