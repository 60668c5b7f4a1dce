#include "deb/systems/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "deb/core/error.h"
#include "deb/systems/interconnect.h"

namespace deb {
namespace {

void RequireFinite(const std::vector<double>& p, const char* name) {
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!std::isfinite(p[k])) {
      std::ostringstream os;
      os << "transfer function: " << name << " coefficient " << k + 1 << " = " << p[k]
         << " is not finite";
      throw InputError(os.str());
    }
}

std::vector<double> TrimLeadingZeros(std::vector<double> p) {
  std::size_t first = 0;
  while (first < p.size() && p[first] == 0.0) ++first;
  p.erase(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(first));
  return p;
}

std::complex<double> Horner(const std::vector<double>& p, std::complex<double> s) {
  std::complex<double> v = 0.0;
  for (double c : p) v = v * s + c;
  return v;
}


// Controllable canonical form, balanced (defined below).
StateSpace CompanionForm(const TransferFunction& tf);

using LongDouble = long double;
using ComplexLD = std::complex<LongDouble>;

// p(s) and p'(s) in long double; p highest power first, exact in long double.
void EvaluateLD(const std::vector<double>& p, ComplexLD s, ComplexLD& value, ComplexLD& slope) {
  value = 0.0L;
  slope = 0.0L;
  for (double c : p) {
    slope = slope * s + value;
    value = value * s + static_cast<LongDouble>(c);
  }
}

// A real factor s + c0 (degree 1) or s^2 + c1 s + c0 (degree 2) and one of its
// roots (Im >= 0).
struct Factor {
  int degree = 1;
  LongDouble c1 = 0.0L, c0 = 0.0L;
  ComplexLD root;
};

// The monic real factors of p (degree >= 1, p.front() != 0): the eigenvalues of
// the balanced companion matrix, each polished by Newton's method in long
// double on the exact coefficients. A polynomial with clustered roots has
// roots so sensitive that the double eigenvalues are only those of a nearby
// polynomial (an order-20 product of resonators at 3 % spacing: 3e-4 |Re p|
// apart); polished, they are those of p itself to ~1e-7 |Re p|.
// Real roots are returned as degree-1 factors unless pair_real_roots, which
// combines them two by two (sorted) into quadratics. nullopt if the
// eigenvalues do not come in conjugate pairs or are not finite.
std::optional<std::vector<Factor>> RealFactors(const std::vector<double>& p, bool pair_real_roots) {
  const int n = static_cast<int>(p.size()) - 1;
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) companion(0, k) = -p[k + 1] / p[0];
  for (int k = 1; k < n; ++k) companion(k, k - 1) = 1.0;
  const Eigen::VectorXd t = BalancingScale(companion), ti = t.cwiseInverse();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(ti.asDiagonal() * companion * t.asDiagonal(),
                                                false);
  if (eig.info() != Eigen::Success) return std::nullopt;
  const auto polish = [&](ComplexLD r, bool real) {
    ComplexLD value, slope;
    EvaluateLD(p, r, value, slope);
    for (int it = 0; it < 20 && std::abs(value) > 0.0L; ++it) {
      if (std::abs(slope) == 0.0L) break;
      ComplexLD next = r - value / slope;
      if (real) next = next.real();
      ComplexLD next_value, next_slope;
      EvaluateLD(p, next, next_value, next_slope);
      if (!(std::abs(next_value) < std::abs(value))) break;  // no more progress
      r = next;
      value = next_value;
      slope = next_slope;
    }
    return r;
  };
  std::vector<Factor> factors;
  std::vector<LongDouble> reals;
  int upper = 0, lower = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::complex<double> e = eig.eigenvalues()(k);
    if (!std::isfinite(e.real()) || !std::isfinite(e.imag())) return std::nullopt;
    if (e.imag() < 0.0) {
      ++lower;
    } else if (e.imag() == 0.0) {
      reals.push_back(polish(ComplexLD(e.real(), 0.0L), true).real());
    } else {
      ++upper;
      const ComplexLD r = polish(ComplexLD(e.real(), e.imag()), false);
      Factor f;
      f.degree = 2;
      f.c1 = -2.0L * r.real();
      f.c0 = std::norm(r);
      f.root = ComplexLD(r.real(), std::abs(r.imag()));
      factors.push_back(f);
    }
  }
  if (upper != lower) return std::nullopt;
  std::sort(reals.begin(), reals.end());
  for (std::size_t k = 0; k < reals.size(); ++k) {
    Factor f;
    if (pair_real_roots && k + 1 < reals.size()) {
      f.degree = 2;
      f.c1 = -(reals[k] + reals[k + 1]);
      f.c0 = reals[k] * reals[k + 1];
      ++k;
    } else {
      f.c0 = -reals[k];
    }
    f.root = ComplexLD(reals[k], 0.0L);
    factors.push_back(f);
  }
  return factors;
}

