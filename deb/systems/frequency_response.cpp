#include "deb/systems/frequency_response.h"

#include <cmath>
#include <complex>
#include <limits>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/parallel.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// |j omega - lambda| <= kPoleSlack * eps * (|A| + |omega|) is "on the pole":
// eigenvalues are only known to about eps * |A|.
constexpr double kPoleSlack = 64.0;

}  // namespace

struct FrequencyResponse::Workspace {
  explicit Workspace(const FrequencyResponse& r) {
    if (r.method_ == Method::kModal) {
      wr.resize(r.residues_.cols());
      wi.resize(r.residues_.cols());
      hr.resize(r.p_ * r.m_);
      hi.resize(r.p_ * r.m_);
    } else if (r.m_ <= r.p_) {
      x.resize(r.n_, r.m_);
    } else {
      x.resize(r.p_, r.n_);
    }
  }
  Eigen::VectorXd wr, wi, hr, hi;  // modal: term weights, H real/imag parts
  Eigen::MatrixXcd x;              // Schur: (sI-T)^-1 U^H B, or C U (sI-T)^-1
};

FrequencyResponse::FrequencyResponse(const StateSpace& sys, Method method)
    : n_(sys.states()), m_(sys.inputs()), p_(sys.outputs()), d_(sys.D()) {
  if (n_ == 0) {
    method_ = Method::kModal;
    eigenvector_condition_ = 1.0;
    residues_.resize(p_ * m_, 0);
    return;
  }
  const StateSpace bal = sys.Balanced();
  const Eigen::MatrixXd& a = bal.A();
  pole_tolerance_ = kPoleSlack * kEps * a.norm();

  // Modal reduction; kept if the eigenvector matrix is well conditioned.
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(a, true);
  DEB_DEMAND(eig.info() == Eigen::Success);
  Eigen::MatrixXcd v = eig.eigenvectors();
  v.colwise().normalize();
  const Eigen::VectorXcd lambda = eig.eigenvalues();
  const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(v);
  const auto& sv = svd.singularValues();
  eigenvector_condition_ = sv(sv.size() - 1) > 0.0 ? sv(0) / sv(sv.size() - 1)
                                                   : std::numeric_limits<double>::infinity();
  const bool modal =
      method == Method::kModal ||
      (method == Method::kAuto && eigenvector_condition_ <= kMaxModalCondition);

  if (modal) {
    method_ = Method::kModal;
    const Eigen::MatrixXcd ct = bal.C() * v;                            // p x n
    const Eigen::MatrixXcd bt = v.partialPivLu().solve(bal.B().cast<Complex>());  // n x m
    // Real eigenvalues have im == 0 exactly; complex ones come in exact
    // conjugate pairs (real Schur 2x2 blocks), of which the im > 0 member
    // carries the pair.
    std::vector<Eigen::VectorXd> cols;
    for (int k = 0; k < n_; ++k) {
      const double re = lambda(k).real(), im = lambda(k).imag();
      if (im < 0.0) continue;
      const Eigen::MatrixXcd r = ct.col(k) * bt.row(k);  // residue, p x m
      const Eigen::Map<const Eigen::VectorXcd> rv(r.data(), p_ * m_);
      if (im == 0.0) {
        terms_.push_back({re, 0.0, false});
        cols.push_back(rv.real());
      } else {
        terms_.push_back({re, im, true});
        cols.push_back(2.0 * rv.real());                             // P
        cols.push_back(2.0 * (rv * std::conj(lambda(k))).real());    // Q
      }
    }
    residues_.resize(p_ * m_, static_cast<Eigen::Index>(cols.size()));
    for (std::size_t c = 0; c < cols.size(); ++c) residues_.col(c) = cols[c];
    return;
  }

  method_ = Method::kSchur;
  const Eigen::ComplexSchur<Eigen::MatrixXcd> schur(a.cast<Complex>());
  DEB_DEMAND(schur.info() == Eigen::Success);
  t_ = schur.matrixT().triangularView<Eigen::Upper>();
  bs_ = schur.matrixU().adjoint() * bal.B().cast<Complex>();
  cs_ = bal.C().cast<Complex>() * schur.matrixU();
}

Eigen::MatrixXcd FrequencyResponse::At(double f_hz) const {
  Workspace w(*this);
  Eigen::MatrixXcd h(p_, m_);
  EvaluateInto(f_hz, w, h);
  return h;
}

std::vector<Eigen::MatrixXcd> FrequencyResponse::Evaluate(const std::vector<double>& f_hz,
                                                          int threads) const {
  std::vector<Eigen::MatrixXcd> out(f_hz.size());
  ParallelFor(
      f_hz.size(),
      [&](std::size_t begin, std::size_t end) {
        Workspace w(*this);
        for (std::size_t k = begin; k < end; ++k) {
          out[k].resize(p_, m_);
          EvaluateInto(f_hz[k], w, out[k]);
        }
      },
      threads);
  return out;
}

