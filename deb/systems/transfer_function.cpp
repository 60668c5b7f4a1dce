#include "deb/systems/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "deb/core/error.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/polynomial_factors.h"
#include "deb/systems/polynomial_product.h"

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

// The accuracy deb promises for |H| and variances (docs/method.md), and the error of
// a long-double factorisation above which it is redone in double-double.
constexpr double kMaxRelativeError = 1e-6;
constexpr double kRefine = 1e-9;

ComplexLD EvaluateFactors(const std::vector<const PolynomialFactor*>& fs, ComplexLD s) {
  ComplexLD v = 1.0L;
  for (const PolynomialFactor* f : fs) v *= f->At(s);
  return v;
}

// A section of the cascade: its denominator factor, and the numerator
// factors assigned to it.
struct Section {
  PolynomialFactor den;
  std::vector<const PolynomialFactor*> zeros;
  int room = 0;  // degree of den less the degrees of the zeros
};

// H = num/den as a cascade of sections: one per factor of den (a real root
// or a pair, or two real roots, polynomial_factors.h), each zero factor of
// num assigned to the section with the nearest pole that still has room
// (two sections are merged into one where none has room for a pair of
// zeros), each section scaled to unit gain |H_k(-|p_k|)| = 1 and the
// remaining gain put on the last. nullopt if the factorisation fails; the
// caller then uses the companion form.
struct CascadeForm {
  StateSpace system;
  // The estimated relative error of its H (CascadeError).
  double error = 0.0;
};

// The relative error of the cascade's H = prod num_k / prod den_k (the
// sections' coefficients as realised, in double) against num/den, estimated
// at s = j omega for omega = 0 and the frequency of each root of the
// denominator (where |H| and its error peak: a root r off by d changes H by
// d / |j omega - r|) and of each zero damped by more than 1e-4 (closer to the
// axis |H| dips to nothing and its relative error means little). All in
// double-double; the estimate is the difference plus the rounding bounds of
// both sides, relative to num/den. Points where num or den is zero are
// skipped.
double CascadeError(const TransferFunction& tf, const std::vector<std::vector<double>>& num_k,
                    const std::vector<std::vector<double>>& den_k, const std::vector<double>& omega) {
  double worst = 0.0;
  for (const double w : omega) {
    const ComplexLD s(0.0L, w);
    const PreciseValue pn = EvaluatePrecisely(tf.num(), s), pd = EvaluatePrecisely(tf.den(), s);
    if (pn.value == 0.0L || pd.value == 0.0L) continue;
    ComplexLD ratio = 1.0L;
    LongDouble rounding = pn.rounding / std::abs(pn.value) + pd.rounding / std::abs(pd.value);
    for (std::size_t k = 0; k < num_k.size(); ++k) {
      const PreciseValue n = EvaluatePrecisely(num_k[k], s), d = EvaluatePrecisely(den_k[k], s);
      if (n.value == 0.0L || d.value == 0.0L) return std::numeric_limits<double>::infinity();
      ratio *= n.value / d.value;
      rounding += n.rounding / std::abs(n.value) + d.rounding / std::abs(d.value);
    }
    const LongDouble e = std::abs(ratio * pd.value / pn.value - 1.0L) + rounding;
    worst = std::max(worst, std::isfinite(e) ? static_cast<double>(e) : std::numeric_limits<double>::infinity());
  }
  return worst;
}

