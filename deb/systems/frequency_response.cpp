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

// out[e] = d[e] + sum_k (wr[k] + j wi[k]) g[e + k pm] for e in [begin, end)
// in chunks of kChunk entries held in registers over all k (an axpy per k
// would be bound by loads and stores). Entries are summed in the same order
// whatever the chunk, so results do not depend on the chunking. Returns the
// first entry not done.
template <int kChunk>
Eigen::Index AccumulateChunks(Eigen::Index begin, Eigen::Index end, int columns, const double* g,
                              const double* d, const double* wr, const double* wi, Complex* out) {
  using Chunk = Eigen::Array<double, kChunk, 1>;
  const Eigen::Index pm = end;
  Eigen::Index e = begin;
  for (; e + kChunk <= end; e += kChunk) {
    Chunk hr = Eigen::Map<const Chunk>(d + e), hi = Chunk::Zero();
    const double* gk = g + e;
    for (int k = 0; k < columns; ++k, gk += pm) {
      const Eigen::Map<const Chunk> gc(gk);
      hr += wr[k] * gc;
      hi += wi[k] * gc;
    }
    for (int i = 0; i < kChunk; ++i) out[e + i] = Complex(hr[i], hi[i]);
  }
  return e;
}

}  // namespace

struct FrequencyResponse::Workspace {
  explicit Workspace(const FrequencyResponse& r) {
    if (r.method_ == Method::kModal) {
      wr.resize(r.residues_.cols());
      wi.resize(r.residues_.cols());
    } else {
      yr.resize(r.lr_.rows(), r.n_);
      yi.resize(r.lr_.rows(), r.n_);
      gr.resize(r.lr_.rows(), r.rr_.cols());
      gi.resize(r.lr_.rows(), r.rr_.cols());
    }
  }
  Eigen::VectorXd wr, wi;  // modal: complex weight of each residue column
  Eigen::MatrixXd yr, yi;  // Schur: Y = L (sI - T)^-1
  Eigen::MatrixXd gr, gi;  // Schur: G = Y R
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
  // cond_1(V) = |V|_1 |V^-1|_1 (within a factor n of the 2-norm one); the
  // inverse is needed anyway for the residues. A defective A gives a
  // numerically singular V and an infinite or huge condition number.
  const Eigen::MatrixXcd v_inv = v.partialPivLu().inverse();
  const auto norm1 = [](const Eigen::MatrixXcd& x) { return x.cwiseAbs().colwise().sum().maxCoeff(); };
  eigenvector_condition_ = v_inv.allFinite() ? norm1(v) * norm1(v_inv)
                                             : std::numeric_limits<double>::infinity();
  const bool modal =
      method == Method::kModal ||
      (method == Method::kAuto && eigenvector_condition_ <= kMaxModalCondition);

