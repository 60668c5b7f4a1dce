// Internal: not part of the public API.
// The real factors of a polynomial with real coefficients, for realising a
// transfer function as a cascade (transfer_function.h): linear and quadratic,
// one per real root or conjugate pair.
//
// Why clusters: a root of multiplicity k is determined by the coefficients
// only to about eps^(1/k) of its size, so roots found (and polished) one at a
// time land eps^(1/k) apart in arbitrary directions and their product, the
// polynomial they define, is off by as much: 1/(s + 1)^4 realised from four
// separately polished roots had a DC gain 1.6e-5 off. The cluster's factor as
// a whole is well determined. It is computed from the power sums of its
// roots, each a contour integral of p'/p on a circle around the cluster and
// away from every other root (Delves & Lyness, Math. Comp. 21, 1967), which
// needs p only at points where it is evaluated accurately, then the factor's
// coefficients by Newton's identities, all in double-double.
//
// Why the cluster is split again: realised as one companion section of
// degree 2k, a k-fold lightly damped pair is a defective block whose
// eigenvalues rounding moves by eps^(1/k): (s^2 + s/512 + 1)^k expanded had
// H off by 2.0e-5 (k = 4) and 3.1e-2 (k = 5) near the resonance. The
// cluster's roots are therefore taken as the eigenvalues of its factor's
// companion matrix, scaled to the cluster's own spread: computed together,
// backward stably, they are the exact roots of a polynomial within rounding
// of the factor, so the linear and quadratic factors they make multiply to
// it (the caller checks the product against p in double-double).
#pragma once

#include <complex>
#include <optional>
#include <vector>

namespace deb {

struct PolynomialFactor {
  // Monic, highest power first: {1, c1, c0} = s^2 + c1 s + c0; degree 1 or
  // 2.
  std::vector<long double> coefficients;
  // A root (a single root or the upper one of a pair); Im >= 0.
  std::complex<long double> root;
  int degree() const { return static_cast<int>(coefficients.size()) - 1; }
  // The factor's value at s.
  std::complex<long double> At(std::complex<long double> s) const;
};

// The arithmetic in which roots are polished and p is evaluated: long double
// (64 bits on x86, 53 where it is double) or double-double (106 bits,
// double_double.h), which places the roots of an ill-conditioned polynomial
// about 1e13 times closer and costs about ten times as much.
enum class Precision { kLongDouble, kDoubleDouble };

// The monic real factors of p (highest power first, degree >= 1, p.front()
// != 0), whose product is p / p.front(). Roots are the eigenvalues of the
// balanced companion matrix polished together (Aberth-Ehrlich iteration) on
// the exact coefficients, p evaluated in `precision`; roots whose estimated
// errors are comparable to their distance (multiple or nearly multiple roots)
// form a cluster whose roots are found together, as above. Real roots are
// combined two by two (sorted) into quadratics if pair_real_roots. nullopt if
// the roots cannot be found or grouped (eigenvalues not finite or not in
// conjugate pairs, a cluster's contour integral that does not count its
// roots).
std::optional<std::vector<PolynomialFactor>> RealFactors(const std::vector<double>& p, bool pair_real_roots,
                                                         Precision precision = Precision::kLongDouble);

// p(s) by Horner's rule in double-double, and a bound on its rounding
// (n 2^-100 sum |a_k| |s|^(n-k) for degree n, plus the rounding to long
// double): the reference against which a factorisation is checked.
struct PreciseValue {
  std::complex<long double> value;
  long double rounding = 0.0L;
};
PreciseValue EvaluatePrecisely(const std::vector<double>& p, std::complex<long double> s);

}  // namespace deb
