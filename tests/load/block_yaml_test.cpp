// Control blocks as path types (block_yaml.h): each loads to its formula, in
// the path's units, from numbers or expressions of parameters.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/systems/frequency_response.h"
#include "tests/support/contains.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using test::Contains;
using Complex = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

// A force on a mass (2 kg on 800 N/m and 4 N s/m, 3.18 Hz), measured in um,
// and a PID with a low-pass, all from parameters.
const char* kBlocks = R"(name: blocks
parameters:
  m: 2000 g
  k: 800 N/m
  d: 4 N s/m
  f_c: 50 Hz
grid: {type: log, min_hz: 0.1, max_hz: 1000, points: 400}
sources:
  - {name: force, unit: N, spectrum: {type: flat, quantity: asd, level: 0.01}}
paths:
  - {name: plant, type: mass_spring_damper, m: m, k: k, d: d, input_unit: N, output_unit: um, outputs: [x]}
  - {name: controller, type: pid, gain: 1e-3, f_i_hz: f_c/10, f_d_hz: f_c/3, f_lp_hz: 3*f_c, input_unit: um, output_unit: N}
  - {name: resonance, type: second_order, f_hz: 40, zeta: 0.05, gain: 2, input_unit: N, output_unit: N}
  - {name: filter, type: lowpass, f_hz: 200, order: 4, shape: bessel, input_unit: N, output_unit: N}
  - {name: lead, type: lead_lag, f_hz: f_c, phase_deg: 0.5 rad, input_unit: N, output_unit: N}
  - {name: dip, type: notch, f_hz: 50, depth_db: 30, width_hz: 4, input_unit: N, output_unit: N}
  - {name: shaped, type: zpk, zeros: [10], poles: [1, {f_hz: 100, zeta: 0.1}], gain_at: {f_hz: 1, value: 2}, input_unit: N, output_unit: N}
  - {name: slow, type: integrator, f_hz: 1, input_unit: N, output_unit: N}
  - {name: edge, type: highpass, f_hz: 5, order: 2, input_unit: N, output_unit: N}
contributors:
  - {name: force, source: force, path: plant}
outputs:
  - {name: x, signal: x, unit: um}
)";

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { LoadBudgetText(text, "b.yaml"); });
}

const Path& Find(const Budget& b, const std::string& name) {
  for (const Path& p : b.paths)
    if (p.name == name) return p;
  FAIL("no path " << name);
  return b.paths.front();
}

Complex At(const Budget& b, const std::string& path, double f_hz) {
  return FrequencyResponse(Find(b, path).system).At(f_hz)(0, 0);
}

TEST_CASE("blocks load to their formulas, in the path's units") {
  const Budget b = LoadBudgetText(kBlocks, "b.yaml");
  for (double f : {0.1, 1.0, 3.18, 10.0, 100.0}) {
    CAPTURE(f);
    const Complex s(0.0, 2 * kPi * f);
    // 2000 g is 2 kg; N to um: 1e6 times the SI response.
    const Complex plant = 1e6 / (2.0 * s * s + 4.0 * s + 800.0);
    CHECK(std::abs(At(b, "plant", f) - plant) <= 1e-9 * std::abs(plant));
    const double wi = 2 * kPi * 5.0, wd = 2 * kPi * 50.0 / 3.0, wlp = 2 * kPi * 150.0;
    const Complex pid = 1e-3 * (1.0 + wi / s) * (1.0 + s / wd) / (1.0 + s / wlp);
    CHECK(std::abs(At(b, "controller", f) - pid) <= 1e-9 * std::abs(pid));
    const double w = 2 * kPi * 40.0;
    const Complex resonance = 2.0 * w * w / (s * s + 2 * 0.05 * w * s + w * w);
    CHECK(std::abs(At(b, "resonance", f) - resonance) <= 1e-9 * std::abs(resonance));
  }
  CHECK(std::abs(std::abs(At(b, "filter", 200.0)) - std::sqrt(0.5)) <= 1e-9);
  CHECK(std::abs(std::arg(At(b, "lead", 50.0)) - 0.5) <= 1e-9);  // 0.5 rad of lead at f_c
  CHECK(std::abs(std::abs(At(b, "dip", 50.0)) - std::pow(10.0, -1.5)) <= 1e-9);
  CHECK(std::abs(std::abs(At(b, "shaped", 1.0)) - 2.0) <= 1e-9);
  CHECK(std::abs(std::abs(At(b, "slow", 1.0)) - 1.0) <= 1e-9);
  CHECK(std::abs(std::abs(At(b, "edge", 5.0)) - std::sqrt(0.5)) <= 1e-9);
}

TEST_CASE("a block and the transfer function it stands for give the same budget") {
  const std::string literal = Replace(kBlocks,
                                      "{name: plant, type: mass_spring_damper, m: m, k: k, d: d, input_unit: N,",
                                      "{name: plant, type: transfer_function, num: [1e6], den: [2, 4, 800], input_unit: N,");
  const double a = Evaluate(LoadBudgetText(kBlocks, "a.yaml")).outputs[0].rms();
  const double b = Evaluate(LoadBudgetText(literal, "b.yaml")).outputs[0].rms();
  CHECK(a == doctest::Approx(b).epsilon(1e-12));
}

TEST_CASE("bad blocks: the key and the rule") {
  CHECK(Contains(ErrorOf(Replace(kBlocks, "input_unit: N, output_unit: um, outputs: [x]",
                                 "input_unit: N, output_unit: um/s, outputs: [x]")),
                 "paths[0].output_unit: a mass_spring_damper is N to m: 'um/s' is not the same quantity as 'm'"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "m: m, k: k", "m: k, k: k")),
                 "paths[0].m: 'k' is a quantity in kg s-2; this value is in kg"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "gain: 1e-3, f_i_hz", "kp: 1, gain: 1e-3, f_i_hz")),
                 "paths[1]: a pid is parallel (kp, ki, kd) or series (gain, f_i_hz, f_d_hz), not both"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "shape: bessel", "shape: chebyshev")),
                 "paths[3].shape: filter shape 'chebyshev' is not known; allowed: butterworth, bessel"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "order: 4", "order: 12")), "paths[3]: filter order must be 1 to 10, not 12"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "phase_deg: 0.5 rad", "phase_deg: 95")), "between -90 and 90"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "gain_at: {f_hz: 1, value: 2}", "gain: 1, gain_at: {f_hz: 1, value: 2}")),
                 "give gain or gain_at, not both"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "type: integrator, f_hz: 1", "type: integrator, f_hz: 1, zeta: 2")),
                 "unknown key 'zeta'"));
  CHECK(Contains(ErrorOf(Replace(kBlocks, "zeros: [10]", "zeros: [10 rad/s]")), "give frequencies in Hz, not rad/s"));
}

}  // namespace
}  // namespace deb
