// Internal: not part of the public API.
// A phase axis in degrees that stays readable over any span: an unwrapped
// phase runs over thousands of degrees on a path with hundreds of modes.
#pragma once

#include "deb/report/figure/figure_axis.h"

namespace deb::report {

// The tick step for a phase span: 45° · 2^k, the smallest that divides the
// span into at most kMaxPhaseIntervals steps (45° up to 225°, 90° up to
// 450°, ... 1440° up to 7200°). Five: a phase panel is the lower third of a
// Bode figure, about 120 pt tall in report.pdf, where more labels run
// together.
inline constexpr int kMaxPhaseIntervals = 5;
double PhaseStepDeg(double span_deg);

// Sets `y` to [lo_deg, hi_deg] widened outward to whole steps, at least
// `min_span_deg` tall, with a labelled tick at every step: the step of the
// span (PhaseStepDeg), doubled while the widened axis holds more than
// kMaxPhaseIntervals of them.
// Needs lo_deg <= hi_deg, both finite.
void SetPhaseAxis(FigureAxis& y, double lo_deg, double hi_deg, double min_span_deg = 0.0);

}  // namespace deb::report
