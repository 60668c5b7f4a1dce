#include "deb/budget/failure_guidance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "deb/budget/allocation.h"
#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

// Contributors by variance, largest first (ties in the budget's order).
std::vector<std::size_t> ByVariance(const OutputResult& o) {
  std::vector<std::size_t> order(o.contributors.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return o.contributors[a].variance > o.contributors[b].variance; });
  return order;
}

// The uniform factor on the RMS of `group` that puts the output at its limit:
// 1/sqrt(k), k the allocation factor on their PSDs.
ContributorReduction Reduction(const OutputResult& o, std::vector<std::size_t> group) {
  ContributorReduction r;
  const Allocation a = SourceAllocationFactor(o, group);
  if (a.factor && *a.factor > 0.0) r.rms_factor = 1.0 / std::sqrt(*a.factor);
  r.contributors = std::move(group);
  return r;
}

RequirementGuidance GuideRequirement(const OutputResult& o, const FrequencyGrid& grid) {
  RequirementGuidance g;
  g.fail_factor = o.rms() / *o.rms_max;
  const std::vector<std::size_t> order = ByVariance(o);
  g.dominant = order.front();
  const double dominant_variance = o.contributors[g.dominant].variance;
  g.dominant_share = o.variance > 0.0 ? dominant_variance / o.variance : 0.0;
  double most = 0.0;
  for (const BandResult& b : o.bands)
    if (b.contributor_variance[g.dominant] > most) {
      most = b.contributor_variance[g.dominant];
      g.dominant_band = b.band;
    }
  g.reduce = Reductions(o);
  g.remove = g.reduce.front().contributors;
  g.cps_crossing_hz = CpsCrossingHz(grid.f_hz(), o.total_psd, o.total_cps, *o.rms_max * *o.rms_max);
  return g;
}

BandGuidance GuideBand(const OutputResult& o, const FrequencyGrid& grid, const BandRequirementResult& b) {
  BandGuidance g;
  g.requirement = b.requirement;
  g.rms = b.rms();
  g.fail_factor = b.rms() / b.requirement.rms_max;
  const std::vector<double> within = VarianceWithin(o, grid, b.requirement.lo_hz, b.requirement.hi_hz);
  g.largest = static_cast<std::size_t>(std::max_element(within.begin(), within.end()) - within.begin());
  const double largest = within[g.largest];
  g.largest_share = b.variance > 0.0 ? largest / b.variance : 0.0;
  const double others = b.variance - largest;
  const double limit2 = b.requirement.rms_max * b.requirement.rms_max;
  if (largest > 0.0 && others < limit2) g.largest_rms_factor = std::sqrt(largest / (limit2 - others));
  return g;
}

std::string Number(double value, int digits) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string Factor(double value, int digits) { return Number(value, digits) + "×"; }

std::string Percent(double fraction) { return Number(100.0 * fraction, 3) + " %"; }

std::string BandText(double lo_hz, double hi_hz) { return Number(lo_hz, 6) + "–" + Number(hi_hz, 6) + " Hz"; }

// "a", "a and b", "a, b and c".
std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return s;
}

}  // namespace

std::vector<double> VarianceWithin(const OutputResult& output, const FrequencyGrid& grid, double lo_hz,
                                   double hi_hz) {
  std::vector<double> v;
  for (const ContributorResult& c : output.contributors) v.push_back(ContributorVarianceBetween(grid, c, lo_hz, hi_hz));
  return v;
}

ContributorReduction SmallestReduction(const OutputResult& output) {
  DEB_DEMAND(!output.pass());
  const double limit2 = *output.rms_max * *output.rms_max;
  const std::vector<std::size_t> order = ByVariance(output);
  // Greedy: the fewest largest contributors whose removal meets the limit
  // (the header argues it is of the smallest count).
  double removed = 0.0;
  std::size_t m = 0;
  while (m < order.size() && output.variance - removed > limit2) removed += output.contributors[order[m++]].variance;
  return Reduction(output, std::vector<std::size_t>(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(m)));
}

std::vector<ContributorReduction> Reductions(const OutputResult& output) {
  std::vector<ContributorReduction> r = {SmallestReduction(output)};
  const std::vector<std::size_t> order = ByVariance(output);
  const std::size_t m = r.front().contributors.size();
  if (m < order.size() && output.contributors[order[m]].variance > 0.0)
    r.push_back(Reduction(output, std::vector<std::size_t>(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(m + 1))));
  return r;
}

