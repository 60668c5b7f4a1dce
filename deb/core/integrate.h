// Integration of sampled spectra over frequency, used for every CPS, RMS and
// band figure. An interval between two points is integrated exactly for a
// power law through its two end points (a straight line in log-log axes):
// spectra are close to power laws between breakpoints and resonances
// (roll-offs, 1/f^n floors), where the linear trapezoid rule over-estimates on
// log-spaced grids; where either end is zero it falls back to the linear
// trapezoid. On a grid's panels (frequency_grid.h) the Gauss-Lobatto rule
// applies instead: exact for polynomials of degree 9 over the panel, and at
// the points inside it the integral of the interpolating polynomial (made
// non-decreasing, as the integral of a PSD is).
#pragma once

#include <cstddef>
#include <vector>

#include "deb/core/frequency_grid.h"

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

// The same over a grid, with its panels: cumulative[i] = integral from
// min_hz to f[i]. s.size() == grid.size(); s >= 0.
std::vector<double> CumulativeIntegral(const FrequencyGrid& grid, const std::vector<double>& s);

// q with sum_i q[i] s[i] the grid's integral of s by a rule linear in s: the
// Lobatto weights on panels (the same integral as CumulativeIntegral there)
// and the trapezoid rule on the other intervals (where CumulativeIntegral
// takes the power law, which is not linear). For splitting one integral
// into parts that add up (the modes of a path, mode_shares.h).
std::vector<double> LinearQuadratureWeights(const FrequencyGrid& grid);

// q with q[i] = d (CumulativeIntegral(grid, s).back()) / d s[i]: the
// derivative of the grid's integral with respect to each sample, at s. On
// panels the Lobatto weights; on the other intervals the partial derivatives
// of PowerLawIntervalIntegral (the trapezoid's where an end is zero, as the
// integral itself). So that the derivative of a variance follows from the
// derivative of its PSD, sum_i q[i] ds[i], without differencing integrals.
std::vector<double> IntegralGradientWeights(const FrequencyGrid& grid, const std::vector<double>& s);

// Integral over [lo_hz, hi_hz] within the grid (FrequencyGrid::Covers: an edge
// within its tolerance of an end is that end) from its cumulative integral:
// at a grid point the cumulative value, between two points the power law
// through them from the point below.
double IntegralBetween(const FrequencyGrid& grid, const std::vector<double>& s,
                       const std::vector<double>& cumulative, double lo_hz, double hi_hz);

}  // namespace deb
