// Delays and sampled blocks as path types: exact on the grid, their rational
// approximations for poles and exact variance, the phase they cost a loop,
// and the notes a user reads (the approximation at the crossover, Nyquist).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "deb/budget/budget_description.h"
#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contains.h"
#include "tests/support/contributor_of.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using test::Contains;
constexpr double kPi = 3.14159265358979323846;

// A 1 kg mass on a 10 Hz suspension under a PID; the same loop with 100 us
// of delay and with a 10 kHz sampled low-pass behind a hold; a first-order
// low-pass in series with a delay (an all-pass: the same variance).
const char* kBudget = R"(name: delayed
parameters:
  Td: 100 us
grid: {type: log, min_hz: 0.01, max_hz: 4000, points: 3000}
sources:
  - {name: force, unit: N, spectrum: {type: flat, quantity: asd, level: 1}}
paths:
  - {name: plant, type: mass_spring_damper, m: 1 kg, k: 3948 N/m, d: 12.6 N s/m, input_unit: N, output_unit: um, outputs: [x]}
  - {name: pid, type: pid, gain: 0.1, f_i_hz: 5, f_d_hz: 20, f_lp_hz: 200, input_unit: um, output_unit: N}
  - {name: wait, type: delay, seconds: Td, input_unit: N, output_unit: N}
  - {name: sampler, type: discrete, sample_hz: 10 kHz, num: [0.2], den: [1, -0.8], zoh: true, input_unit: N, output_unit: N}
  - {name: late_pid, type: series, of: [pid, wait]}
  - {name: sampled_pid, type: series, of: [pid, sampler]}
  - {name: loop, type: feedback, plant: plant, controller: pid}
  - {name: late_loop, type: feedback, plant: plant, controller: late_pid}
  - {name: sampled_loop, type: feedback, plant: plant, controller: sampled_pid}
  - {name: filter, type: lowpass, f_hz: 100, order: 1, input_unit: N, output_unit: um, outputs: [x]}
  - {name: wait_um, type: delay, seconds: Td, input_unit: um, output_unit: um}
  - {name: late_filter, type: series, of: [filter, wait_um], outputs: [x]}
contributors:
  - {name: loop, source: force, path: loop}
  - {name: late_loop, source: force, path: late_loop}
  - {name: sampled_loop, source: force, path: sampled_loop}
  - {name: late_filter, source: force, path: late_filter}
outputs:
  - {name: x, signal: x, unit: um}
)";

using test::ContributorOf;

const LoopResult& LoopOf(const BudgetResult& r, const std::string& controller) {
  for (const LoopResult& l : r.loops)
    if (l.controller == controller) return l;
  FAIL("no loop closed by " << controller);
  return r.loops[0];
}

TEST_CASE("a delay in series keeps the exact variance: the Pade approximant is an all-pass") {
  const BudgetResult r = Evaluate(LoadBudgetText(kBudget, "b.yaml"));
  const ContributorResult& c = ContributorOf(r.outputs[0], "late_filter");
  REQUIRE(c.exact_variance);
  // One-sided S0 = 1 N^2/Hz through 1/(1 + j f/100) um/N: S0 f_c pi/2 um^2.
  CHECK(*c.exact_variance == doctest::Approx(100.0 * kPi / 2.0).epsilon(1e-10));
  CHECK(c.variance + c.tail_variance_estimate == doctest::Approx(*c.exact_variance).epsilon(1e-4));
}

TEST_CASE("a loop with a delay: 360 f_c tau degrees less phase margin, its Pade error at the crossover stated") {
  const BudgetResult r = Evaluate(LoadBudgetText(kBudget, "b.yaml"));
  const LoopResult& plain = LoopOf(r, "pid");
  const LoopResult& late = LoopOf(r, "late_pid");
  REQUIRE(plain.margins.phase_margin);
  REQUIRE(late.margins.phase_margin);
  const double f_c = plain.margins.phase_margin->f_hz;
  CHECK(late.margins.phase_margin->f_hz == doctest::Approx(f_c).epsilon(1e-9));
  CHECK(plain.margins.phase_margin->phase_margin_deg - late.margins.phase_margin->phase_margin_deg ==
        doctest::Approx(360.0 * f_c * 1e-4).epsilon(1e-7));
  CHECK(plain.approximations.empty());
  REQUIRE(late.approximations.size() == 1);
  CHECK(late.approximations[0].block == "a delay of 100 us");
  CHECK(late.approximations[0].approximation == "Pade (6, 6)");
  CHECK(late.approximations[0].f_hz == doctest::Approx(f_c).epsilon(1e-12));
  CHECK(std::abs(late.approximations[0].phase_error_deg) < 1e-9);
  CHECK(Contains(MarginsText(late), "a delay of 100 us by Pade (6, 6): phase error"));
  // The closed loop gets an exact variance from the approximation, and the
  // grid (exact delay) agrees with it.
  const ContributorResult& c = ContributorOf(r.outputs[0], "late_loop");
  REQUIRE(c.exact_variance);
  CHECK(c.variance + c.tail_variance_estimate == doctest::Approx(*c.exact_variance).epsilon(1e-4));
  CHECK(*c.exact_variance > *ContributorOf(r.outputs[0], "loop").exact_variance);  // less phase margin, more peaking
}