std::optional<double> CpsCrossingHz(const std::vector<double>& f_hz, const std::vector<double>& psd,
                                    const std::vector<double>& cps, double variance) {
  DEB_DEMAND(!f_hz.empty() && psd.size() == f_hz.size() && cps.size() == f_hz.size());
  if (!(variance > 0.0)) return std::nullopt;
  const std::size_t k = static_cast<std::size_t>(
      std::find_if(cps.begin(), cps.end(), [&](double c) { return c >= variance; }) - cps.begin());
  if (k == cps.size()) return std::nullopt;
  if (k == 0) return f_hz.front();
  const double f0 = f_hz[k - 1], f1 = f_hz[k];
  const double t = (variance - cps[k - 1]) / (cps[k] - cps[k - 1]);  // in (0, 1]
  if (t >= 1.0) return f1;
  const std::vector<double> f = {f0, f1}, s = {psd[k - 1], psd[k]};
  const double whole = IntegralBetween(f, s, f0, f1);
  if (!(whole > 0.0)) return f0 + t * (f1 - f0);  // no PSD to shape the step: linear
  // The partial integral rises monotonically with x: bisect to the last bit.
  double lo = f0, hi = f1;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (IntegralBetween(f, s, f0, mid) / whole < t)
      lo = mid;
    else
      hi = mid;
  }
  return hi;
}

std::optional<FailureGuidance> GuideFailure(const OutputResult& output, const FrequencyGrid& grid) {
  if (output.AllPass() || output.contributors.empty()) return std::nullopt;
  DEB_DEMAND(output.total_psd.size() == grid.size() && output.total_cps.size() == grid.size());
  FailureGuidance g;
  if (!output.pass()) g.overall = GuideRequirement(output, grid);
  for (const BandRequirementResult& b : output.band_requirements)
    if (!b.pass()) g.bands.push_back(GuideBand(output, grid, b));
  g.sentence = GuidanceSentence(output, g, DisplayUnit(output.unit));
  return g;
}

std::string GuidanceSentence(const OutputResult& output, const FailureGuidance& guidance,
                             const std::string& unit_text, int digits) {
  const auto name = [&](std::size_t c) { return output.contributors[c].name; };
  const std::string unit = unit_text.empty() || unit_text == "1" ? "" : " " + unit_text;
  std::string s;
  if (const auto& g = guidance.overall) {
    s = output.name + " fails by " + Factor(g->fail_factor, digits) + ": ";
    std::string dominant = name(g->dominant) + " (" + Percent(g->dominant_share);
    if (g->dominant_band) dominant += ", " + BandText(g->dominant_band->lo_hz, g->dominant_band->hi_hz);
    dominant += ")";
    const ContributorReduction& least = g->reduce.front();
    if (least.contributors.size() == output.contributors.size() && least.contributors.size() > 1) {
      s += "every contributor must drop " + Factor(g->fail_factor, digits) + " (the largest: " + dominant + ")";
    } else {
      std::vector<std::string> names = {dominant};
      for (std::size_t i = 1; i < least.contributors.size(); ++i) names.push_back(name(least.contributors[i]));
      s += Join(names) + " must ";
      if (!least.rms_factor)
        s += "be removed";
      else
        s += "drop " + Factor(*least.rms_factor, digits) + (names.size() > 1 ? " each" : "");
      if (g->reduce.size() > 1 && g->reduce[1].rms_factor) {
        std::vector<std::string> more;
        for (std::size_t c : g->reduce[1].contributors) more.push_back(name(c));
        s += ", or " + Join(more) + " " + Factor(*g->reduce[1].rms_factor, digits) + " each";
      }
    }
    if (g->cps_crossing_hz)
      s += "; the cumulative RMS reaches " + Number(*output.rms_max, 6) + unit + " at " +
           Number(*g->cps_crossing_hz, digits) + " Hz";
  }
  for (const BandGuidance& b : guidance.bands) {
    const std::string band = BandText(b.requirement.lo_hz, b.requirement.hi_hz);
    s += s.empty() ? output.name + " fails in band " + band + " by " + Factor(b.fail_factor, digits)
                   : "; band " + band + " fails by " + Factor(b.fail_factor, digits);
    s += " (largest: " + name(b.largest) + ", " + Percent(b.largest_share) + " of the band";
    if (b.largest_rms_factor) s += ", must drop " + Factor(*b.largest_rms_factor, digits);
    s += ")";
  }
  return s;
}

}  // namespace deb
