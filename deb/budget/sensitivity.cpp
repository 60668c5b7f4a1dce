#include "deb/budget/sensitivity.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "deb/budget/realisation_gradient.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"

namespace deb {

namespace {

// One entry: the nominal variance v0 and its derivative d.
Sensitivity Entry(const std::string& parameter, const OutputResult& o, const std::string& contributor, double v0,
                  double d, bool exact) {
  Sensitivity s;
  s.parameter = parameter;
  s.output = o.name;
  s.unit = o.unit;
  s.contributor = contributor;
  s.variance = v0;
  s.d_variance_d_log_p = d;
  s.elasticity = v0 > 0.0 ? d / v0 : 0.0;
  s.exact = exact;
  return s;
}

}  // namespace

std::vector<Sensitivity> Sensitivities(const std::string& parameter, double relative_step, const BudgetResult& nominal,
                                       const BudgetResult& up, const BudgetResult& down) {
  DEB_DEMAND(relative_step > 0.0 && relative_step < 1.0);
  DEB_DEMAND(up.outputs.size() == nominal.outputs.size() && down.outputs.size() == nominal.outputs.size());
  const double dlog = std::log1p(relative_step) - std::log1p(-relative_step);
  std::vector<Sensitivity> out;
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& n = nominal.outputs[o];
    const OutputResult& u = up.outputs[o];
    const OutputResult& d = down.outputs[o];
    DEB_DEMAND(u.contributors.size() == n.contributors.size() && d.contributors.size() == n.contributors.size());
    out.push_back(Entry(parameter, n, "total", n.variance, (u.variance - d.variance) / dlog, false));
    for (std::size_t c = 0; c < n.contributors.size(); ++c)
      out.push_back(Entry(parameter, n, n.contributors[c].name, n.contributors[c].variance,
                          (u.contributors[c].variance - d.contributors[c].variance) / dlog, false));
  }
  return out;
}

namespace {

// The entries of Sensitivities() from exact derivatives.
std::vector<Sensitivity> ExactSensitivities(const std::string& parameter, const BudgetResult& nominal,
                                            const RealisationGradient& g) {
  DEB_DEMAND(g.exact && g.d_variance.size() == nominal.outputs.size());
  std::vector<Sensitivity> out;
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& n = nominal.outputs[o];
    const std::vector<double>& d = g.d_variance[o];
    DEB_DEMAND(d.size() == n.contributors.size());
    double total = 0.0;  // the output's variance is the sum of its contributors'
    for (double x : d) total += x;
    out.push_back(Entry(parameter, n, "total", n.variance, total, true));
    for (std::size_t c = 0; c < n.contributors.size(); ++c)
      out.push_back(Entry(parameter, n, n.contributors[c].name, n.contributors[c].variance, d[c], true));
  }
  return out;
}

}  // namespace

std::vector<Sensitivity> RankedForOutput(const std::vector<Sensitivity>& all, const std::string& output) {
  std::vector<Sensitivity> r;
  for (const auto& s : all)
    if (s.output == output) r.push_back(s);
  std::stable_sort(r.begin(), r.end(), [](const Sensitivity& a, const Sensitivity& b) {
    const bool ta = a.contributor == "total", tb = b.contributor == "total";
    if (ta != tb) return ta;
    return std::abs(a.d_variance_d_log_p) > std::abs(b.d_variance_d_log_p);
  });
  return r;
}

SensitivityStudy ComputeSensitivities(const Budget& budget, const std::vector<std::string>& parameters,
                                      double relative_step, const ScaledBudget& scaled, const EngineOptions& options,
                                      SensitivityMode mode) {
  SensitivityStudy study;
  study.nominal = Evaluate(budget, options);
  const double h = relative_step;
  const bool try_exact = mode == SensitivityMode::kExactWherePossible;
  std::vector<std::vector<Sensitivity>> parts(parameters.size());
  study.methods.resize(parameters.size());
  ParallelForEach(
      parameters.size(),
      [&](std::size_t k) {
        const std::array<double, 4> factors = {1.0 + h, 1.0 - h, 1.0 + 0.5 * h, 1.0 - 0.5 * h};
        std::array<Budget, 4> b;
        for (std::size_t j = 0; j < (try_exact ? 4 : 2); ++j) {
          b[j] = scaled(parameters[k], factors[j]);
          b[j].grid = ExplicitGrid(study.nominal.grid);
          if (b[j].bands.empty()) b[j].bands = budget.bands;
        }
        SensitivityMethod& method = study.methods[k];
        method.parameter = parameters[k];
        if (try_exact) {
          const RealisationGradient g = ComputeRealisationGradient(budget, study.nominal, b, h, options);
          if (g.exact) {
            method.exact = true;
            method.note = g.note;
            parts[k] = ExactSensitivities(parameters[k], study.nominal, g);
            return;
          }
          method.note = "central differences: " + g.note;
        } else {
          method.note = "central differences (asked for)";
        }
        parts[k] = Sensitivities(parameters[k], h, study.nominal, Evaluate(b[0], options), Evaluate(b[1], options));
      },
      options.threads);
  for (const auto& part : parts) study.sensitivities.insert(study.sensitivities.end(), part.begin(), part.end());
  return study;
}

}  // namespace deb