TEST_CASE("a sampled controller: evaluated at e^(j w T), its Tustin equivalent stated, a warning above Nyquist") {
  const Budget b = LoadBudgetText(kBudget, "b.yaml");
  CHECK(b.FindPath("sampled_loop").SystemApproximates());
  const BudgetResult r = Evaluate(b);
  const LoopResult& l = LoopOf(r, "sampled_pid");
  REQUIRE(l.approximations.size() == 1);
  CHECK(l.approximations[0].block == "a 10 kHz sampled block with a zero-order hold");
  CHECK(Contains(l.approximations[0].approximation, "Tustin"));
  CHECK(std::abs(l.approximations[0].phase_error_deg) < 0.01);
  int above = 0;
  for (const std::string& w : r.warnings) above += Contains(w, "above its Nyquist frequency 5000 Hz");
  CHECK(above == 0);  // the grid ends at 4 kHz
  const std::string wide = test::Replace(kBudget, "max_hz: 4000", "max_hz: 2e4");
  const BudgetResult r2 = Evaluate(LoadBudgetText(wide, "b.yaml"));
  for (const std::string& w : r2.warnings) above += Contains(w, "above its Nyquist frequency 5000 Hz");
  CHECK(above >= 1);
  const std::string text = DescribeBudget(b, PlanEvaluation(b));
  CHECK(Contains(text, "by its approximation: a 10 kHz sampled block with a zero-order hold by its Tustin"));
}

TEST_CASE("a sampled block from its zeros and poles in z equals its num/den twin") {
  // 0.2 (z - 0.5) / ((z - 0.8)(z^2 - 0.6 z + 0.25)): a real zero, a real
  // pole and the pair 0.3 +- 0.4j.
  const auto psd_of = [](const std::string& sampler) {
    const std::string text =
        test::Replace(kBudget, "num: [0.2], den: [1, -0.8]", sampler);
    const BudgetResult r = Evaluate(LoadBudgetText(text, "b.yaml"));
    return ContributorOf(r.outputs[0], "sampled_loop").psd;
  };
  const std::vector<double> twin = psd_of("num: [0.2, -0.1], den: [1, -1.4, 0.73, -0.2]");
  const std::vector<double> roots = psd_of("zeros: [0.5], poles: [0.8, {re: 0.3, im: 0.4}], gain: 0.2");
  REQUIRE(twin.size() == roots.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < twin.size(); ++k) worst = std::max(worst, std::abs(roots[k] - twin[k]) / twin[k]);
  CHECK(worst <= 1e-13);
  const auto error = [](const std::string& to) {
    return test::InputErrorOf(
        [&] { LoadBudgetText(test::Replace(kBudget, "num: [0.2], den: [1, -0.8]", to), "b.yaml"); });
  };
  CHECK(Contains(error("num: [0.2], den: [1, -0.8], poles: [0.8]"), "give num and den, or zeros, poles and gain"));
  CHECK(Contains(error("poles: [{re: 0.3, im: 0}]"), "a conjugate pair needs im != 0"));
  CHECK(Contains(error("poles: [-1]"), "root at z = -1"));
}

TEST_CASE("bad delay and discrete entries: the key and the rule") {
  const auto error = [](const std::string& from, const std::string& to) {
    return test::InputErrorOf([&] { LoadBudgetText(test::Replace(kBudget, from, to), "b.yaml"); });
  };
  CHECK(Contains(error("seconds: Td", "seconds: -Td"), "finite number of seconds >= 0"));
  CHECK(Contains(error("seconds: Td", "seconds: 3 m"), "paths[2].seconds"));
  CHECK(Contains(error("seconds: Td,", "seconds: Td, pade_order: 20,"), "pade_order must be 1 to 12, not 20"));
  CHECK(Contains(error("den: [1, -0.8]", "den: [1, 1]"), "root at z = -1"));
  CHECK(Contains(error("num: [0.2]", "num: [0.2, 0, 0]"), "not causal"));
  CHECK(Contains(error("zoh: true", "zoh: maybe"), "zoh"));
  CHECK(Contains(error("sample_hz: 10 kHz", "sample_hz: 0"), "sample_hz must be > 0"));
}

}  // namespace
}  // namespace deb