void FrequencyResponse::ForEach(const std::vector<double>& f_hz, const Visitor& fn,
                                int threads) const {
  ParallelFor(
      f_hz.size(),
      [&](std::size_t begin, std::size_t end) {
        Workspace w(*this);
        Eigen::MatrixXcd h(p_, m_);
        for (std::size_t k = begin; k < end; ++k) {
          EvaluateInto(f_hz[k], w, h);
          fn(k, h);
        }
      },
      threads);
}

void FrequencyResponse::EvaluateInto(double f_hz, Workspace& w, Eigen::MatrixXcd& h) const {
  if (!std::isfinite(f_hz)) {
    std::ostringstream os;
    os << "frequency response: frequency " << f_hz << " Hz is not finite";
    throw InputError(os.str());
  }
  if (method_ == Method::kModal)
    EvaluateModal(kTwoPi * f_hz, w, h);
  else
    EvaluateSchur(kTwoPi * f_hz, w, h);
}

void FrequencyResponse::EvaluateModal(double omega, Workspace& w, Eigen::MatrixXcd& h) const {
  const double tol = pole_tolerance_ + kPoleSlack * kEps * std::abs(omega);
  double* wr = w.wr.data();
  double* wi = w.wi.data();
  int c = 0;
  for (const Term& t : terms_) {
    if (!t.pair) {
      // 1 / (j omega - re) = (-re - j omega) / (re^2 + omega^2)
      const double den = t.re * t.re + omega * omega;
      if (std::sqrt(den) <= tol) ThrowOnPole(omega / kTwoPi, {t.re, 0.0});
      wr[c] = -t.re / den;
      wi[c] = -omega / den;
      ++c;
    } else {
      // q = (j omega - lambda)(j omega - conj lambda), each factor formed as a
      // difference first: accurate near a lightly damped resonance.
      const Complex z1(-t.re, omega - t.im), z2(-t.re, omega + t.im);
      if (std::min(std::abs(z1), std::abs(z2)) <= tol)
        ThrowOnPole(omega / kTwoPi, {t.re, omega >= 0.0 ? t.im : -t.im});
      const Complex q = z1 * z2;
      const double qq = std::norm(q);
      const double cr = q.real() / qq, ci = -q.imag() / qq;  // 1/q
      // (cr + j ci)(j omega P - Q)
      wr[c] = -ci * omega;
      wi[c] = cr * omega;
      wr[c + 1] = -cr;
      wi[c + 1] = -ci;
      c += 2;
    }
  }
  const Eigen::Index pm = static_cast<Eigen::Index>(p_) * m_;
  double* hr = w.hr.data();
  double* hi = w.hi.data();
  const double* d = d_.data();
  for (Eigen::Index e = 0; e < pm; ++e) {
    hr[e] = d[e];
    hi[e] = 0.0;
  }
  const double* g = residues_.data();
  for (int k = 0; k < c; ++k, g += pm) {
    const double a = wr[k], b = wi[k];
    for (Eigen::Index e = 0; e < pm; ++e) {
      hr[e] += a * g[e];
      hi[e] += b * g[e];
    }
  }
  Complex* out = h.data();
  for (Eigen::Index e = 0; e < pm; ++e) out[e] = Complex(hr[e], hi[e]);
}

void FrequencyResponse::EvaluateSchur(double omega, Workspace& w, Eigen::MatrixXcd& h) const {
  const double tol = pole_tolerance_ + kPoleSlack * kEps * std::abs(omega);
  const Complex s(0.0, omega);
  for (int i = 0; i < n_; ++i)
    if (std::abs(s - t_(i, i)) <= tol) ThrowOnPole(omega / kTwoPi, t_(i, i));
  Eigen::MatrixXcd& x = w.x;
  if (m_ <= p_) {
    // X = (sI - T)^-1 U^H B by back substitution, m right-hand sides.
    for (int i = n_ - 1; i >= 0; --i) {
      x.row(i) = bs_.row(i);
      for (int k = i + 1; k < n_; ++k) x.row(i) += t_(i, k) * x.row(k);
      x.row(i) *= Complex(1.0) / (s - t_(i, i));
    }
    h.noalias() = cs_ * x;
  } else {
    // Y = C U (sI - T)^-1 by forward substitution on Y (sI - T) = C U, p rows.
    for (int i = 0; i < n_; ++i) {
      x.col(i) = cs_.col(i);
      for (int k = 0; k < i; ++k) x.col(i) += t_(k, i) * x.col(k);
      x.col(i) *= Complex(1.0) / (s - t_(i, i));
    }
    h.noalias() = x * bs_;
  }
  h += d_.cast<Complex>();
}

void FrequencyResponse::ThrowOnPole(double f_hz, std::complex<double> pole) const {
  std::ostringstream os;
  os << "frequency response: frequency " << f_hz << " Hz coincides with a pole of the path at "
     << pole.real() << (pole.imag() < 0.0 ? "" : "+") << pole.imag()
     << "j rad/s; H is unbounded there, leave this frequency out of the grid";
  throw InputError(os.str());
}

}  // namespace deb
