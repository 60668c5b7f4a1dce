#include "deb/systems/polynomial_factors.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "deb/systems/double_double.h"
#include "deb/systems/state_space.h"

namespace deb {
namespace {

using LongDouble = long double;
using ComplexLD = std::complex<LongDouble>;
constexpr LongDouble kEpsLD = std::numeric_limits<LongDouble>::epsilon();
// Roots i and j are one cluster if |r_i - r_j| <= kJoin max(e_i, e_j), e the
// estimated errors: the roots of a k-fold root land within about 2 e of
// each other.
constexpr LongDouble kJoin = 16.0L;
// A cluster takes in every root within kReach times its radius of its
// centre, so that the contour of radius half the distance to the nearest
// other root lies at least twice as far out as the cluster's roots.
constexpr LongDouble kReach = 4.0L;
// Nodes of the contour integrals: the trapezoid rule on a circle errs by
// about (ratio)^kNodes, ratio <= 1/2 (the cluster's radius to the circle's,
// and the circle's to the nearest other root).
constexpr int kNodes = 128;

// p(s), p'(s), and sum |a_k| |s|^(n-k): the size of the rounding of p(s).
struct Value {
  ComplexLD p = 0.0L, slope = 0.0L;
  LongDouble magnitude = 0.0L;
};

Value EvaluateLD(const std::vector<double>& p, ComplexLD s) {
  Value v;
  const LongDouble r = std::abs(s);
  for (const double c : p) {
    v.slope = v.slope * s + v.p;
    v.p = v.p * s + static_cast<LongDouble>(c);
    v.magnitude = v.magnitude * r + std::abs(static_cast<LongDouble>(c));
  }
  return v;
}

ComplexDD ToDD(ComplexLD s) { return {DoubleDouble::From(s.real()), DoubleDouble::From(s.imag())}; }
ComplexLD ToLD(const ComplexDD& s) { return {s.re.ToLongDouble(), s.im.ToLongDouble()}; }

// The same by Horner's rule in double-double.
Value EvaluateDD(const std::vector<double>& p, ComplexLD at) {
  const ComplexDD s = ToDD(at);
  ComplexDD value, slope;
  Value v;
  const LongDouble r = std::abs(at);
  for (const double c : p) {
    slope = slope * s + value;
    value = value * s + ComplexDD{c, 0.0};
    v.magnitude = v.magnitude * r + std::abs(static_cast<LongDouble>(c));
  }
  v.p = ToLD(value);
  v.slope = ToLD(slope);
  return v;
}

Value Evaluate(const std::vector<double>& p, ComplexLD s, Precision precision) {
  return precision == Precision::kDoubleDouble ? EvaluateDD(p, s) : EvaluateLD(p, s);
}

// Relative rounding of one evaluation step: a complex product and sum.
LongDouble UnitRounding(Precision precision) {
  return precision == Precision::kDoubleDouble ? 0x1p-100L : kEpsLD;
}

// Aberth-Ehrlich iteration on all roots together: Newton's step
// N_i = p(r_i) / p'(r_i), deflated by the other roots,
//   r_i -= N_i / (1 - N_i sum_{j != i} 1 / (r_i - r_j)),
// so that two starting values never converge to the same root (polished one
// by one, two eigenvalues of a clustered order-24 polynomial did, and the
// realisation fell back to the companion form). Pairs stay exact
// conjugates (mirror), real roots real. Descending: a step is kept only if
// it makes |p(r_i)| smaller, and the iteration ends when no step is kept.
// Free: every finite step is kept (the iteration as published, which
// converges from starting values the descending rule cannot leave: for 14
// clustered modes as one polynomial, three pairs of eigenvalues straddled
// the imaginary axis 0.3-1 rad/s from the roots), until no step exceeds
// 16 eps |r_i| or after 200 sweeps.
enum class Steps { kDescending, kFree };

void Polish(const std::vector<double>& p, std::vector<ComplexLD>& roots, const std::vector<int>& mirror,
            Precision precision, Steps steps) {
  const int n = static_cast<int>(roots.size());
  std::vector<LongDouble> size(n);
  for (int i = 0; i < n; ++i) size[i] = std::abs(Evaluate(p, roots[i], precision).p);
  const int sweeps = steps == Steps::kFree ? 200 : 100;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    bool moved = false;
    for (int i = 0; i < n; ++i) {
      if (roots[i].imag() < 0.0L || size[i] == 0.0L) continue;
      const Value v = Evaluate(p, roots[i], precision);
      if (std::abs(v.slope) == 0.0L) continue;
      const ComplexLD newton = v.p / v.slope;
      ComplexLD repel = 0.0L;
      for (int j = 0; j < n; ++j)
        if (j != i && roots[j] != roots[i]) repel += 1.0L / (roots[i] - roots[j]);
      ComplexLD next = roots[i] - newton / (1.0L - newton * repel);
      if (mirror[i] == i) next = next.real();
      else next = ComplexLD(next.real(), std::abs(next.imag()));
      const LongDouble next_size = std::abs(Evaluate(p, next, precision).p);
      if (!std::isfinite(next_size) || !std::isfinite(std::abs(next))) continue;
      if (steps == Steps::kDescending && !(next_size < size[i])) continue;
      if (steps == Steps::kFree && std::abs(next - roots[i]) > 16.0L * kEpsLD * std::abs(roots[i])) moved = true;
      roots[i] = next;
      size[i] = next_size;
      if (mirror[i] != i) {
        roots[mirror[i]] = std::conj(next);
        size[mirror[i]] = next_size;
      }
      if (steps == Steps::kDescending) moved = true;
    }
    if (!moved) break;
  }
}

// The error of a computed root r of p, as far as rounding in p(r) allows:
// with t_j = p^(j)(r) / j! (Taylor coefficients at r), a root of
// multiplicity k moves by about (eps S / |t_k|)^(1/k) for a rounding eps S
// of p(r); the smallest such bound over j.
LongDouble RootError(const std::vector<double>& p, ComplexLD r, Precision precision) {
  const int n = static_cast<int>(p.size()) - 1;
  std::vector<ComplexLD> t(p.begin(), p.end());
  const LongDouble rounding = UnitRounding(precision) * std::max(EvaluateLD(p, r).magnitude, LongDouble{1e-4930L});
  LongDouble error = std::numeric_limits<LongDouble>::infinity();
  // Repeated synthetic division by (s - r): after pass j, t[n - j] = t_j.
  for (int j = 0; j <= n; ++j) {
    for (int i = 1; i <= n - j; ++i) t[i] += r * t[i - 1];
    if (j > 0 && std::abs(t[n - j]) > 0.0L)
      error = std::min(error, std::pow(rounding / std::abs(t[n - j]), 1.0L / j));
  }
  return std::max(error, kEpsLD * std::abs(r));
}

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// e^(2 pi j l / kNodes), l = 0 .. kNodes - 1, in double-double: cosine and
// sine by their Taylor series on the first octant, the rest by symmetry.
const std::vector<ComplexDD>& UnitRoots() {
  static_assert(kNodes % 8 == 0, "the nodes' octants are mirrored");
  static const std::vector<ComplexDD> roots = [] {
    constexpr int kQuarter = kNodes / 4;
    const DoubleDouble two_pi(6.283185307179586232, 2.4492935982947064e-16);
    std::vector<ComplexDD> octant(kQuarter / 2 + 1);
    for (int r = 0; r <= kQuarter / 2; ++r) {
      const DoubleDouble x = two_pi * DoubleDouble(r) / DoubleDouble(kNodes), x2 = x * x;
      DoubleDouble c = 1.0, s = x, tc = 1.0, ts = x;
      for (int i = 1; i <= 20; ++i) {  // x <= pi/4: the 20th terms are below 1e-60
        tc = -(tc * x2 / DoubleDouble((2.0 * i - 1) * (2.0 * i)));
        ts = -(ts * x2 / DoubleDouble((2.0 * i) * (2.0 * i + 1)));
        c = c + tc;
        s = s + ts;
      }
      octant[r] = {c, s};
    }
    std::vector<ComplexDD> all(kNodes);
    for (int l = 0; l < kNodes; ++l) {
      const int q = l / kQuarter, r = l % kQuarter;
      ComplexDD v = r <= kQuarter / 2 ? octant[r] : ComplexDD{octant[kQuarter - r].im, octant[kQuarter - r].re};
      for (int i = 0; i < q; ++i) v = {-v.im, v.re};  // times j
      all[l] = v;
    }
    return all;
  }();
  return roots;
}

// The roots of p inside the circle |s - z| = radius, taken together: the
// monic factor q of p that holds them, from their power sums
//   s_m = (1 / 2 pi j) oint (s - z)^m p'(s) / p(s) ds  (trapezoid rule)
// in units of the radius and Newton's identities, all in double-double; then
// the eigenvalues of q's companion matrix (long double QR) in units of the
// roots' own spread rho. The eigenvalues are the exact roots of a polynomial
// within rounding of q in those units, so their product is q to about
// eps_LD rho / |s - z| relative at s: the linear and quadratic factors they
// make multiply to p near the cluster, where polished roots of a k-fold root
// would not (each is off by eps^(1/k) in its own direction). q itself is
// known to the rounding of p in double-double, relative to |q(s)| about
// 2^-104 |s - z|^-k for a k-fold root. Real q (z real) if `real`. nullopt
// unless s_0, the number of roots inside, is `count`, or if the QR
// iteration fails.
std::optional<std::vector<ComplexLD>> ClusterRoots(const std::vector<double>& p, ComplexLD z, LongDouble radius,
                                                   int count, bool real) {
  const std::vector<ComplexDD>& tau = UnitRoots();
  const ComplexDD zd = ToDD(z);
  const DoubleDouble rd = DoubleDouble::From(radius);
  std::vector<ComplexDD> sums(count + 1);
  for (int l = 0; l < kNodes; ++l) {
    const ComplexDD s = zd + ComplexDD{rd * tau[l].re, rd * tau[l].im};
    ComplexDD value, slope;
    for (const double c : p) {
      slope = slope * s + value;
      value = value * s + ComplexDD{c, 0.0};
    }
    if (value.re.hi == 0.0 && value.im.hi == 0.0) return std::nullopt;
    ComplexDD g = slope / value;
    g = {rd * g.re, rd * g.im};
    for (int m = 0; m <= count; ++m) sums[m] = sums[m] + tau[(l * (m + 1)) % kNodes] * g;
  }
  for (ComplexDD& s : sums) s = {s.re / DoubleDouble(kNodes), s.im / DoubleDouble(kNodes)};
  if (!(std::abs(ToLD(sums[0]) - static_cast<LongDouble>(count)) < 0.25L)) return std::nullopt;
  // Elementary symmetric functions of the roots t_i = (r_i - z) / radius.
  std::vector<ComplexDD> e(count + 1);
  e[0] = {1.0, 0.0};
  LongDouble rho = 0.0L;
  for (int m = 1; m <= count; ++m) {
    ComplexDD acc;
    for (int i = 1; i <= m; ++i) {
      const ComplexDD term = e[m - i] * sums[i];
      acc = i % 2 ? acc + term : acc - term;
    }
    e[m] = {acc.re / DoubleDouble(m), acc.im / DoubleDouble(m)};
    if (real) e[m].im = 0.0;
    rho = std::max(rho, std::pow(std::abs(ToLD(e[m])), 1.0L / m));
  }
  if (!std::isfinite(rho)) return std::nullopt;
  if (rho == 0.0L) return std::vector<ComplexLD>(count, z);  // one root of multiplicity count
  // u = t / 2^scale, |u| < 2 for every root: q(u) = u^count + sum_m a_m u^(count - m),
  // a_m = (-1)^m e_m 2^(-m scale), exact.
  const int scale = std::ilogb(static_cast<double>(rho)) + 1;
  std::vector<ComplexLD> a(count + 1);
  for (int m = 1; m <= count; ++m) a[m] = (m % 2 ? -1.0L : 1.0L) * ToLD(Ldexp(e[m], -m * scale));
  std::vector<ComplexLD> u;
  if (real) {
    Eigen::Matrix<LongDouble, Eigen::Dynamic, Eigen::Dynamic> companion =
        Eigen::Matrix<LongDouble, Eigen::Dynamic, Eigen::Dynamic>::Zero(count, count);
    for (int m = 0; m < count; ++m) companion(0, m) = -a[m + 1].real();
    for (int m = 1; m < count; ++m) companion(m, m - 1) = 1.0L;
    const Eigen::EigenSolver<decltype(companion)> eig(companion, false);
    if (eig.info() != Eigen::Success) return std::nullopt;
    for (int m = 0; m < count; ++m) u.push_back(eig.eigenvalues()(m));
  } else {
    Eigen::Matrix<ComplexLD, Eigen::Dynamic, Eigen::Dynamic> companion =
        Eigen::Matrix<ComplexLD, Eigen::Dynamic, Eigen::Dynamic>::Zero(count, count);
    for (int m = 0; m < count; ++m) companion(0, m) = -a[m + 1];
    for (int m = 1; m < count; ++m) companion(m, m - 1) = 1.0L;
    const Eigen::ComplexEigenSolver<decltype(companion)> eig(companion, false);
    if (eig.info() != Eigen::Success) return std::nullopt;
    for (int m = 0; m < count; ++m) u.push_back(eig.eigenvalues()(m));
  }
  std::vector<ComplexLD> roots;
  const LongDouble unit = std::ldexp(radius, scale);
  for (const ComplexLD& x : u) {
    // Real roots and exact conjugate pairs stay so (z is real if `real`).
    const ComplexLD r = z + unit * x;
    if (!std::isfinite(r.real()) || !std::isfinite(r.imag())) return std::nullopt;
    roots.push_back(r);
  }
  return roots;
}

PolynomialFactor Linear(LongDouble root) { return {{1.0L, -root}, ComplexLD(root, 0.0L)}; }

PolynomialFactor Quadratic(ComplexLD root) {
  return {{1.0L, -2.0L * root.real(), std::norm(root)}, ComplexLD(root.real(), std::abs(root.imag()))};
}

}  // namespace

