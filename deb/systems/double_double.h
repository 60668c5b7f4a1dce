// Internal: not part of the public API.
// Double-double arithmetic: a value hi + lo held as two doubles with
// |lo| <= ulp(hi) / 2, about 106 bits (relative rounding 2^-104 per
// operation). For evaluating a polynomial near a root that double or long
// double cannot place: the roots of an expanded order-24 polynomial of
// clustered modes moved by up to 2.4e-5 of their distance to the imaginary
// axis when located with long double evaluation (polynomial_factors.h).
// Error-free transformations from Dekker (Numer. Math. 18, 1971) and Knuth
// (TAOCP 2, 4.2.2); the product uses a fused multiply-add, exact by the C
// standard on every platform.
#pragma once

#include <algorithm>
#include <cmath>

namespace deb {

struct DoubleDouble {
  double hi = 0.0, lo = 0.0;

  DoubleDouble() = default;
  DoubleDouble(double x) : hi(x) {}  // NOLINT(google-explicit-constructor)
  DoubleDouble(double h, double l) : hi(h), lo(l) {}
  // x split exactly when its significand has at most 106 bits (long double
  // on x86: 64).
  static DoubleDouble From(long double x) {
    const double h = static_cast<double>(x);
    return {h, static_cast<double>(x - h)};
  }
  long double ToLongDouble() const { return static_cast<long double>(hi) + lo; }
};

namespace double_double {

// s + e = a + b exactly.
inline DoubleDouble TwoSum(double a, double b) {
  const double s = a + b, v = s - a;
  return {s, (a - (s - v)) + (b - v)};
}

// p + e = a b exactly.
inline DoubleDouble TwoProduct(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

inline DoubleDouble Normalise(double hi, double lo) { return TwoSum(hi, lo); }

}  // namespace double_double

inline DoubleDouble operator+(DoubleDouble a, DoubleDouble b) {
  const DoubleDouble s = double_double::TwoSum(a.hi, b.hi), t = double_double::TwoSum(a.lo, b.lo);
  const DoubleDouble u = double_double::Normalise(s.hi, s.lo + t.hi);
  return double_double::Normalise(u.hi, u.lo + t.lo);
}

inline DoubleDouble operator-(DoubleDouble a) { return {-a.hi, -a.lo}; }
inline DoubleDouble operator-(DoubleDouble a, DoubleDouble b) { return a + (-b); }

inline DoubleDouble operator*(DoubleDouble a, DoubleDouble b) {
  const DoubleDouble p = double_double::TwoProduct(a.hi, b.hi);
  return double_double::Normalise(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}

// Long division: three quotient digits, each from the remainder left by the
// previous ones.
inline DoubleDouble operator/(DoubleDouble a, DoubleDouble b) {
  const double q1 = a.hi / b.hi;
  const DoubleDouble r1 = a - b * DoubleDouble(q1);
  const double q2 = r1.hi / b.hi;
  const DoubleDouble r2 = r1 - b * DoubleDouble(q2);
  const double q3 = r2.hi / b.hi;
  return double_double::Normalise(q1, q2) + DoubleDouble(q3);
}

// x 2^e, exact (barring underflow).
inline DoubleDouble Ldexp(DoubleDouble x, int e) { return {std::ldexp(x.hi, e), std::ldexp(x.lo, e)}; }

// A complex double-double, re + j im.
struct ComplexDD {
  DoubleDouble re, im;
};

inline ComplexDD operator+(const ComplexDD& a, const ComplexDD& b) { return {a.re + b.re, a.im + b.im}; }
inline ComplexDD operator-(const ComplexDD& a, const ComplexDD& b) { return {a.re - b.re, a.im - b.im}; }
inline ComplexDD operator*(const ComplexDD& a, const ComplexDD& b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
inline ComplexDD Ldexp(const ComplexDD& x, int e) { return {Ldexp(x.re, e), Ldexp(x.im, e)}; }
inline ComplexDD Conj(const ComplexDD& x) { return {x.re, -x.im}; }
// a / b = a conj(b) / |b|^2, both scaled by a power of two first so that
// |b|^2 neither overflows nor underflows. b != 0.
inline ComplexDD operator/(const ComplexDD& a, const ComplexDD& b) {
  const int e = std::ilogb(std::max(std::abs(b.re.hi), std::abs(b.im.hi)));
  const ComplexDD as = Ldexp(a, -e), bs = Ldexp(b, -e);
  const DoubleDouble norm = bs.re * bs.re + bs.im * bs.im;
  const ComplexDD n = as * Conj(bs);
  return {n.re / norm, n.im / norm};
}

}  // namespace deb