ComplexLD EvaluateFactors(const std::vector<const Factor*>& fs, ComplexLD s) {
  ComplexLD v = 1.0L;
  for (const Factor* f : fs) v *= f->degree == 1 ? s + f->c0 : (s + f->c1) * s + f->c0;
  return v;
}

// H = num/den as a cascade of sections of order <= 2: one per quadratic (or
// linear) factor of den, each zero factor of num assigned to the section with
// the nearest pole that still has room, each section scaled to unit gain
// |H_k(-|p_k|)| = 1 and the remaining gain put on the last. nullopt if the
// factorisation fails; the caller then uses the companion form.
std::optional<StateSpace> Cascade(const TransferFunction& tf) {
  const auto den = RealFactors(tf.den(), true);
  if (!den) return std::nullopt;
  const bool zero_num = tf.num().size() == 1 && tf.num()[0] == 0.0;
  if (zero_num) return std::nullopt;
  std::optional<std::vector<Factor>> num = std::vector<Factor>{};
  if (tf.num().size() > 1) num = RealFactors(tf.num(), false);
  if (!num) return std::nullopt;
  std::vector<Factor> sections = *den;
  std::sort(sections.begin(), sections.end(),
            [](const Factor& a, const Factor& b) { return std::abs(a.root) < std::abs(b.root); });
  std::vector<int> room(sections.size());
  for (std::size_t k = 0; k < sections.size(); ++k) room[k] = sections[k].degree;
  std::vector<std::vector<const Factor*>> zeros(sections.size());
  std::vector<const Factor*> order;
  for (const Factor& f : *num) if (f.degree == 2) order.push_back(&f);
  for (const Factor& f : *num) if (f.degree == 1) order.push_back(&f);
  for (const Factor* f : order) {
    int best = -1;
    for (std::size_t k = 0; k < sections.size(); ++k)
      if (room[k] >= f->degree &&
          (best < 0 || std::abs(f->root - sections[k].root) < std::abs(f->root - sections[best].root)))
        best = static_cast<int>(k);
    if (best < 0) return std::nullopt;
    room[best] -= f->degree;
    zeros[best].push_back(f);
  }
  // Overall gain: leading coefficients of num and den.
  LongDouble gain = static_cast<LongDouble>(tf.num().front()) / tf.den().front();
  std::optional<StateSpace> result;
  for (std::size_t k = 0; k < sections.size(); ++k) {
    const Factor& d = sections[k];
    const ComplexLD s0(-std::max(std::abs(d.root), 1e-300L), 0.0L);
    const ComplexLD dv = EvaluateFactors({&d}, s0), nv = EvaluateFactors(zeros[k], s0);
    LongDouble g = std::abs(dv) / std::abs(nv);
    if (!std::isfinite(static_cast<double>(g)) || g == 0.0L) g = 1.0L;
    if (k + 1 == sections.size()) g = gain;
    else gain /= g;
    // Section numerator g * prod(zeros), padded to the section's degree.
    std::vector<LongDouble> nk{g};
    for (const Factor* z : zeros[k]) {
      std::vector<LongDouble> f = z->degree == 1 ? std::vector<LongDouble>{1.0L, z->c0}
                                                 : std::vector<LongDouble>{1.0L, z->c1, z->c0};
      std::vector<LongDouble> prod(nk.size() + f.size() - 1, 0.0L);
      for (std::size_t i = 0; i < nk.size(); ++i)
        for (std::size_t j = 0; j < f.size(); ++j) prod[i + j] += nk[i] * f[j];
      nk = std::move(prod);
    }
    std::vector<double> nd(nk.begin(), nk.end());
    std::vector<double> dd = d.degree == 1 ? std::vector<double>{1.0, static_cast<double>(d.c0)}
                                           : std::vector<double>{1.0, static_cast<double>(d.c1),
                                                                 static_cast<double>(d.c0)};
    for (double c : nd) if (!std::isfinite(c)) return std::nullopt;
    for (double c : dd) if (!std::isfinite(c)) return std::nullopt;
    const StateSpace section = CompanionForm(TransferFunction(std::move(nd), std::move(dd)));
    result = result ? Series(*result, section) : section;
  }
  return result->Balanced();
}
}  // namespace

