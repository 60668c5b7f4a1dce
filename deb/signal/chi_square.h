// The chi-square distribution with (possibly fractional) degrees of freedom:
// a Welch PSD estimate P of a true S is distributed as S chi2_nu / nu, which
// gives confidence bounds nu P / chi2_nu(1 - a/2) <= S <= nu P / chi2_nu(a/2)
// for the level 1 - a (Bendat & Piersol, "Random Data", 4th ed., sec. 8.5).
#pragma once

namespace deb {

// Regularised lower incomplete gamma function P(a, x) = gamma(a, x) / Gamma(a),
// a > 0, x >= 0 (series for x < a + 1, continued fraction otherwise).
double RegularizedGammaP(double a, double x);

// CDF of chi-square with nu > 0 degrees of freedom: P(nu/2, x/2).
double ChiSquareCdf(double x, double nu);

// The p-quantile, 0 < p < 1: x with ChiSquareCdf(x, nu) = p (bisection to
// relative 1e-14). @throws InputError if p or nu is out of range.
double ChiSquareQuantile(double p, double nu);

}  // namespace deb
