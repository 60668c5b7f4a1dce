// deb/budget/realisation_gradient.h on budgets loaded from their files: the
// exact derivatives of every variance against central differences on the
// same grid, extrapolated (Richardson, steps 4 %, 2 % and 1 %: truncation
// O(h^6)), and the parameters it must leave to central differences.
//
// Why not a step of 1e-3: a variance is evaluated to ~1e-12 of itself (the
// frequency response's rounding near a resonance), and a term whose
// derivative is 1e-5 of its variance (the flexure's damping on the floor's
// 1 Hz motion) then has a difference quotient noisy by 1e-4 at h = 1e-3.
// The exact derivative has no such noise; the reference's is measured as
// the difference of two extrapolations.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "deb/budget/sensitivity.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/sweep_yaml.h"

namespace deb {
namespace {

std::string Example(const std::string& name) { return std::string(DEB_SOURCE_DIR) + "/budgets/" + name; }

SensitivityStudy Study(const std::string& file, const std::vector<std::string>& parameters, double h,
                       SensitivityMode mode) {
  const ScaledBudget scaled = [&](const std::string& key, double factor) {
    return LoadBudgetWithScaledParameter(file, key, factor);
  };
  return ComputeSensitivities(LoadBudgetFile(file), parameters, h, scaled, {}, mode);
}

// Every derivative of `exact` (each parameter by the realisation's
// derivative where `exact_expected`) equals the extrapolated central
// difference to 1e-6 of itself, or within twice the reference's own scatter
// (the same extrapolation from steps twice as large) where that is larger:
// a term whose derivative is a small part of its variance has a reference
// no better than that.
void CheckAgainstCentralDifferences(const std::string& file, const std::vector<std::string>& parameters,
                                    const std::vector<bool>& exact_expected) {
  const SensitivityStudy exact = Study(file, parameters, 1e-3, SensitivityMode::kExactWherePossible);
  std::vector<SensitivityStudy> cd;
  for (double h : {0.08, 0.04, 0.02, 0.01}) cd.push_back(Study(file, parameters, h, SensitivityMode::kCentralDifferences));
  REQUIRE(exact.methods.size() == parameters.size());
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    INFO(parameters[k] << ": " << exact.methods[k].note);
    CHECK(exact.methods[k].exact == exact_expected[k]);
  }
  for (const SensitivityStudy& c : cd) REQUIRE(c.sensitivities.size() == exact.sensitivities.size());
  // The error is even in h: c2 h^2 + c4 h^4 + ...; two Richardson steps
  // from the steps 4h, 2h, h.
  const auto extrapolated = [&](std::size_t first, std::size_t i) {
    const double d0 = cd[first].sensitivities[i].d_variance_d_log_p;
    const double d1 = cd[first + 1].sensitivities[i].d_variance_d_log_p;
    const double d2 = cd[first + 2].sensitivities[i].d_variance_d_log_p;
    return (16.0 * (4.0 * d2 - d1) / 3.0 - (4.0 * d1 - d0) / 3.0) / 15.0;
  };
  double largest_relative = 0.0;
  int within_scatter = 0;
  for (std::size_t i = 0; i < exact.sensitivities.size(); ++i) {
    const Sensitivity& e = exact.sensitivities[i];
    const double reference = extrapolated(1, i);                  // 4, 2, 1 %
    const double scatter = std::abs(extrapolated(0, i) - reference);  // against 8, 4, 2 %
    INFO(e.parameter << " on " << e.output << " / " << e.contributor << ": " << e.d_variance_d_log_p << " vs "
                     << reference << " (scatter " << scatter << ")");
    const double difference = std::abs(e.d_variance_d_log_p - reference);
    CHECK(difference <= std::max(1e-6 * std::abs(reference), 2.0 * scatter) + 1e-300);
    if (difference > 1e-6 * std::abs(reference)) ++within_scatter;
    if (reference != 0.0) largest_relative = std::max(largest_relative, difference / std::abs(reference));
  }
  MESSAGE(file << ": " << exact.sensitivities.size() << " derivatives, largest relative difference "
               << largest_relative << "; " << within_scatter << " beyond 1e-6 but within the reference's scatter");
}

}  // namespace

TEST_CASE("thesis budget: every parameter's derivatives equal central differences to 1e-6") {
  // k_h, c_iso, Kv and h enter the isolation model's realisation: exact.
  // s_geo is the geophones' noise level, a source: central differences, and
  // the geophone contributor's variance is linear in it (d var / d ln s = var).
  const std::string file = Example("nizamoglu2015_tolerances.yaml");
  CheckAgainstCentralDifferences(file, {"k_h", "c_iso", "s_geo", "Kv", "h"}, {true, true, false, true, true});
  const SensitivityStudy s = Study(file, {"s_geo"}, 1e-3, SensitivityMode::kExactWherePossible);
  CHECK(s.methods[0].note.find("source") != std::string::npos);
  int linear = 0;
  for (const Sensitivity& x : s.sensitivities)
    if (x.contributor == "sensor_noise") {  // the geophones' noise alone
      CHECK(x.elasticity == doctest::Approx(1.0).epsilon(1e-6));  // ln-step central difference: 1 - h^2/3
      ++linear;
    }
  CHECK(linear > 0);
}

TEST_CASE("optical table: masses, flexure and loop parameters through a PID loop, with a tone, exactly") {
  // The ripple source is a tone at 50 Hz: its variance |H(f0) a|^2 is
  // differentiated with the rest.
  CheckAgainstCentralDifferences(Example("optical_table.yaml"), {"m_table", "f_flex", "zeta_flex", "f_c"},
                                 {true, true, true, true});
}

TEST_CASE("a parameter of a sampled or delayed loop is left to central differences, saying why") {
  const SensitivityStudy s =
      Study(Example("wafer_stage.yaml"), {"f_c", "t_io"}, 1e-3, SensitivityMode::kExactWherePossible);
  for (const SensitivityMethod& m : s.methods) {
    INFO(m.parameter << ": " << m.note);
    CHECK_FALSE(m.exact);
    CHECK(m.note.rfind("central differences: ", 0) == 0);
  }
}

}  // namespace deb
