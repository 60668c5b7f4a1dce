#include "deb/budget/sensitivity.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/parallel.h"

namespace deb {

std::vector<Sensitivity> Sensitivities(const std::string& parameter, double relative_step, const BudgetResult& nominal,
                                       const BudgetResult& up, const BudgetResult& down) {
  DEB_DEMAND(relative_step > 0.0 && relative_step < 1.0);
  DEB_DEMAND(up.outputs.size() == nominal.outputs.size() && down.outputs.size() == nominal.outputs.size());
  const double dlog = std::log1p(relative_step) - std::log1p(-relative_step);
  std::vector<Sensitivity> out;
  auto add = [&](const OutputResult& o, const std::string& contributor, double v0, double vu, double vd) {
    Sensitivity s;
    s.parameter = parameter;
    s.output = o.name;
    s.unit = o.unit;
    s.contributor = contributor;
    s.variance = v0;
    s.d_variance_d_log_p = (vu - vd) / dlog;
    s.elasticity = v0 > 0.0 ? s.d_variance_d_log_p / v0 : 0.0;
    out.push_back(s);
  };
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& n = nominal.outputs[o];
    const OutputResult& u = up.outputs[o];
    const OutputResult& d = down.outputs[o];
    DEB_DEMAND(u.contributors.size() == n.contributors.size() && d.contributors.size() == n.contributors.size());
    add(n, "total", n.variance, u.variance, d.variance);
    for (std::size_t c = 0; c < n.contributors.size(); ++c)
      add(n, n.contributors[c].name, n.contributors[c].variance, u.contributors[c].variance,
          d.contributors[c].variance);
  }
  return out;
}

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
                                      double relative_step, const ScaledBudget& scaled, const EngineOptions& options) {
  SensitivityStudy study;
  study.nominal = Evaluate(budget, options);
  // Job 2k is parameter k scaled by 1 + h, job 2k + 1 by 1 - h.
  std::vector<BudgetResult> perturbed(2 * parameters.size());
  ParallelForEach(
      perturbed.size(),
      [&](std::size_t job) {
        Budget b = scaled(parameters[job / 2], job % 2 == 0 ? 1.0 + relative_step : 1.0 - relative_step);
        b.grid = GridSpec();
        b.grid.kind = GridKind::kExplicit;  // the nominal grid: no refinement noise in the difference
        b.grid.f_hz = study.nominal.grid.f_hz();
        b.grid.panel_starts = study.nominal.grid.panel_starts();
        if (b.bands.empty()) b.bands = budget.bands;
        perturbed[job] = Evaluate(b, options);
      },
      options.threads);
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const auto part = Sensitivities(parameters[k], relative_step, study.nominal, perturbed[2 * k], perturbed[2 * k + 1]);
    study.sensitivities.insert(study.sensitivities.end(), part.begin(), part.end());
  }
  return study;
}

}  // namespace deb
