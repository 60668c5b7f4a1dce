// `breakdown: channels`: the part of each source channel. On the thesis
// budget (seven independent geophones) the parts add up to the contributor
// exactly, and each equals the exact variance of that geophone alone (the
// same source on one path input, `inputs: [z3]`, integrated on its own); with correlated channels
// the cross terms are the rest, against the closed form.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contributor_of.h"

namespace deb {
namespace {

const std::string kThesis = std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_h210.yaml";

using test::ContributorOf;

}  // namespace

TEST_CASE("seven independent geophones: the parts add up to the contributor and each is that geophone alone") {
  const BudgetResult r = Evaluate(LoadBudgetFile(kThesis));
  for (const OutputResult& o : r.outputs) {
    const ContributorResult& c = ContributorOf(o, "sensor_noise");
    REQUIRE(c.channels.size() == 7);
    double sum = 0.0;
    for (const auto& p : c.channels) sum += p.variance;
    CHECK(std::abs(sum / c.variance - 1.0) < 1e-12);
    CHECK(c.cross_variance == 0.0);
    for (std::size_t k = 0; k < c.cps.size(); k += 50) {
      double at = 0.0;
      for (const auto& p : c.channels) at += p.cps[k];
      CHECK(std::abs(at - c.cps[k]) <= 1e-12 * c.variance);
    }
  }
  // Each geophone alone: one channel of the same noise into its own input.
  const std::vector<std::string> geophones = {"x1", "z1", "y2", "x3", "z3", "y4", "z4"};
  for (std::size_t j = 0; j < geophones.size(); ++j) {
    const BudgetResult one = Evaluate(LoadBudgetFile(
        kThesis, {{"sources[1].channels", "[" + geophones[j] + "]"},
                  {"contributors[1]", "{name: sensor_noise, source: geophone_noise, path: avis.sensor_noise, inputs: [" +
                                          geophones[j] + "]}"}}));
    for (std::size_t o = 0; o < r.outputs.size(); ++o) {
      const ContributorResult& part = ContributorOf(r.outputs[o], "sensor_noise");
      const ContributorResult& alone = ContributorOf(one.outputs[o], "sensor_noise");
      const double whole = part.variance;
      // Against the geophone alone, integrated on its own grid (the reduced single-input path gets its
      // own automatic grid of ~46 points per decade, the power-law rule on its PSD, where the part splits
      // the contributor's CPS interval by interval): measured up to 2.3e-5 of the whole contributor, so
      // 1e-4 (parts of 1e-32 are zero by symmetry). The single input leaves a numerically zero pole that
      // the Lyapunov solve refuses, so the grid figure is the reference here.
      CHECK_MESSAGE(std::abs(part.channels[j].variance - alone.variance) <= 1e-4 * whole,
                    r.outputs[o].name << ", " << geophones[j]);
    }
  }
}

TEST_CASE("correlated channels: the channel parts plus the cross terms make the contributor, the cross term in closed form") {
  // Two channels of white noise (level 1, correlation rho) into a path that adds them: y = u1 + u2 through
  // a first-order low-pass. var y = (1 + 1 + 2 rho) V with V the variance of one channel alone.
  const std::string budget = R"(name: corr
grid: {type: log, min_hz: 0.001, max_hz: 1000000, points: 4000}
sources:
  - {name: n, unit: um, channels: [a, b], correlation: 0.6, spectrum: {type: flat, level: 1}}
paths:
  - name: p
    type: state_space
    A: [[-10]]
    B: [[10, 10]]
    C: [[1]]
    D: [[0, 0]]
    inputs: [a, b]
    input_unit: um
    output_unit: um
    outputs: [y]
contributors:
  - {name: c, source: n, path: p, breakdown: channels}
outputs:
  - {name: y, signal: y, unit: um}
)";
  const BudgetResult r = Evaluate(LoadBudgetText(budget, "b.yaml"));
  const ContributorResult& c = r.outputs[0].contributors[0];
  REQUIRE(c.channels.size() == 2);
  const double v = c.channels[0].variance;
  CHECK(std::abs(c.channels[1].variance / v - 1.0) < 1e-12);
  CHECK(std::abs(c.cross_variance / (2 * 0.6 * v) - 1.0) < 1e-9);
  CHECK(std::abs((c.channels[0].variance + c.channels[1].variance + c.cross_variance) / c.variance - 1.0) < 1e-12);
  // One channel of the low-pass 10/(s + 10) under white one-sided level 1: V = 10 / 4 = 2.5 (to the grid's tails).
  CHECK(std::abs(v / 2.5 - 1.0) < 1e-3);
}

