#include "deb/budget/sensitivity.h"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "deb/core/integrate.h"
#include "deb/core/math_constants.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

// White S0 through 1/(tau s + 1) on a fixed log grid 1e-4...1e6 Hz:
// variance S0 / (4 tau) up to what lies outside the grid (< 1e-4 here).
Budget LowPass(double s0, double tau) {
  Budget b;
  b.name = "sensitivity";
  b.grid.kind = GridKind::kLog;
  b.grid.auto_options.min_hz = 1e-4;
  b.grid.auto_options.max_hz = 1e6;
  b.grid.points = 20000;
  Source s;
  s.name = "w";
  s.unit = "N";
  s.channel_names = {"w"};
  s.spectrum = std::make_shared<FlatSpectrum>(s0);
  Path p;
  p.name = "lag";
  p.system = ToStateSpace(TransferFunction({1.0}, {tau, 1.0}));
  p.input_names = {"u"};
  p.output_names = {"y"};
  p.input_units = {"N"};
  p.output_units = {"um"};
  b.sources = {s};
  b.paths = {p};
  b.contributors = {{"c", "w", "lag", ExactVariance::kAuto, {}, {}, false}};
  Output o;
  o.name = "y";
  o.signal = "y";
  o.unit = "um";
  b.outputs = {o};
  return b;
}

}  // namespace

TEST_CASE("central differences give the elasticities of S0 / (4 tau): +1 in the level, -1 in the time constant") {
  const double s0 = 2.0, tau = 0.01, h = 1e-3;
  const BudgetResult nominal = Evaluate(LowPass(s0, tau));
  const auto level = Sensitivities("level", h, nominal, Evaluate(LowPass(s0 * (1 + h), tau)),
                                   Evaluate(LowPass(s0 * (1 - h), tau)));
  REQUIRE(level.size() == 2);  // total and the one contributor
  CHECK(level[0].contributor == "total");
  // Linear in p is exponential in ln p: the central difference is 1 + h^2/3 + O(h^4) off.
  CHECK(level[0].elasticity == doctest::Approx(1.0).epsilon(1e-6));
  const auto time_constant = Sensitivities("tau", h, nominal, Evaluate(LowPass(s0, tau * (1 + h))),
                                           Evaluate(LowPass(s0, tau * (1 - h))));
  // Truncation O(h^2) = 1e-6; the grid's missing tails move with tau by < 1e-4.
  CHECK(time_constant[1].elasticity == doctest::Approx(-1.0).epsilon(2e-4));
  CHECK(time_constant[1].d_variance_d_log_p == doctest::Approx(-s0 / (4.0 * tau)).epsilon(3e-4));
  const auto ranked = RankedForOutput(time_constant, "y");
  CHECK(ranked.size() == 2);
  CHECK(ranked[0].contributor == "total");  // the total leads, whatever the contributors' magnitudes
  CHECK(RankedForOutput(time_constant, "none").empty());
}

TEST_CASE("the sensitivity driver differences budgets scaled about the nominal: d var / d ln S = var for a flat level") {
  // var = S0 / (4 tau): linear in S0, so d var / d ln S0 = var (to h^2 / 3),
  // and d var / d ln tau = -var.
  const double s0 = 2.0, tau = 0.01, h = 1e-3;
  std::vector<std::pair<std::string, double>> asked;
  const ScaledBudget scaled = [&](const std::string& key, double factor) {
    asked.push_back({key, factor});
    return key == "level" ? LowPass(s0 * factor, tau) : LowPass(s0, tau * factor);
  };
  EngineOptions serial;
  serial.threads = 1;  // `asked` is not guarded
  const SensitivityStudy study =
      ComputeSensitivities(LowPass(s0, tau), {"level", "tau"}, h, scaled, serial, SensitivityMode::kCentralDifferences);
  CHECK(asked == std::vector<std::pair<std::string, double>>{{"level", 1 + h}, {"level", 1 - h}, {"tau", 1 + h},
                                                             {"tau", 1 - h}});
  REQUIRE(study.sensitivities.size() == 4);  // per parameter: total and the one contributor
  REQUIRE(study.methods.size() == 2);
  CHECK_FALSE(study.methods[1].exact);
  const double var = study.nominal.outputs[0].variance;
  CHECK(var == doctest::Approx(s0 / (4.0 * tau)).epsilon(1e-4));
  for (int i : {0, 1}) {
    CHECK(study.sensitivities[i].parameter == "level");
    CHECK(study.sensitivities[i].d_variance_d_log_p == doctest::Approx(var).epsilon(1e-6));
    CHECK(study.sensitivities[i].elasticity == doctest::Approx(1.0).epsilon(1e-6));
  }
  CHECK(study.sensitivities[2].parameter == "tau");
  CHECK(study.sensitivities[2].elasticity == doctest::Approx(-1.0).epsilon(2e-4));
  // The perturbed budgets are evaluated on the nominal grid: the same as
  // differencing results evaluated on it.
  Budget up = LowPass(s0, tau * (1 + h)), down = LowPass(s0, tau * (1 - h));
  for (Budget* b : {&up, &down}) {
    b->grid = GridSpec();
    b->grid.kind = GridKind::kExplicit;
    b->grid.f_hz = study.nominal.grid.f_hz();
    b->grid.panel_starts = study.nominal.grid.panel_starts();
  }
  const auto direct = Sensitivities("tau", h, study.nominal, Evaluate(up), Evaluate(down));
  CHECK(study.sensitivities[3].d_variance_d_log_p == direct[1].d_variance_d_log_p);
}

