// Integration of sampled spectra over frequency, used for every CPS, RMS and
// band figure. Each interval is integrated exactly for a power law through its
// two end points (a straight line in log-log axes): spectra are close to power
// laws between breakpoints and resonances (roll-offs, 1/f^n floors), where the
// linear trapezoid rule over-estimates on log-spaced grids. Where either end is
// zero the interval falls back to the linear trapezoid.
#pragma once

#include <cstddef>
#include <vector>

namespace deb {

// Integral over [f1_hz, f2_hz] of the power law through (f1, s1) and (f2, s2),
// s1, s2 >= 0, 0 < f1 < f2.
double PowerLawIntervalIntegral(double f1_hz, double f2_hz, double s1, double s2);

// cumulative[i] = integral of s from f[0] to f[i] (cumulative[0] = 0).
// f and s must have the same size >= 1; f strictly increasing and > 0.
// The interval integrals (a log and an expm1 each) are computed on `threads`
// threads (<= 0: DefaultThreadCount()); the running sum is serial, so the
// result does not depend on the thread count.
std::vector<double> CumulativeIntegral(const std::vector<double>& f_hz,
                                       const std::vector<double>& s, int threads = 1);

// Integral of s over [lo_hz, hi_hz] ⊂ [f.front(), f.back()], with partial
// intervals at both ends evaluated on the same power law.
double IntegralBetween(const std::vector<double>& f_hz, const std::vector<double>& s, double lo_hz,
                       double hi_hz);

}  // namespace deb