TransferFunction::TransferFunction(std::vector<double> num, std::vector<double> den) {
  RequireFinite(num, "numerator");
  RequireFinite(den, "denominator");
  num_ = TrimLeadingZeros(std::move(num));
  den_ = TrimLeadingZeros(std::move(den));
  if (den_.empty())
    throw InputError("transfer function: the denominator is empty or all zero");
  if (num_.empty()) num_ = {0.0};
  if (num_.size() > den_.size()) {
    std::ostringstream os;
    os << "transfer function: improper, numerator degree " << num_.size() - 1
       << " > denominator degree " << den_.size() - 1
       << " (deb needs deg num <= deg den; add poles above the band of interest)";
    throw InputError(os.str());
  }
}

TransferFunction TransferFunction::Gain(double k) { return TransferFunction({k}, {1.0}); }

std::complex<double> TransferFunction::Evaluate(std::complex<double> s) const {
  return Horner(num_, s) / Horner(den_, s);
}

namespace {

StateSpace CompanionForm(const TransferFunction& tf) {
  const int n = tf.order();
  const double lead = tf.den().front();
  // Monic denominator s^n + a1 s^(n-1) + ... + an; numerator padded to n+1
  // coefficients b0 s^n + ... + bn, both divided by the leading coefficient.
  Eigen::VectorXd a(n + 1), b = Eigen::VectorXd::Zero(n + 1);
  for (int k = 0; k <= n; ++k) a(k) = tf.den()[k] / lead;
  const int offset = n + 1 - static_cast<int>(tf.num().size());
  for (std::size_t k = 0; k < tf.num().size(); ++k) b(offset + k) = tf.num()[k] / lead;
  Eigen::MatrixXd d(1, 1);
  d(0, 0) = b(0);
  if (n == 0) return StateSpace::Gain(d);
  // Controllable canonical form: x1' = -a1 x1 - ... - an xn + u, x(k+1)' = xk,
  // y = sum (bk - ak b0) xk + b0 u (the strictly proper remainder plus b0).
  Eigen::MatrixXd am = Eigen::MatrixXd::Zero(n, n), bm = Eigen::MatrixXd::Zero(n, 1);
  Eigen::MatrixXd cm(1, n);
  for (int k = 0; k < n; ++k) {
    am(0, k) = -a(k + 1);
    cm(0, k) = b(k + 1) - a(k + 1) * b(0);
  }
  for (int k = 1; k < n; ++k) am(k, k - 1) = 1.0;
  bm(0, 0) = 1.0;
  return StateSpace(std::move(am), std::move(bm), std::move(cm), std::move(d)).Balanced();
}

}  // namespace

StateSpace ToStateSpace(const TransferFunction& tf) {
  if (tf.order() <= 2) return CompanionForm(tf);
  if (std::optional<StateSpace> cascade = Cascade(tf)) return *std::move(cascade);
  return CompanionForm(tf);
}

StateSpace ToStateSpace(const std::vector<std::vector<TransferFunction>>& tf) {
  if (tf.empty() || tf.front().empty())
    throw InputError("transfer matrix: needs at least one row and one column");
  const std::size_t rows = tf.size(), cols = tf.front().size();
  int n = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    if (tf[i].size() != cols) {
      std::ostringstream os;
      os << "transfer matrix: row " << i + 1 << " has " << tf[i].size()
         << " entries but row 1 has " << cols;
      throw InputError(os.str());
    }
    for (const auto& entry : tf[i]) n += entry.order();
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n), b = Eigen::MatrixXd::Zero(n, cols);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(rows, n), d(rows, cols);
  int at = 0;
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) {
      const StateSpace s = ToStateSpace(tf[i][j]);
      const int k = s.states();
      a.block(at, at, k, k) = s.A();
      b.block(at, j, k, 1) = s.B();
      c.block(i, at, 1, k) = s.C();
      d(i, j) = s.D()(0, 0);
      at += k;
    }
  return StateSpace(std::move(a), std::move(b), std::move(c), std::move(d));
}

}  // namespace deb
