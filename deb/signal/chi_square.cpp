#include "deb/signal/chi_square.h"

#include <cmath>
#include <limits>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {

double RegularizedGammaP(double a, double x) {
  DEB_DEMAND(a > 0.0 && x >= 0.0);
  if (x == 0.0) return 0.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  constexpr double kEps = 1e-16;
  if (x < a + 1.0) {
    // P = e^-x x^a / Gamma(a) sum_n x^n / (a (a+1) ... (a+n)).
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000 && term > kEps * sum; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::min(1.0, sum * std::exp(log_prefactor));
  }
  // Q = e^-x x^a / Gamma(a) * 1/(x+1-a- 1(1-a)/(x+3-a- ...)), modified Lentz.
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEps) break;
  }
  return std::max(0.0, 1.0 - std::exp(log_prefactor) * h);
}

double ChiSquareCdf(double x, double nu) {
  DEB_DEMAND(nu > 0.0);
  return x <= 0.0 ? 0.0 : RegularizedGammaP(0.5 * nu, 0.5 * x);
}

double ChiSquareQuantile(double p, double nu) {
  if (!(p > 0.0 && p < 1.0)) throw InputError("probability " + NumberText(p) + " must be in (0, 1)");
  if (!(nu > 0.0 && std::isfinite(nu)))
    throw InputError("degrees of freedom " + NumberText(nu) + " must be finite and > 0");
  double lo = 0.0, hi = nu + 10.0;
  while (ChiSquareCdf(hi, nu) < p) hi *= 2.0;
  for (int i = 0; i < 400 && hi - lo > 1e-14 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareCdf(mid, nu) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace deb