PreciseValue EvaluatePrecisely(const std::vector<double>& p, ComplexLD s) {
  const Value v = EvaluateDD(p, s);
  const LongDouble degree = static_cast<LongDouble>(p.size() > 1 ? p.size() - 1 : 1);
  return {v.p, degree * 0x1p-100L * v.magnitude + kEpsLD * std::abs(v.p)};
}

ComplexLD PolynomialFactor::At(ComplexLD s) const {
  ComplexLD v = 0.0L;
  for (const LongDouble c : coefficients) v = v * s + c;
  return v;
}

namespace {

// RealFactors of a p whose last coefficient is not zero (no root at 0).
std::optional<std::vector<PolynomialFactor>> FactorsAwayFromOrigin(const std::vector<double>& p,
                                                                   bool pair_real_roots, Precision precision) {
  const int n = static_cast<int>(p.size()) - 1;
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) companion(0, k) = -p[k + 1] / p[0];
  for (int k = 1; k < n; ++k) companion(k, k - 1) = 1.0;
  if (!companion.allFinite()) return std::nullopt;
  const Eigen::VectorXd t = BalancingScale(companion), ti = t.cwiseInverse();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(ti.asDiagonal() * companion * t.asDiagonal(), false);
  if (eig.info() != Eigen::Success) return std::nullopt;