TEST_CASE("independent channels on clustered modes: each part is its mode's closed form, as accurate as the total") {
  // Channel a drives a unit mass at 10 Hz, channel b one at 10.05 Hz, zeta 1e-3 (five half-power bands
  // apart); y = x1 + x2. Under a white one-sided force PSD S0, one mode alone gives S0 / (8 zeta wn^3).
  // Parts split from the contributor's CPS in proportion to the end points of each interval were off by
  // 1e-3 of a part here; integrated on the grid's own rule they are as accurate as the total.
  const double zeta = 1e-3, f1 = 10.0, f2 = 10.05, s0 = 1.0;
  const double w1 = 2 * M_PI * f1, w2 = 2 * M_PI * f2;
  char a[256];
  std::snprintf(a, sizeof a, "[[0, 1, 0, 0], [%.17g, %.17g, 0, 0], [0, 0, 0, 1], [0, 0, %.17g, %.17g]]", -w1 * w1,
                -2 * zeta * w1, -w2 * w2, -2 * zeta * w2);
  const std::string budget = std::string("name: clustered\nsources:\n"
                                         "  - {name: n, unit: N, channels: [a, b], spectrum: {type: flat, quantity: psd, level: 1}}\n"
                                         "paths:\n  - name: p\n    type: state_space\n    A: ") +
                             a +
                             "\n    B: [[0, 0], [1, 0], [0, 0], [0, 1]]\n    C: [[1, 0, 1, 0]]\n    D: [[0, 0]]\n"
                             "    inputs: [a, b]\n    input_unit: N\n    output_unit: m\n    outputs: [y]\n"
                             "contributors:\n  - {name: c, source: n, path: p, breakdown: channels}\n"
                             "outputs:\n  - {name: y, signal: y, unit: m}\n";
  const BudgetResult r = Evaluate(LoadBudgetText(budget, "b.yaml"));
  const ContributorResult& c = r.outputs[0].contributors[0];
  REQUIRE(c.channels.size() == 2);
  const double v1 = s0 / (8 * zeta * w1 * w1 * w1), v2 = s0 / (8 * zeta * w2 * w2 * w2);
  REQUIRE(c.exact_variance.has_value());
  CHECK(std::abs(*c.exact_variance / (v1 + v2) - 1.0) < 1e-9);
  // The grid's figures cover 0.1..1000 Hz: without the tails below (S0 f_min / wn^4, 1.3e-5 of a part)
  // and above (S0 / (3 (2 pi)^4 f_max^3)), to (f_min / f_n)^2 = 1e-4 of the tails.
  const double f_min = r.grid.min_hz(), f_max = r.grid.max_hz();
  const auto on_grid = [&](double v, double wn) {
    return v - s0 * f_min / (wn * wn * wn * wn) - s0 / (3 * std::pow(2 * M_PI, 4) * f_max * f_max * f_max);
  };
  const double g1 = on_grid(v1, w1), g2 = on_grid(v2, w2);
  const double total_error = std::abs(c.variance / (g1 + g2) - 1.0);
  const double e1 = std::abs(c.channels[0].variance / g1 - 1.0), e2 = std::abs(c.channels[1].variance / g2 - 1.0);
  MESSAGE("total " << total_error << ", parts " << e1 << ", " << e2);
  CHECK(total_error < 1e-6);
  CHECK(e1 < 1e-6);
  CHECK(e2 < 1e-6);
  CHECK(c.cross_variance == 0.0);
  CHECK(std::abs((c.channels[0].variance + c.channels[1].variance) / c.variance - 1.0) < 1e-12);
}

TEST_CASE("an unknown breakdown is a located error") {
  try {
    LoadBudgetFile(kThesis, {{"contributors[1].breakdown", "geophones"}});
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("contributors[1].breakdown") != std::string::npos);
    CHECK(std::string(e.what()).find("the one breakdown is 'channels'") != std::string::npos);
  }
}

}  // namespace deb
