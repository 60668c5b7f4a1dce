#include "deb/budget/result.h"

#include <algorithm>
#include <cmath>

#include "deb/core/integrate.h"

namespace deb {

double OutputResult::rms() const { return std::sqrt(variance); }

bool OutputResult::pass() const { return !rms_max || rms() <= *rms_max; }

double BandRequirementResult::rms() const { return std::sqrt(variance); }

bool BandRequirementResult::pass() const { return rms() <= requirement.rms_max; }

bool OutputResult::AllPass() const {
  for (const auto& b : band_requirements)
    if (!b.pass()) return false;
  return pass();
}

std::vector<double> ReverseCps(const std::vector<double>& cps) {
  std::vector<double> r(cps.size());
  for (std::size_t i = 0; i < cps.size(); ++i) r[i] = cps.back() - cps[i];
  return r;
}

void AddToneStep(const std::vector<double>& f_hz, double tone_f_hz, double variance, std::vector<double>* cps) {
  const auto first = static_cast<std::size_t>(std::lower_bound(f_hz.begin(), f_hz.end(), tone_f_hz) - f_hz.begin());
  for (std::size_t k = first; k < f_hz.size(); ++k) (*cps)[k] += variance;
}

double ContributorVarianceBetween(const FrequencyGrid& grid, const ContributorResult& c, double lo_hz, double hi_hz) {
  if (c.tones.empty()) return IntegralBetween(grid, c.psd, c.cps, lo_hz, hi_hz);
  // The density's CPS: the tones' steps taken out again.
  const std::vector<double>& f = grid.f_hz();
  std::vector<double> density_cps = c.cps;
  double tonal = 0.0;
  // (lo, hi], closed below at the grid's start: the CPS holds a tone on the
  // first point from that point on, so the band from there must count it.
  const bool from_start = grid.ClampToRange(lo_hz) == grid.min_hz();
  for (const ContributorResult::Tone& t : c.tones) {
    AddToneStep(f, t.f_hz, -t.variance, &density_cps);
    if ((lo_hz < t.f_hz || (from_start && t.f_hz <= lo_hz)) && t.f_hz <= hi_hz) tonal += t.variance;
  }
  return IntegralBetween(grid, c.psd, density_cps, lo_hz, hi_hz) + tonal;
}

}  // namespace deb
