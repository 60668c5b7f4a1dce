#include "deb/budget/sweep_ranking.h"

#include <algorithm>

#include "deb/core/error.h"

namespace deb {

std::size_t BestVariant(const std::vector<BudgetResult>& results, std::size_t output) {
  DEB_DEMAND(!results.empty() && output < results.front().outputs.size());
  std::size_t best = 0;
  for (std::size_t i = 1; i < results.size(); ++i)
    if (results[i].outputs[output].rms() < results[best].outputs[output].rms()) best = i;
  return best;
}

std::vector<VariantScore> RankVariants(const std::vector<BudgetResult>& results) {
  std::vector<VariantScore> scores;
  if (results.empty()) return scores;
  const std::size_t outputs = results.front().outputs.size();
  std::vector<double> highest(outputs, 0.0);
  for (const BudgetResult& r : results)
    for (std::size_t o = 0; o < outputs; ++o) highest[o] = std::max(highest[o], r.outputs[o].rms());
  for (std::size_t i = 0; i < results.size(); ++i) {
    VariantScore s;
    s.variant = i;
    for (std::size_t o = 0; o < outputs; ++o) {
      const OutputResult& out = results[i].outputs[o];
      s.failing += out.AllPass() ? 0 : 1;
      if (out.rms_max && *out.rms_max > 0.0) s.worst_utilisation = std::max(s.worst_utilisation, out.rms() / *out.rms_max);
      for (const auto& b : out.band_requirements)
        if (b.requirement.rms_max > 0.0)
          s.worst_utilisation = std::max(s.worst_utilisation, b.rms() / b.requirement.rms_max);
      s.relative_rms += highest[o] > 0.0 ? out.rms() / highest[o] : 0.0;
    }
    scores.push_back(s);
  }
  std::stable_sort(scores.begin(), scores.end(), [](const VariantScore& a, const VariantScore& b) {
    if (a.failing != b.failing) return a.failing < b.failing;
    if (a.worst_utilisation != b.worst_utilisation) return a.worst_utilisation < b.worst_utilisation;
    return a.relative_rms < b.relative_rms;
  });
  return scores;
}

}  // namespace deb