TEST_CASE("a parameter of the realisation alone is differentiated exactly; one of the source by central differences") {
  // d var / d ln tau of the grid's variance: against the grid's own integral
  // of the closed-form dS/d ln tau = -2 S0 (omega tau)^2 / (1 + (omega tau)^2)^2
  // (the same grid and rule, so to rounding), and against the closed form
  // -S0 / (4 tau) to what lies outside the grid.
  const double s0 = 2.0, tau = 0.01, h = 1e-3;
  const ScaledBudget scaled = [&](const std::string& key, double factor) {
    return key == "level" ? LowPass(s0 * factor, tau) : LowPass(s0, tau * factor);
  };
  const SensitivityStudy study = ComputeSensitivities(LowPass(s0, tau), {"level", "tau"}, h, scaled);
  REQUIRE(study.methods.size() == 2);
  CHECK_FALSE(study.methods[0].exact);
  CHECK(study.methods[0].note.find("source") != std::string::npos);
  CHECK(study.methods[1].exact);
  CHECK(study.methods[1].note.find("'lag'") != std::string::npos);
  REQUIRE(study.sensitivities.size() == 4);
  const Sensitivity& exact = study.sensitivities[3];
  CHECK(exact.exact);
  CHECK(exact.contributor == "c");
  const FrequencyGrid& grid = study.nominal.grid;
  const std::vector<double>& psd = study.nominal.outputs[0].contributors[0].psd;
  const std::vector<double> q = IntegralGradientWeights(grid, psd);
  double reference = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const double wt = 2.0 * kPi * grid.f_hz()[k] * tau;
    // um: the path's output is in um and the output too; S0 one-sided in N^2/Hz.
    reference += q[k] * (-2.0 * psd[k] * wt * wt / (1.0 + wt * wt));
  }
  CHECK(exact.d_variance_d_log_p == doctest::Approx(reference).epsilon(1e-12));
  CHECK(exact.d_variance_d_log_p == doctest::Approx(-s0 / (4.0 * tau)).epsilon(2e-4));
  CHECK(study.sensitivities[2].d_variance_d_log_p == exact.d_variance_d_log_p);  // the total: one contributor
  // The central difference agrees to its truncation, O(h^2).
  const SensitivityStudy cd =
      ComputeSensitivities(LowPass(s0, tau), {"tau"}, h, scaled, {}, SensitivityMode::kCentralDifferences);
  CHECK(cd.sensitivities[1].d_variance_d_log_p == doctest::Approx(reference).epsilon(2e-6));
}

}  // namespace deb


namespace deb {

TEST_CASE("an output's sensitivities list the totals first, then the contributors, each by magnitude") {
  // Two contributors cancel in the total: they move more than it does.
  const std::vector<Sensitivity> all = {{"k", "y", "nm", "total", 1.0, 0.1, 0.1},
                                        {"k", "y", "nm", "a", 0.5, 3.0, 6.0},
                                        {"k", "y", "nm", "b", 0.5, -2.9, -5.8},
                                        {"m", "y", "nm", "total", 1.0, -0.5, -0.5},
                                        {"m", "z", "nm", "total", 1.0, 9.0, 9.0}};
  const auto ranked = RankedForOutput(all, "y");
  REQUIRE(ranked.size() == 4);
  CHECK(ranked[0].parameter == "m");
  CHECK(ranked[0].contributor == "total");
  CHECK(ranked[1].parameter == "k");
  CHECK(ranked[1].contributor == "total");
  CHECK(ranked[2].contributor == "a");
  CHECK(ranked[3].contributor == "b");
}

}  // namespace deb