  // All n roots, polished; a pair as (upper, lower) at k, k + 1, exact
  // conjugates. mirror[k] is the index of conj(root k).
  std::vector<ComplexLD> roots(n);
  std::vector<int> mirror(n);
  for (int k = 0; k < n; ++k) {
    const std::complex<double> e = eig.eigenvalues()(k);
    if (!std::isfinite(e.real()) || !std::isfinite(e.imag())) return std::nullopt;
    if (e.imag() == 0.0) {
      roots[k] = ComplexLD(e.real(), 0.0L);
      mirror[k] = k;
    } else {
      if (e.imag() < 0.0 || k + 1 == n || eig.eigenvalues()(k + 1) != std::conj(e)) return std::nullopt;
      roots[k] = ComplexLD(e.real(), e.imag());
      roots[k + 1] = std::conj(roots[k]);
      mirror[k] = k + 1;
      mirror[k + 1] = k;
      ++k;
    }
  }
  Polish(p, roots, mirror, Precision::kLongDouble, Steps::kDescending);
  if (precision == Precision::kDoubleDouble) {
    Polish(p, roots, mirror, precision, Steps::kFree);
    Polish(p, roots, mirror, precision, Steps::kDescending);
  }

  // Clusters: roots whose errors reach each other, then every root near a
  // cluster (so that a circle can separate it from the rest).
  std::vector<LongDouble> error(n);
  for (int k = 0; k < n; ++k) error[k] = RootError(p, roots[k], precision);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto join = [&](int a, int b) { parent[Find(parent, a)] = Find(parent, b); };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (std::abs(roots[i] - roots[j]) <= kJoin * std::max(error[i], error[j])) join(i, j);
  std::vector<std::vector<int>> members;
  std::vector<ComplexLD> centre;
  std::vector<LongDouble> reach;
  for (bool changed = true; changed;) {
    changed = false;
    members.assign(n, {});
    for (int k = 0; k < n; ++k) members[Find(parent, k)].push_back(k);
    centre.assign(n, 0.0L);
    reach.assign(n, 0.0L);
    for (int c = 0; c < n; ++c) {
      if (members[c].size() < 2) continue;
      for (const int k : members[c]) centre[c] += roots[k];
      centre[c] /= static_cast<LongDouble>(members[c].size());
      for (const int k : members[c]) reach[c] = std::max(reach[c], std::abs(roots[k] - centre[c]));
      for (int k = 0; k < n; ++k)
        if (Find(parent, k) != c && std::abs(roots[k] - centre[c]) <= kReach * reach[c]) {
          join(k, c);
          changed = true;
        }
      // A cluster that reaches its mirror image holds it.
      if (std::abs(centre[c].imag()) <= kReach * reach[c])
        for (const int k : members[c])
          if (Find(parent, mirror[k]) != Find(parent, k)) {
            join(mirror[k], k);
            changed = true;
          }
      if (changed) break;
    }
  }

