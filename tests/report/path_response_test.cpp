// deb/budget/path_response.h, tested here because it needs the YAML loader
// (deb_load) for the example budgets, which the budget layer's tests do not link.
#include "deb/budget/path_response.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// sum_k |h_k|^2 S_kk must be the engine's PSD for uncorrelated channels.
void CheckAgainstEngine(const Budget& budget) {
  const BudgetResult result = Evaluate(budget);
  const std::vector<double>& f = result.grid.f_hz();
  for (std::size_t c = 0; c < budget.contributors.size(); ++c) {
    const Source& source = budget.FindSource(budget.contributors[c].source);
    REQUIRE(source.spectrum->IsDiagonal());
    for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
      const PathResponse r = ComputePathResponse(budget, result, c, o, f);
      REQUIRE(r.gain2.size() == static_cast<std::size_t>(source.channels()));
      const std::vector<double>& engine = result.outputs[o].contributors[c].psd;
      double worst = 0.0;
      for (std::size_t i = 0; i < f.size(); ++i) {
        const Eigen::VectorXd s = source.spectrum->Psd(f[i]);
        double psd = 0.0;
        for (std::size_t k = 0; k < r.gain2.size(); ++k) psd += r.gain2[k][i] * s(static_cast<Eigen::Index>(k));
        if (engine[i] > 0.0) worst = std::max(worst, std::abs(psd - engine[i]) / engine[i]);
        else CHECK(psd == 0.0);
      }
      CHECK_MESSAGE(worst < 1e-12, budget.contributors[c].name << " -> " << budget.outputs[o].name);
    }
  }
}

}  // namespace

TEST_CASE("path response times the source PSD, summed over channels, is the engine's contributor PSD") {
  CheckAgainstEngine(LoadBudgetFile(test::ExampleBudget()));
}

TEST_CASE("path response carries the unit conversion and the weighting: a unit gain seen in nm through 1/(s+1)") {
  // um/s through a unit gain, weighted by 1/(s + 1) [s], read in nm:
  // |h|^2 = (1e3)^2 / (1 + (2 pi f)^2).
  const Budget budget = LoadBudgetText(R"(
name: weighted
grid: {type: log, min_hz: 0.1, max_hz: 100, points: 40}
sources:
  - {name: v, unit: um/s, channels: [a, b], spectrum: {type: flat, level: 2}}
paths:
  - {name: g, type: gain, gain: [[1, 3]], input_unit: um/s, output_unit: um/s, outputs: [y]}
contributors:
  - {name: c, source: v, path: g}
outputs:
  - {name: pos, signal: y, unit: nm, weighting: {num: [1], den: [1, 1], unit: s}}
)",
                                       "weighted.yaml");
  const std::vector<double> f = {0.1, 1.0, 10.0};
  const PathResponse r = ComputePathResponse(budget, Evaluate(budget), 0, 0, f);
  CHECK(r.channels == std::vector<std::string>{"a", "b"});
  CHECK(r.unit == "nm/(um/s)");
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double w = kTwoPi * f[i];
    CHECK(r.gain2[0][i] == doctest::Approx(1e6 / (1.0 + w * w)).epsilon(1e-12));
    CHECK(r.gain2[1][i] == doctest::Approx(9e6 / (1.0 + w * w)).epsilon(1e-12));
  }
  CheckAgainstEngine(budget);
}

TEST_CASE("a unit that differs by a time derivative enters the path response as (2 pi f)^2 per derivative") {
  // Example budget: sensor noise (um/s) to z_displacement (nm) integrates once.
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const std::vector<double> f = {0.5, 5.0};
  const BudgetResult result = Evaluate(budget);
  const PathResponse velocity = ComputePathResponse(budget, result, 1, 0, f);
  const PathResponse displacement = ComputePathResponse(budget, result, 1, 1, f);
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double w = kTwoPi * f[i];
    CHECK(displacement.gain2[0][i] == doctest::Approx(velocity.gain2[0][i] * 1e6 / (w * w)).epsilon(1e-12));
  }
}

}  // namespace deb
