// A controller's integrator in series with the loop it closes: the noise path
// written as `series [minus, pid, force_to_position]` (-C P S, which is -T)
// has a pole at 0 that its transfer cancels. It gets its exact variance, the
// same as the loop's own T, and no warning about the grid's ends.
#include <doctest/doctest.h>

#include <string>

#include "deb/budget/budget_description.h"
#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contains.h"
#include "tests/support/contributor_of.h"

namespace deb {
namespace {

using test::Contains;

// A two-mass plant, force on mass 1, position of mass 1 (collocated):
// (m2 s^2 + d s + k) / (s^2 (m1 m2 s^2 + (m1 + m2)(d s + k))), m1 = 20 kg,
// m2 = 5 kg, k = 2e6 N/m, d = 20 N s/m (a 113 Hz resonance), under a PID
// at a 20 Hz crossover; the sensor's noise reaches the position through -T.
const char* kBudget = R"(name: cancelled
parameters:
  f_c: 20 Hz
  kp: 25 kg * (2*pi*f_c)^2 / 3
grid: {type: log, min_hz: 0.01, max_hz: 10000, points: 4000}
sources:
  - {name: sensor, unit: nm, spectrum: {type: flat, quantity: asd, level: 0.01}}
paths:
  - {name: plant, type: transfer_function, num: [5, 20, 2e6], den: [100, 500, 5e7, 0, 0], input_unit: N, output_unit: m, outputs: [x]}
  - {name: pid, type: pid, gain: kp/(1 N/m), f_i_hz: f_c/5, f_d_hz: f_c/3, f_lp_hz: 3*f_c, input_unit: m, output_unit: N}
  - {name: minus, type: gain, gain: [[-1]], input_unit: m, output_unit: m}
  - {name: unity, type: gain, gain: [[1]], input_unit: m, output_unit: m, outputs: [x]}
  - {name: force_to_position, type: feedback, plant: plant, controller: pid}
  - {name: loop_gain, type: series, of: [pid, plant]}
  - {name: measurement_to_position, type: feedback, plant: loop_gain, controller: unity}
  - {name: noise_to_position, type: series, of: [minus, pid, force_to_position]}
contributors:
  - {name: through_t, source: sensor, path: measurement_to_position}
  - {name: through_series, source: sensor, path: noise_to_position}
outputs:
  - {name: x, signal: x, unit: nm}
)";

using test::ContributorOf;

}  // namespace

TEST_CASE("series [minus, pid, closed loop]: the integrator cancels, the exact variance is T's") {
  const Budget b = LoadBudgetText(kBudget, "b.yaml");
  const BudgetResult r = Evaluate(b);
  const ContributorResult& t = ContributorOf(r.outputs[0], "through_t");
  const ContributorResult& s = ContributorOf(r.outputs[0], "through_series");
  REQUIRE(t.exact_variance);
  REQUIRE(s.exact_variance);
  // Two realisations of one transfer, solved independently.
  CHECK(*s.exact_variance == doctest::Approx(*t.exact_variance).epsilon(1e-10));
  // And the grid agrees with it, as for any stable path.
  CHECK(s.variance + s.tail_variance_estimate == doctest::Approx(*s.exact_variance).epsilon(1e-4));
  for (const std::string& w : r.warnings) CHECK_FALSE(Contains(w, "grid's ends"));

  const std::string text = DescribeBudget(b, PlanEvaluation(b));
  CHECK(Contains(text, "stable (1 pole(s) at 0 cancelled by zeros at 0: they do not reach the outputs)"));
  CHECK(Contains(text, "marginally stable (integrator: 1 pole(s) at 0; close a loop around it)"));  // the PID alone
  CHECK_FALSE(Contains(text, "no exact variance"));
}

TEST_CASE("an integrator that does reach the output is not cancelled: no exact variance, the warning stays") {
  // The open loop -C P: the PID's integrator and the plant's double
  // integrator all reach the position.
  std::string text = kBudget;
  text.replace(text.find("path: noise_to_position"), 23, "path: open_loop");
  text.replace(text.find("contributors:"), 0, "  - {name: open_loop, type: series, of: [minus, pid, plant]}\n");
  const Budget b = LoadBudgetText(text, "b.yaml");
  const BudgetResult r = Evaluate(b);
  CHECK_FALSE(ContributorOf(r.outputs[0], "through_series").exact_variance);
  bool warned = false;
  for (const std::string& w : r.warnings) warned = warned || Contains(w, "grid's ends");
  CHECK(warned);
}

}  // namespace deb