  std::vector<PolynomialFactor> factors;
  std::vector<LongDouble> reals;
  int degree = 0;
  for (int c = 0; c < n; ++c) {
    const std::vector<int>& m = members[c];
    if (m.empty()) continue;
    if (m.size() == 1) {
      const ComplexLD r = roots[m[0]];
      if (r.imag() == 0.0L) reals.push_back(r.real());
      else if (r.imag() > 0.0L) factors.push_back(Quadratic(r));
      degree += r.imag() == 0.0L ? 1 : r.imag() > 0.0L ? 2 : 0;
      continue;
    }
    const bool self_mirror =
        std::all_of(m.begin(), m.end(), [&](int k) { return Find(parent, mirror[k]) == c; });
    if (!self_mirror && centre[c].imag() < 0.0L) continue;  // the mirror of another cluster
    const ComplexLD z = self_mirror ? ComplexLD(centre[c].real(), 0.0L) : centre[c];
    LongDouble nearest = std::numeric_limits<LongDouble>::infinity(), inside = 0.0L;
    for (int k = 0; k < n; ++k) {
      const LongDouble d = std::abs(roots[k] - z);
      if (Find(parent, k) == c) inside = std::max(inside, d);
      else nearest = std::min(nearest, d);
    }
    LongDouble radius = std::isfinite(nearest) ? 0.5L * nearest : std::max(kReach * inside, 0.5L * std::abs(z));
    if (radius == 0.0L) radius = 1.0L;
    if (!(radius >= 2.0L * inside)) return std::nullopt;
    const int count = static_cast<int>(m.size());
    const std::optional<std::vector<ComplexLD>> cluster = ClusterRoots(p, z, radius, count, self_mirror);
    if (!cluster) return std::nullopt;
    for (const ComplexLD& r : *cluster) {
      if (self_mirror && r.imag() == 0.0L) {
        reals.push_back(r.real());
        degree += 1;
      } else if (!self_mirror || r.imag() > 0.0L) {
        // A root of a cluster off the real axis and its mirror image.
        factors.push_back(Quadratic(r));
        degree += 2;
      }
    }
  }
  if (degree != n) return std::nullopt;
  std::sort(reals.begin(), reals.end());
  for (std::size_t k = 0; k < reals.size(); ++k) {
    if (pair_real_roots && k + 1 < reals.size()) {
      factors.push_back({{1.0L, -(reals[k] + reals[k + 1]), reals[k] * reals[k + 1]},
                         ComplexLD(reals[k + 1], 0.0L)});
      ++k;
    } else {
      factors.push_back(Linear(reals[k]));
    }
  }
  return factors;
}

}  // namespace

