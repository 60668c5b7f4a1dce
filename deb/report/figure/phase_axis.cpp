#include "deb/report/figure/phase_axis.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "deb/core/error.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

namespace {

// The axis ends for `step`: lo and hi rounded outward to whole steps (an end
// exactly on a step gets one more, so no curve runs along the frame).
std::pair<double, double> Ends(double lo_deg, double hi_deg, double step) {
  return {step * std::floor(lo_deg / step - 1e-9), step * std::ceil(hi_deg / step + 1e-9)};
}

}  // namespace

double PhaseStepDeg(double span_deg) {
  double step = 45.0;
  while (span_deg > kMaxPhaseIntervals * step) step *= 2.0;
  return step;
}

void SetPhaseAxis(FigureAxis& y, double lo_deg, double hi_deg, double min_span_deg) {
  DEB_DEMAND(std::isfinite(lo_deg) && std::isfinite(hi_deg) && lo_deg <= hi_deg);
  // The smallest step whose whole steps, rounded outward, are at most kMaxPhaseIntervals.
  double step = PhaseStepDeg(std::max(hi_deg - lo_deg, min_span_deg));
  for (;;) {
    const auto [lo, hi] = Ends(lo_deg, hi_deg, step);
    if (std::max(hi, lo + min_span_deg) - lo <= kMaxPhaseIntervals * step * (1 + 1e-12)) break;
    step *= 2.0;
  }
  const auto [lo, hi] = Ends(lo_deg, hi_deg, step);
  y.min = lo;
  y.max = std::max(hi, lo + min_span_deg);
  y.tics.clear();
  for (double t = *y.min; t <= *y.max + 1e-9; t += step) y.tics.push_back({t, Short(t)});
}

}  // namespace deb::report
