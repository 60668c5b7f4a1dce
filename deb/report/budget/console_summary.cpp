#include "deb/report/budget/console_summary.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/core/formatted_text.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot.h"

namespace deb::report {
namespace {

// Each group's RMS and share, indented by depth, after the contributors.
void AddGroups(std::string& text, const OutputResult& o, int digits) {
  const std::vector<GroupResult> groups = ComputeGroups(o);
  if (groups.empty()) return;
  AppendFormatted(text, "  %-24s %14s %8s\n", "group", "rms", "share");
  for (const GroupResult& g : groups) {
    const std::string label = std::string(2 * static_cast<std::size_t>(g.depth), ' ') + g.name;
    AppendFormatted(text, "  %-24s %14s %7.2f%%\n", label.c_str(), Sig(std::sqrt(g.variance), digits).c_str(),
                    100.0 * g.share);
  }
}

// The correlation matrix of the budget's `covariance:` outputs (the
// covariance itself is in summary.json).
void AddCorrelation(std::string& text, const CovarianceResult& cov) {
  AppendFormatted(text, "\ncorrelation of outputs (covariance matrices in summary.json)\n  %-16s", "");
  for (const std::string& name : cov.outputs) AppendFormatted(text, " %12.12s", name.c_str());
  for (std::size_t a = 0; a < cov.outputs.size(); ++a) {
    AppendFormatted(text, "\n  %-16.16s", cov.outputs[a].c_str());
    for (std::size_t b = 0; b < cov.outputs.size(); ++b) {
      const double r = cov.correlation(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
      if (std::isfinite(r))
        AppendFormatted(text, " %12.3f", r);
      else
        AppendFormatted(text, " %12s", "-");
    }
  }
  AppendFormatted(text, "\n");
}

// One contributor's row, its top modes and its channel parts.
void AddContributor(std::string& text, const OutputResult& o, const ContributorResult& c, int digits) {
  const double share = o.variance > 0 ? 100.0 * c.variance / o.variance : 0.0;
  AppendFormatted(text, "  %-24s %14s %7.2f%% %14s\n", c.name.c_str(), Sig(std::sqrt(c.variance), digits).c_str(),
                  share, c.exact_variance ? Sig(std::sqrt(*c.exact_variance), digits).c_str() : "-");
  if (!c.top_modes.empty()) {  // a modal path: the modes that carry its exact variance
    std::string modes;
    for (std::size_t i = 0; i < c.top_modes.size() && i < 3; ++i)
      AppendFormatted(modes, "%smode %d, %.*g Hz: %.0f%%", i ? "; " : "", c.top_modes[i].mode, digits,
                      c.top_modes[i].f_hz, 100.0 * c.top_modes[i].share);
    AppendFormatted(text, "  %-24s %s\n", "", modes.c_str());
  }
  if (c.channels.empty()) return;
  // The breakdown: channels, largest first.
  std::vector<const ContributorResult::ChannelPart*> parts;
  for (const auto& p : c.channels) parts.push_back(&p);
  std::stable_sort(parts.begin(), parts.end(), [](const auto* a, const auto* b) { return a->variance > b->variance; });
  for (const auto* p : parts) {
    const std::string label = "  channel " + p->channel;
    const double v = std::max(WithoutRounding(p->variance, c.variance), 0.0);
    AppendFormatted(text, "  %-24s %14s %7.2f%%\n", label.c_str(), v > 0.0 ? Sig(std::sqrt(v), digits).c_str() : "0",
                    o.variance > 0 ? 100.0 * v / o.variance : 0.0);
  }
  if (c.cross_variance != 0.0)
    AppendFormatted(text, "  %-24s %14s %7.2f%%  (variance; correlation between channels)\n", "  cross terms",
                    Sig(c.cross_variance, digits).c_str(),
                    o.variance > 0 ? 100.0 * c.cross_variance / o.variance : 0.0);
}

void AddOutput(std::string& text, const OutputResult& o, const FrequencyGrid& grid, int digits) {
  AppendFormatted(text, "\noutput %s [%s]: rms %s", o.name.c_str(), o.unit.c_str(), Sig(o.rms(), digits).c_str());
  if (o.rms_max) AppendFormatted(text, "  (requirement %g: %s)", *o.rms_max, o.pass() ? "PASS" : "FAIL");
  AppendFormatted(text, "\n  %-24s %14s %8s %14s\n", "contributor", "rms", "share", "exact rms");
  for (std::size_t index : ShareOrder(o)) AddContributor(text, o, o.contributors[index], digits);  // as in the report
  AddGroups(text, o, digits);
  for (const ReferenceResult& ref : o.references) {
    const double budget = ref.budget_variance;
    AppendFormatted(text, "  reference %s (%g-%g Hz): measured rms %s, budget %s, measured/budget %s, unexplained %s\n",
                    ref.name.c_str(), ref.covered_lo_hz, ref.covered_hi_hz,
                    Sig(std::sqrt(ref.variance), digits).c_str(), Sig(std::sqrt(budget), digits).c_str(),
                    budget > 0 ? Sig(std::sqrt(ref.variance / budget), digits).c_str() : "-",
                    Sig(std::sqrt(std::max(ref.variance - budget, 0.0)), digits).c_str());
  }
  for (const auto& b : o.band_requirements)
    AppendFormatted(text, "  band %g-%g Hz: rms %s (requirement %g: %s)\n", b.requirement.lo_hz, b.requirement.hi_hz,
                    Sig(b.rms(), digits).c_str(), b.requirement.rms_max, b.pass() ? "PASS" : "FAIL");
  if (const auto g = GuideFailure(o, grid)) AppendFormatted(text, "  to fix: %s\n", g->sentence.c_str());
}

}  // namespace

std::string ConsoleSummary(const BudgetResult& r, std::optional<double> evaluation_seconds, int digits) {
  std::string text;
  AppendFormatted(text, "budget %s: %zu frequencies, %g-%g Hz", r.outline.name.c_str(), r.grid.size(), r.grid.min_hz(),
                  r.grid.max_hz());
  if (evaluation_seconds) AppendFormatted(text, ", evaluated in %.3f s", *evaluation_seconds);
  AppendFormatted(text, "\n");
  for (const OutputResult& o : r.outputs) AddOutput(text, o, r.grid, digits);
  if (r.covariance) AddCorrelation(text, *r.covariance);
  for (const LoopResult& loop : r.loops)
    if (const std::string checks = MarginChecksText(loop); !checks.empty())
      AppendFormatted(text, "loop %s closed by %s: %s\n", loop.plant.c_str(), loop.controller.c_str(), checks.c_str());
  return text;
}

}  // namespace deb::report