// Roots at the origin are exact, one per trailing zero coefficient, and are
// split off before the others are located: the companion matrix and the
// polishing would place a k-fold root at 0 only to about eps^(1/k) of the
// polynomial's scale, off the origin (a double integrator as the pair
// 6e-117 +- 2e-59 j, which no realisation error bound survives).
std::optional<std::vector<PolynomialFactor>> RealFactors(const std::vector<double>& p,
                                                         bool pair_real_roots, Precision precision) {
  std::size_t at_origin = 0;
  while (at_origin + 1 < p.size() && p[p.size() - 1 - at_origin] == 0.0) ++at_origin;
  if (at_origin == 0) return FactorsAwayFromOrigin(p, pair_real_roots, precision);
  std::vector<PolynomialFactor> factors;
  if (p.size() - at_origin > 1) {
    const std::vector<double> rest(p.begin(), p.end() - static_cast<std::ptrdiff_t>(at_origin));
    std::optional<std::vector<PolynomialFactor>> others = FactorsAwayFromOrigin(rest, pair_real_roots, precision);
    if (!others) return std::nullopt;
    factors = std::move(*others);
  }
  for (std::size_t k = 0; k < at_origin; ++k) {
    if (pair_real_roots && k + 1 < at_origin) {
      factors.push_back({{1.0L, 0.0L, 0.0L}, ComplexLD(0.0L, 0.0L)});
      ++k;
    } else {
      factors.push_back({{1.0L, 0.0L}, ComplexLD(0.0L, 0.0L)});
    }
  }
  return factors;
}

}  // namespace deb
