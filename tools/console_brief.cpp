#include "tools/console_brief.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/report/figure/plot.h"
#include "deb/report/budget/spectrum_plots.h"

namespace deb::tools {
namespace {

// Each group's RMS and share, indented by depth, after the contributors.
void PrintGroups(const deb::OutputResult& o, int digits) {
  const std::vector<deb::GroupResult> groups = deb::ComputeGroups(o);
  if (groups.empty()) return;
  std::printf("  %-24s %14s %8s\n", "group", "rms", "share");
  for (const deb::GroupResult& g : groups) {
    const std::string label = std::string(2 * static_cast<std::size_t>(g.depth), ' ') + g.name;
    std::printf("  %-24s %14s %7.2f%%\n", label.c_str(), deb::report::Sig(std::sqrt(g.variance), digits).c_str(),
                100.0 * g.share);
  }
}

// The correlation matrix of the budget's `covariance:` outputs (the
// covariance itself is in summary.json).
void PrintCorrelation(const deb::CovarianceResult& cov) {
  std::printf("\ncorrelation of outputs (covariance matrices in summary.json)\n  %-16s", "");
  for (const std::string& name : cov.outputs) std::printf(" %12.12s", name.c_str());
  for (std::size_t a = 0; a < cov.outputs.size(); ++a) {
    std::printf("\n  %-16.16s", cov.outputs[a].c_str());
    for (std::size_t b = 0; b < cov.outputs.size(); ++b) {
      const double r = cov.correlation(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
      if (std::isfinite(r)) std::printf(" %12.3f", r);
      else std::printf(" %12s", "-");
    }
  }
  std::printf("\n");
}

}  // namespace

void PrintBrief(const deb::BudgetResult& r, std::optional<double> seconds, int digits) {
  std::printf("budget %s: %zu frequencies, %g-%g Hz", r.outline.name.c_str(), r.grid.size(), r.grid.min_hz(),
              r.grid.max_hz());
  if (seconds) std::printf(", evaluated in %.3f s", *seconds);
  std::printf("\n");
  for (const auto& o : r.outputs) {
    using deb::report::Sig;  // the report's number text: "0.3000", "1.234e-05"
    std::printf("\noutput %s [%s]: rms %s", o.name.c_str(), o.unit.c_str(), Sig(o.rms(), digits).c_str());
    if (o.rms_max) std::printf("  (requirement %g: %s)", *o.rms_max, o.pass() ? "PASS" : "FAIL");
    std::printf("\n  %-24s %14s %8s %14s\n", "contributor", "rms", "share", "exact rms");
    for (std::size_t index : deb::report::ShareOrder(o)) {  // largest first, as in the report
      const auto& c = o.contributors[index];
      const double share = o.variance > 0 ? 100.0 * c.variance / o.variance : 0.0;
      if (c.exact_variance)
        std::printf("  %-24s %14s %7.2f%% %14s\n", c.name.c_str(), Sig(std::sqrt(c.variance), digits).c_str(), share,
                    Sig(std::sqrt(*c.exact_variance), digits).c_str());
      else
        std::printf("  %-24s %14s %7.2f%% %14s\n", c.name.c_str(), Sig(std::sqrt(c.variance), digits).c_str(), share, "-");
      if (!c.top_modes.empty()) {  // a modal path: the modes that carry its exact variance
        std::string modes;
        for (std::size_t i = 0; i < c.top_modes.size() && i < 3; ++i) {
          char one[96];
          std::snprintf(one, sizeof one, "%smode %d, %.*g Hz: %.0f%%", i ? "; " : "", c.top_modes[i].mode, digits,
                        c.top_modes[i].f_hz, 100.0 * c.top_modes[i].share);
          modes += one;
        }
        std::printf("  %-24s %s\n", "", modes.c_str());
      }
      if (!c.channels.empty()) {  // breakdown: channels, largest first
        std::vector<const deb::ContributorResult::ChannelPart*> parts;
        for (const auto& p : c.channels) parts.push_back(&p);
        std::stable_sort(parts.begin(), parts.end(), [](const auto* a, const auto* b) { return a->variance > b->variance; });
        for (const auto* p : parts) {
          const std::string label = "  channel " + p->channel;
          const double v = deb::report::RoundingZero(p->variance, c.variance) ? 0.0 : std::max(p->variance, 0.0);
          std::printf("  %-24s %14s %7.2f%%\n", label.c_str(), v > 0.0 ? Sig(std::sqrt(v), digits).c_str() : "0",
                      o.variance > 0 ? 100.0 * v / o.variance : 0.0);
        }
        if (c.cross_variance != 0.0)
          std::printf("  %-24s %14s %7.2f%%  (variance; correlation between channels)\n", "  cross terms",
                      Sig(c.cross_variance, digits).c_str(), o.variance > 0 ? 100.0 * c.cross_variance / o.variance : 0.0);
      }
    }
    PrintGroups(o, digits);
    for (const deb::ReferenceResult& ref : o.references) {
      const double budget = ref.budget_variance;
      std::printf("  reference %s (%g-%g Hz): measured rms %s, budget %s, measured/budget %s, unexplained %s\n",
                  ref.name.c_str(), ref.covered_lo_hz, ref.covered_hi_hz,
                  Sig(std::sqrt(ref.variance), digits).c_str(), Sig(std::sqrt(budget), digits).c_str(),
                  budget > 0 ? Sig(std::sqrt(ref.variance / budget), digits).c_str() : "-",
                  Sig(std::sqrt(std::max(ref.variance - budget, 0.0)), digits).c_str());
    }
    for (const auto& b : o.band_requirements)
      std::printf("  band %g-%g Hz: rms %s (requirement %g: %s)\n", b.requirement.lo_hz, b.requirement.hi_hz,
                  Sig(b.rms(), digits).c_str(), b.requirement.rms_max, b.pass() ? "PASS" : "FAIL");
    if (const auto g = deb::GuideFailure(o, r.grid)) std::printf("  to fix: %s\n", g->sentence.c_str());
  }
  if (r.covariance) PrintCorrelation(*r.covariance);
  std::fflush(stdout);  // before the report's progress and gnuplot's time
}


}  // namespace deb::tools