std::optional<CascadeForm> Cascade(const TransferFunction& tf, Precision precision) {
  const auto den = RealFactors(tf.den(), true, precision);
  if (!den) return std::nullopt;
  const bool zero_num = tf.num().size() == 1 && tf.num()[0] == 0.0;
  if (zero_num) return std::nullopt;
  std::optional<std::vector<PolynomialFactor>> num = std::vector<PolynomialFactor>{};
  if (tf.num().size() > 1) num = RealFactors(tf.num(), false, precision);
  std::vector<double> omega{0.0};
  for (const PolynomialFactor& f : *den) omega.push_back(static_cast<double>(f.root.imag()));
  for (const PolynomialFactor& f : *num)
    if (std::abs(f.root.real()) > 1e-4L * std::abs(f.root)) omega.push_back(static_cast<double>(f.root.imag()));
  if (!num) return std::nullopt;
  std::vector<Section> sections;
  for (const PolynomialFactor& f : *den) sections.push_back({f, {}, f.degree()});
  std::sort(sections.begin(), sections.end(), [](const Section& a, const Section& b) {
    return std::abs(a.den.root) < std::abs(b.den.root);
  });
  std::vector<const PolynomialFactor*> order;
  for (const PolynomialFactor& f : *num) order.push_back(&f);
  std::stable_sort(order.begin(), order.end(), [](const PolynomialFactor* a, const PolynomialFactor* b) {
    return a->degree() > b->degree();
  });
  const auto distance = [](const PolynomialFactor& a, const PolynomialFactor& b) {
    return std::abs(a.root - b.root);
  };
  for (const PolynomialFactor* f : order) {
    int best = -1;
    for (std::size_t k = 0; k < sections.size(); ++k)
      if (sections[k].room >= f->degree() &&
          (best < 0 || distance(*f, sections[k].den) < distance(*f, sections[best].den)))
        best = static_cast<int>(k);
    while (best < 0) {
      // No section has room: merge the section nearest to the zeros with
      // its nearest neighbour (their product is one factor).
      if (sections.size() < 2) return std::nullopt;
      std::size_t a = 0;
      for (std::size_t k = 1; k < sections.size(); ++k)
        if (distance(*f, sections[k].den) < distance(*f, sections[a].den)) a = k;
      std::size_t b = a == 0 ? 1 : 0;
      for (std::size_t k = 0; k < sections.size(); ++k)
        if (k != a && distance(sections[a].den, sections[k].den) < distance(sections[a].den, sections[b].den)) b = k;
      Section& into = sections[a];
      into.den.coefficients = PolynomialProduct(into.den.coefficients, sections[b].den.coefficients);
      into.zeros.insert(into.zeros.end(), sections[b].zeros.begin(), sections[b].zeros.end());
      into.room += sections[b].room;
      sections.erase(sections.begin() + static_cast<std::ptrdiff_t>(b));
      if (b < a) --a;
      if (sections[a].room >= f->degree()) best = static_cast<int>(a);
    }
    sections[best].room -= f->degree();
    sections[best].zeros.push_back(f);
  }
  // Overall gain: leading coefficients of num and den.
  LongDouble gain = static_cast<LongDouble>(tf.num().front()) / tf.den().front();
  std::optional<StateSpace> result;
  std::vector<std::vector<double>> num_k, den_k;
  for (std::size_t k = 0; k < sections.size(); ++k) {
    const Section& sec = sections[k];
    // Each section's gain is set near its own pole; a pole at the origin (an
    // integrator) has no scale of its own and is set at 1 rad/s (a bound
    // like 1e-300 there made its gain 1e-300 and the last section's 1e300).
    const LongDouble at = std::abs(sec.den.root);
    const ComplexLD s0(at > 0.0L ? -at : -1.0L, 0.0L);
    const ComplexLD dv = sec.den.At(s0), nv = EvaluateFactors(sec.zeros, s0);
    LongDouble g = std::abs(dv) / std::abs(nv);
    if (!std::isfinite(static_cast<double>(g)) || g == 0.0L) g = 1.0L;
    if (k + 1 == sections.size()) g = gain;
    else gain /= g;
    // Section numerator g * prod(zeros), padded to the section's degree.
    std::vector<LongDouble> nk{g};
    for (const PolynomialFactor* z : sec.zeros) nk = PolynomialProduct(nk, z->coefficients);
    std::vector<double> nd(nk.begin(), nk.end());
    std::vector<double> dd(sec.den.coefficients.begin(), sec.den.coefficients.end());
    for (double c : nd) if (!std::isfinite(c)) return std::nullopt;
    for (double c : dd) if (!std::isfinite(c)) return std::nullopt;
    num_k.push_back(nd);
    den_k.push_back(dd);
    const StateSpace section = CompanionForm(TransferFunction(std::move(nd), std::move(dd)));
    result = result ? Series(*result, section) : section;
  }
  return CascadeForm{result->Balanced(), CascadeError(tf, num_k, den_k, omega)};
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
  // Roots polished in long double suffice unless the polynomial is so
  // ill-conditioned that the cascade's H is off by more than kRefine;
  // then again in double-double.
  std::optional<CascadeForm> cascade = Cascade(tf, Precision::kLongDouble);
  if (!cascade || !(cascade->error <= kRefine)) {
    std::optional<CascadeForm> precise = Cascade(tf, Precision::kDoubleDouble);
    if (precise && (!cascade || !(precise->error >= cascade->error))) cascade = std::move(precise);
  }
  if (!cascade) return CompanionForm(tf);
  // |H| off by e relative puts the variance off by at most 2 e + e^2.
  if (!(2.0 * cascade->error <= kMaxRelativeError)) {
    std::ostringstream os;
    os.precision(2);
    os << "transfer function: the roots of its polynomials (order " << tf.order()
       << ") cannot be located to the accuracy deb promises: the sections realising it have an "
          "estimated error of "
       << cascade->error << " relative in |H| near the poles (2x that in the variance), more than "
       << 0.5 * kMaxRelativeError
       << " (expanded polynomials of high order with close roots determine them poorly; give it "
          "as a series of lower-order transfer functions or as a state space)";
    throw InputError(os.str());
  }
  return std::move(cascade->system);
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