  if (modal) {
    method_ = Method::kModal;
    const Eigen::MatrixXcd ct = bal.C() * v;                            // p x n
    const Eigen::MatrixXcd bt = v_inv * bal.B();  // n x m
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
  Eigen::MatrixXcd t = schur.matrixT().triangularView<Eigen::Upper>();
  Eigen::MatrixXcd l = bal.C().cast<Complex>() * schur.matrixU();           // p x n
  Eigen::MatrixXcd r = schur.matrixU().adjoint() * bal.B().cast<Complex>();  // n x m
  schur_transposed_ = m_ < p_;
  if (schur_transposed_) {
    // H^T = (R^T J) (sI - J T^T J)^-1 (J L^T): fewer rows to substitute.
    const Eigen::MatrixXcd rt = r.transpose().rowwise().reverse();
    r = l.transpose().colwise().reverse();
    l = rt;
    t = t.transpose().colwise().reverse().rowwise().reverse().eval();
  }
  schur_diag_ = t.diagonal();
  tr_ = t.real();
  ti_ = t.imag();
  lr_ = l.real();
  li_ = l.imag();
  rr_ = r.real();
  ri_ = r.imag();
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
  const double tol2 = tol * tol;  // squared distances: no hypot in the loop
  double* wr = w.wr.data();
  double* wi = w.wi.data();
  int c = 0;
  for (const Term& t : terms_) {
    if (!t.pair) {
      // 1 / (j omega - re) = (-re - j omega) / (re^2 + omega^2)
      const double den = t.re * t.re + omega * omega;
      if (den <= tol2) ThrowOnPole(omega / kTwoPi, {t.re, 0.0});
      wr[c] = -t.re / den;
      wi[c] = -omega / den;
      ++c;
    } else {
      // q = (j omega - lambda)(j omega - conj lambda)
      //   = (-re + j below)(-re + j above) with below = omega - im, above =
      // omega + im formed first: accurate near a lightly damped resonance.
      const double below = omega - t.im, above = omega + t.im, re2 = t.re * t.re;
      if (std::min(below * below, above * above) + re2 <= tol2)
        ThrowOnPole(omega / kTwoPi, {t.re, omega >= 0.0 ? t.im : -t.im});
      const double qr = re2 - below * above, qi = -t.re * (below + above);
      const double qq = qr * qr + qi * qi;
      const double cr = qr / qq, ci = -qi / qq;  // 1/q
      // (cr + j ci)(j omega P - Q)
      wr[c] = -ci * omega;
      wi[c] = cr * omega;
      wr[c + 1] = -cr;
      wi[c + 1] = -ci;
      c += 2;
    }
  }
  // H = D + sum_k (wr_k + j wi_k) G_k.
  const Eigen::Index pm = static_cast<Eigen::Index>(p_) * m_;
  Eigen::Index e = AccumulateChunks<8>(0, pm, c, residues_.data(), d_.data(), wr, wi, h.data());
  e = AccumulateChunks<2>(e, pm, c, residues_.data(), d_.data(), wr, wi, h.data());
  AccumulateChunks<1>(e, pm, c, residues_.data(), d_.data(), wr, wi, h.data());
}

void FrequencyResponse::EvaluateSchur(double omega, Workspace& w, Eigen::MatrixXcd& h) const {
  const double tol = pole_tolerance_ + kPoleSlack * kEps * std::abs(omega);
  for (int i = 0; i < n_; ++i)
    if (std::norm(Complex(0.0, omega) - schur_diag_(i)) <= tol * tol)
      ThrowOnPole(omega / kTwoPi, schur_diag_(i));
  const int r = static_cast<int>(lr_.rows()), c = static_cast<int>(rr_.cols());
  // Y = L (sI - T)^-1 by forward substitution on Y (sI - T) = L, column i:
  //   y_i = (l_i + sum_{k<i} t_ki y_k) / (s - t_ii).
  double* yr = w.yr.data();
  double* yi = w.yi.data();
  for (int i = 0; i < n_; ++i) {
    double* ur = yr + static_cast<Eigen::Index>(i) * r;
    double* ui = yi + static_cast<Eigen::Index>(i) * r;
    for (int q = 0; q < r; ++q) {
      ur[q] = lr_(q, i);
      ui[q] = li_(q, i);
    }
    for (int k = 0; k < i; ++k) {
      const double a = tr_(k, i), b = ti_(k, i);
      const double* vr = yr + static_cast<Eigen::Index>(k) * r;
      const double* vi = yi + static_cast<Eigen::Index>(k) * r;
      for (int q = 0; q < r; ++q) {
        ur[q] += a * vr[q] - b * vi[q];
        ui[q] += a * vi[q] + b * vr[q];
      }
    }
    // 1 / (s - t_ii) = conj(z) / |z|^2
    const double zr = -schur_diag_(i).real(), zi = omega - schur_diag_(i).imag();
    const double zz = zr * zr + zi * zi, cr = zr / zz, ci = -zi / zz;
    for (int q = 0; q < r; ++q) {
      const double vr = ur[q], vi = ui[q];
      ur[q] = cr * vr - ci * vi;
      ui[q] = cr * vi + ci * vr;
    }
  }
  // G = Y R, column by column.
  double* gr = w.gr.data();
  double* gi = w.gi.data();
  for (int j = 0; j < c; ++j) {
    double* hr = gr + static_cast<Eigen::Index>(j) * r;
    double* hi = gi + static_cast<Eigen::Index>(j) * r;
    for (int q = 0; q < r; ++q) hr[q] = hi[q] = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double a = rr_(i, j), b = ri_(i, j);
      const double* vr = yr + static_cast<Eigen::Index>(i) * r;
      const double* vi = yi + static_cast<Eigen::Index>(i) * r;
      for (int q = 0; q < r; ++q) {
        hr[q] += a * vr[q] - b * vi[q];
        hi[q] += a * vi[q] + b * vr[q];
      }
    }
  }
  for (int j = 0; j < c; ++j)
    for (int q = 0; q < r; ++q) {
      const Complex g(w.gr(q, j), w.gi(q, j));
      if (schur_transposed_)
        h(j, q) = g + d_(j, q);
      else
        h(q, j) = g + d_(q, j);
    }
}

void FrequencyResponse::ThrowOnPole(double f_hz, std::complex<double> pole) const {
  std::ostringstream os;
  os << "frequency response: frequency " << f_hz << " Hz coincides with a pole of the path at "
     << pole.real() << (pole.imag() < 0.0 ? "" : "+") << pole.imag()
     << "j rad/s; H is unbounded there, leave this frequency out of the grid";
  throw InputError(os.str());
}

}  // namespace deb
