// Outputs that combine signals: the combination is the state-space row it
// stands for (its PSD from the cross terms, not a sum of PSDs); terms in
// units that do not fit are located errors.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

// Two lightly coupled resonances seen as a translation x_dot [m/s] and a rotation beta_dot [rad/s].
std::string Body(const std::string& outputs) {
  return R"(name: comb
grid: {type: auto, min_hz: 0.1, max_hz: 1000}
sources:
  - {name: f, unit: N, spectrum: {type: flat, level: 1.0e-4}}
paths:
  - name: body
    type: state_space
    A: [[0, 1, 0, 0], [-1000, -2, 0, 0], [0, 0, 0, 1], [0, 0, -3000, -3]]
    B: [[0], [1], [0], [1]]
    C: [[0, 1, 0, 0], [0, 0, 0, 1], [0, 1, 0, -0.21]]
    D: [[0], [0], [0]]
    input_unit: N
    outputs: [x_dot, beta_dot, by_hand]
    output_units: [m/s, rad/s, m/s]
contributors:
  - {name: force, source: f, path: body}
outputs:
)" + outputs;
}

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { Evaluate(LoadBudgetText(text, "c.yaml")); });
}

}  // namespace

TEST_CASE("x_dot - 210 mm beta_dot equals the state-space row C_x - 0.21 C_beta, and not the sum of the PSDs") {
  const BudgetResult r = Evaluate(LoadBudgetText(
      Body("  - {name: los, unit: um/s, combination: {x_dot: 1, beta_dot: -210 mm}}\n"
           "  - {name: by_hand, unit: um/s}\n"
           "  - {name: x, signal: x_dot, unit: um/s}\n"
           "  - {name: b, signal: beta_dot, unit: urad/s}\n"),
      "c.yaml"));
  const ContributorResult& los = r.outputs[0].contributors[0];
  const ContributorResult& hand = r.outputs[1].contributors[0];
  REQUIRE(los.exact_variance.has_value());
  REQUIRE(hand.exact_variance.has_value());
  CHECK(std::abs(*los.exact_variance / *hand.exact_variance - 1.0) < 1e-12);
  CHECK(std::abs(los.variance / hand.variance - 1.0) < 1e-12);
  for (std::size_t k = 0; k < los.psd.size(); k += 17)
    CHECK(std::abs(los.psd[k] - hand.psd[k]) <= 1e-12 * hand.psd[k]);
  // Sum of the PSDs of x_dot and 0.21 beta_dot: not the same (the modes are coupled through one force).
  const double v_x = r.outputs[2].variance, v_b = r.outputs[3].variance * 0.21 * 0.21;
  CHECK(std::abs((v_x + v_b) / los.variance - 1.0) > 1e-3);
}

TEST_CASE("combination terms that the paths lack or whose units differ are located errors") {
  const std::string missing = ErrorOf(Body("  - {name: los, unit: um/s, combination: {x_dot: 1, gamma_dot: 2}}\n"));
  CHECK(missing.find("outputs[0].combination.gamma_dot") != std::string::npos);
  CHECK(missing.find("has no signal 'gamma_dot'") != std::string::npos);
  const std::string unit = ErrorOf(Body("  - {name: los, unit: um/s, combination: {x_dot: 1, beta_dot: -210 N}}\n"));
  CHECK(unit.find("outputs[0].combination.beta_dot") != std::string::npos);
  const std::string derivative =
      ErrorOf(Body("  - {name: los, unit: um/s, combination: {x_dot: 1, beta_dot: -210 mm s}}\n"));
  CHECK(derivative.find("differ by a time derivative") != std::string::npos);
  CHECK(ErrorOf(Body("  - {name: los, unit: um/s, combination: {x_dot: one}}\n")).find("is not a number") !=
        std::string::npos);
  CHECK(ErrorOf(Body("  - {name: los, unit: um/s, signal: x_dot, combination: {x_dot: 1}}\n"))
            .find("give 'signal' or 'combination'") != std::string::npos);
}

}  // namespace deb
