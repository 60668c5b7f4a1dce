#include "deb/systems/frequency_response.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/parallel.h"
#include "deb/systems/block_triangular.h"
#include "deb/systems/lapack.h"
#include "deb/systems/real_block_diagonal.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// |j omega - lambda| <= kPoleSlack * eps * (|A| + |omega|) is "on the pole":
// eigenvalues are only known to about eps * |A|.
constexpr double kPoleSlack = 64.0;
// Block Schur blocks up to this size are expanded into residue columns,
// size (size + 1) of them; larger ones are solved by substitution.
constexpr int kMaxExpandedBlock = 4;
// Frequencies per block of ForEach: the weights (columns x 2 x this) and the
// sums (entries of H x 2 x this) of a block, a few MB at 2000 states and 20 x
// 20; the product's packing of the residues is 1/(2 x this) of its work.
// Fewer where the sums would exceed kMaxBlockSums values (16 MB) per worker:
// a path of many channels and few states.
constexpr std::size_t kFrequencyBlock = 128;
constexpr double kMaxBlockSums = 2097152.0;

// omega = 2 pi f [rad/s].
// @throws InputError if f_hz is not finite.
double CheckedOmega(double f_hz) {
  if (!std::isfinite(f_hz)) {
    std::ostringstream os;
    os << "frequency response: frequency " << f_hz << " Hz is not finite";
    throw InputError(os.str());
  }
  return kTwoPi * f_hz;
}

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
    // g is indexed only inside the loop: with no residue columns (a static
    // gain) it is the null data() of an empty matrix and takes no offset.
    for (int k = 0; k < columns; ++k) {
      const Eigen::Map<const Chunk> gc(g + k * pm + e);
      hr += wr[k] * gc;
      hi += wi[k] * gc;
    }
    for (int i = 0; i < kChunk; ++i) out[e + i] = Complex(hr[i], hi[i]);
  }
  return e;
}

}  // namespace

struct FrequencyResponse::Workspace {
  explicit Workspace(const FrequencyResponse& r)
      : wr(r.columns_), wi(r.columns_), g(r.transposed_ ? r.rows_ : 0, r.transposed_ ? r.cols_ : 0) {
    if (r.method_ == Method::kHessenberg) {
      m.resize(r.n_, r.n_);
      x.resize(r.n_, r.m_);
    }
    if (r.largest_block_ > kMaxExpandedBlock) {
      yr.resize(r.rows_, r.largest_block_);
      yi.resize(r.rows_, r.largest_block_);
    }
  }
  Eigen::VectorXd wr, wi;  // complex weight of each residue column
  Eigen::MatrixXcd g;      // G = H^T when transposed
  Eigen::MatrixXd yr, yi;  // large block: Y = L_c (sI - T_c)^-1
  Eigen::MatrixXcd m, x;   // Hessenberg: j omega I - H, and the solution
};

FrequencyResponse::FrequencyResponse(const StateSpace& sys, Method method)
    : n_(sys.states()), m_(sys.inputs()), p_(sys.outputs()), rows_(p_), cols_(m_), d_(sys.D()) {
  if (n_ == 0) {
    residues_.resize(p_ * m_, 0);
    return;
  }
  const StateSpace bal = sys.Balanced();
  const Eigen::MatrixXd& a = bal.A();
  RequireWellScaled(a);
  pole_tolerance_ = kPoleSlack * kEps * a.norm();
  if (method == Method::kHessenberg) {
    method_ = Method::kHessenberg;
    const Eigen::HessenbergDecomposition<Eigen::MatrixXd> hd(a);
    hess_ = hd.matrixH();
    const Eigen::MatrixXd q = hd.matrixQ();
    cq_ = bal.C() * q;
    qb_ = q.transpose() * bal.B();
    poles_ = BlockEigenvalues(a);
    return;
  }

  // One block per stage of a cascade (block_triangular.h): the poles are
  // found stage by stage where there are several.
  const BlockTriangularForm structure = BlockTriangular(a);
  const bool reducible = structure.blocks() > 1;
  if (method == Method::kModal) {
    BuildModal(bal, reducible, 1e-3 / kEps, true);
  } else if (method == Method::kSchur) {
    BuildBlockDiagonal(bal, reducible);
  } else if (!HasCoupledBlocks(a, structure)) {
    // Irreducible (a dense model, a loop), or blocks standing apart (a
    // modal realisation): the block-diagonal form. Its
    // rounding is that of a backward-stable solve times at most about
    // cond(Y): kept as it is up to kVerifyCondition, checked against the
    // Hessenberg solve up to kMaxBlockCondition (a companion form of close
    // modes decouples only with a large Y), and beyond, or where they
    // disagree, the Hessenberg solve takes over, at O(n^2 m) per frequency.
    BuildBlockDiagonal(bal, reducible);
    if (condition_ > kVerifyCondition) {
      columns_ = static_cast<int>(residues_.cols());
      FrequencyResponse reference(sys, Method::kHessenberg);
      const bool too_large = !(condition_ <= kMaxBlockCondition);
      if (too_large || !AgreesNear(reference, poles_)) {
        std::ostringstream why;
        why << "the block-diagonal form's cond(Y) " << condition_
            << (too_large ? " is above 1e6" : " is above 100 and it differed from this solve by more than 1e-8");
        reference.condition_ = condition_;
        reference.hessenberg_reason_ = why.str();
        *this = std::move(reference);
      }
    }
  } else {
    // Reducible (a cascade: series connections, transfer functions of order
    // 3 and more): stages may be coupled by entries far below eps |A| that
    // carry the whole response (balancing a cascade of equal sections gave
    // a coupling of 2e-17 and an output row of 4e16); a Schur form of the
    // whole A rounds them away, the Hessenberg solve keeps them. The modal
    // form (or the block-diagonal one where cond(V) > kMaxModalCondition)
    // is used where it agrees with the Hessenberg solve.
    const bool modal = BuildModal(bal, reducible, kMaxModalCondition, false);
    if (!modal) BuildBlockDiagonal(bal, reducible);
    if (!modal || condition_ > kVerifyCondition || HasClusteredPoles(poles_) || SpansDecades(poles_)) {
      columns_ = static_cast<int>(residues_.cols());
      FrequencyResponse reference(sys, Method::kHessenberg);
      if (!AgreesNear(reference, poles_)) {
        reference.condition_ = condition_;
        reference.hessenberg_reason_ = std::string("a cascade whose ") + (modal ? "modal" : "block-diagonal") +
                                       " form differed from this solve by more than 1e-8";
        *this = std::move(reference);
      }
    }
  }
  columns_ = static_cast<int>(residues_.cols());
}

bool FrequencyResponse::BuildModal(const StateSpace& bal, bool reducible, double max_condition, bool required) {
  const Eigen::MatrixXd& a = bal.A();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(a, true);
  if (eig.info() != Eigen::Success) ThrowNotConverged(a);
  Eigen::MatrixXcd v = eig.eigenvectors();
  v.colwise().normalize();
  const Eigen::VectorXcd lambda = eig.eigenvalues();
  // cond_1(V) = |V|_1 |V^-1|_1 (within a factor n of the 2-norm one); the
  // inverse is needed anyway for the residues. A defective A gives a
  // numerically singular V and an infinite or huge condition number.
  const Eigen::MatrixXcd v_inv = v.partialPivLu().inverse();
  const auto norm1 = [](const Eigen::MatrixXcd& x) { return x.cwiseAbs().colwise().sum().maxCoeff(); };
  const double condition = v_inv.allFinite() ? norm1(v) * norm1(v_inv) : std::numeric_limits<double>::infinity();
  if (!(condition <= max_condition)) {
    if (!required) return false;
    // Beyond 1e-3 / eps the eigenvectors are numerically dependent: modal
    // results would carry errors of 1e-3 and more.
    std::ostringstream os;
    os << "frequency response: the modal form was requested but A is numerically defective "
          "(eigenvector condition number "
       << condition << "); use Method::kAuto or kSchur";
    throw InputError(os.str());
  }
  condition_ = condition;
  // The poles reported (stability, modes, the grid) are the diagonal
  // blocks' own where A is reducible (a cascade): those of the dense solver
  // can cross the imaginary axis (block_triangular.h).
  poles_ = reducible ? BlockEigenvalues(a) : lambda;
  method_ = Method::kModal;
  const Eigen::MatrixXcd ct = bal.C() * v;      // p x n
  const Eigen::MatrixXcd bt = v_inv * bal.B();  // n x m
  std::vector<Eigen::VectorXd> cols;
  // Real eigenvalues have im == 0 exactly; complex ones come in exact
  // conjugate pairs (real Schur 2x2 blocks), of which the im > 0 member
  // carries the pair.
  for (int k = 0; k < n_; ++k) {
    const double re = lambda(k).real(), im = lambda(k).imag();
    if (im < 0.0) continue;
    const Eigen::MatrixXcd r = ct.col(k) * bt.row(k);  // residue, p x m
    const Eigen::Map<const Eigen::VectorXcd> rv(r.data(), p_ * m_);
    if (im == 0.0) {
      terms_.push_back({TermKind::kRealPole, re, 0.0, 0, 1});
      cols.push_back(rv.real());
    } else {
      terms_.push_back({TermKind::kPolePair, re, im, 0, 2});
      cols.push_back(2.0 * rv.real());                           // P
      cols.push_back(2.0 * (rv * std::conj(lambda(k))).real());  // Q
    }
  }
  StoreResidues(cols);
  return true;
}

void FrequencyResponse::BuildBlockDiagonal(const StateSpace& bal, bool reducible) {
  const Eigen::MatrixXd& a = bal.A();
  const std::shared_ptr<const RealBlockDiagonalForm> shared = SharedRealBlockDiagonal(a);
  const RealBlockDiagonalForm& form = *shared;
  method_ = Method::kSchur;
  condition_ = form.condition;
  largest_block_ = 1;
  poles_ = reducible ? BlockEigenvalues(a) : form.eigenvalues;
  const Eigen::MatrixXd l = form.Left(bal.C());   // p x n
  const Eigen::MatrixXd r = form.Right(bal.B());  // n x m
  const Eigen::MatrixXd& t = form.t;
  // A group is a real pole, a pole pair in its standardised 2x2 block
  // [a b; c a], or a cluster, brought to complex Schur form on its own.
  const auto is_pair = [&](int g) { return form.group_size(g) == 2 && t(form.start[g] + 1, form.start[g]) != 0.0; };
  for (int g = 0; g < form.groups(); ++g)
    if (form.group_size(g) > 1 && !is_pair(g)) largest_block_ = std::max(largest_block_, form.group_size(g));
  transposed_ = m_ < p_ && largest_block_ > kMaxExpandedBlock;
  if (transposed_) {
    rows_ = m_;
    cols_ = p_;
    d_.transposeInPlace();
  }
  // Residue columns in the layout of G (H, or H^T when transposed).
  const auto outer = [&](int i, int j) -> Eigen::VectorXd {
    Eigen::MatrixXd o = transposed_ ? Eigen::MatrixXd(r.row(j).transpose() * l.col(i).transpose())
                                    : Eigen::MatrixXd(l.col(i) * r.row(j));
    return Eigen::Map<const Eigen::VectorXd>(o.data(), o.size());
  };
  std::vector<Eigen::VectorXd> cols;
  const bool clusters = largest_block_ > 1;
  Eigen::MatrixXcd tc, lc, rc;  // clusters in complex Schur form, at their rows
  if (clusters) {
    tc = Eigen::MatrixXcd::Zero(n_, n_);
    lc = Eigen::MatrixXcd::Zero(p_, n_);
    rc = Eigen::MatrixXcd::Zero(n_, m_);
  }
  for (int g = 0; g < form.groups(); ++g) {
    const int s0 = form.start[g], k = form.group_size(g);
    if (k == 1) {
      terms_.push_back({TermKind::kRealPole, t(s0, s0), 0.0, s0, 1});
      cols.push_back(outer(s0, s0));
    } else if (is_pair(g)) {
      // L (sI - T)^-1 R = (s P - Q) / ((s - a)^2 - b c) with
      //   P = l1 r1 + l2 r2,  Q = a P - b l1 r2 - c l2 r1.
      const double a0 = t(s0, s0), b0 = t(s0, s0 + 1), c0 = t(s0 + 1, s0);
      terms_.push_back({TermKind::kPolePair, a0, form.eigenvalues(s0).imag(), s0, 2});
      const Eigen::VectorXd p = outer(s0, s0) + outer(s0 + 1, s0 + 1);
      cols.push_back(p);
      cols.push_back(a0 * p - b0 * outer(s0, s0 + 1) - c0 * outer(s0 + 1, s0));
    } else {
      const Eigen::ComplexSchur<Eigen::MatrixXcd> schur(t.block(s0, s0, k, k).cast<Complex>());
      if (schur.info() != Eigen::Success) ThrowNotConverged(a);
      const Eigen::MatrixXcd& z = schur.matrixU();
      tc.block(s0, s0, k, k) = schur.matrixT();
      lc.middleCols(s0, k) = l.middleCols(s0, k) * z;
      rc.middleRows(s0, k) = z.adjoint() * r.middleRows(s0, k);
      terms_.push_back({TermKind::kBlock, 0.0, 0.0, s0, k});  // completed below
    }
  }
  if (clusters) {
    std::vector<Term> cluster_terms;
    for (Term& term : terms_)
      if (term.kind == TermKind::kBlock) cluster_terms.push_back(term);
    terms_.erase(std::remove_if(terms_.begin(), terms_.end(), [](const Term& x) { return x.kind == TermKind::kBlock; }),
                 terms_.end());
    if (transposed_) {
      // H^T = (R^T J) (sI - J T^T J)^-1 (J L^T), J the reversal: the blocks
      // stay upper triangular (in reverse order) and the substitution runs
      // on the m < p inputs.
      const Eigen::MatrixXcd rt = rc.transpose().rowwise().reverse();
      rc = lc.transpose().colwise().reverse();
      lc = rt;
      tc = tc.transpose().colwise().reverse().rowwise().reverse().eval();
      for (Term& term : cluster_terms) term.start = n_ - term.start - term.size;
    }
    for (Term& term : cluster_terms) {
      const int s0 = term.start, k = term.size;
      if (k > kMaxExpandedBlock) {
        term.kind = TermKind::kLargeBlock;
        terms_.push_back(term);
        continue;
      }
      terms_.push_back(term);
      // Column pairs (Re, Im) of L_a R_b for a <= b, in the order the
      // weights are computed.
      for (int bi = 0; bi < k; ++bi)
        for (int ai = bi; ai >= 0; --ai) {
          const Eigen::MatrixXcd o = lc.col(s0 + ai) * rc.row(s0 + bi);
          const Eigen::Map<const Eigen::VectorXcd> ov(o.data(), o.size());
          cols.push_back(ov.real());
          cols.push_back(ov.imag());
        }
    }
    tr_ = tc.real();
    ti_ = tc.imag();
    if (largest_block_ > kMaxExpandedBlock) {
      lr_ = lc.real();
      li_ = lc.imag();
      rr_ = rc.real();
      ri_ = rc.imag();
    }
  }
  StoreResidues(cols);
}

void FrequencyResponse::StoreResidues(const std::vector<Eigen::VectorXd>& cols) {
  residues_.resize(static_cast<Eigen::Index>(rows_) * cols_, static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) residues_.col(static_cast<Eigen::Index>(c)) = cols[c];
}

void FrequencyResponse::SolveHessenberg(double omega, Workspace& w, Eigen::MatrixXcd& h) const {
  // Gaussian elimination with partial pivoting on the upper Hessenberg
  // j omega I - H: one subdiagonal entry per column, so rows k and k + 1 are
  // the only candidates; O(n^2 (1 + m)).
  Eigen::MatrixXcd& a = w.m;
  Eigen::MatrixXcd& x = w.x;
  a = -hess_.cast<Complex>();
  a.diagonal().array() += Complex(0.0, omega);
  x = qb_.cast<Complex>();
  for (int k = 0; k + 1 < n_; ++k) {
    if (std::abs(a(k + 1, k)) > std::abs(a(k, k))) {
      a.row(k).segment(k, n_ - k).swap(a.row(k + 1).segment(k, n_ - k));
      x.row(k).swap(x.row(k + 1));
    }
    if (a(k + 1, k) == Complex(0.0)) continue;
    const Complex l = a(k + 1, k) / a(k, k);
    a.row(k + 1).segment(k + 1, n_ - k - 1) -= l * a.row(k).segment(k + 1, n_ - k - 1);
    a(k + 1, k) = 0.0;
    x.row(k + 1) -= l * x.row(k);
  }
  const double tol = pole_tolerance_ + kPoleSlack * kEps * std::abs(omega);
  for (int k = n_ - 1; k >= 0; --k) {
    if (!(std::abs(a(k, k)) > tol)) {
      // A small pivot is not a pole: the pivots of a non-normal H (a high
      // order cascade or companion form) can be tiny 0.1 rad/s away from
      // its nearest pole, where H is finite and the solve backward stable.
      // Only a frequency within the poles' own uncertainty is refused.
      Complex nearest = poles_.size() ? poles_(0) : Complex(0.0, omega);
      for (Eigen::Index i = 0; i < poles_.size(); ++i)
        if (std::abs(poles_(i) - Complex(0.0, omega)) < std::abs(nearest - Complex(0.0, omega))) nearest = poles_(i);
      if (!(std::abs(nearest - Complex(0.0, omega)) > tol)) ThrowOnPole(omega / kTwoPi, nearest);
      // An exactly zero pivot off every pole: perturbed by the rounding
      // bound, as LAPACK's solvers do.
      if (a(k, k) == Complex(0.0)) a(k, k) = tol;
    }
    if (k + 1 < n_) x.row(k) -= a.row(k).segment(k + 1, n_ - k - 1) * x.bottomRows(n_ - k - 1);
    x.row(k) /= a(k, k);
  }
  h = cq_.cast<Complex>() * x;
  h += d_.cast<Complex>();
}

bool FrequencyResponse::HasClusteredPoles(const Eigen::VectorXcd& lambda) {
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    for (Eigen::Index j = i + 1; j < lambda.size(); ++j)
      if (std::abs(lambda(i) - lambda(j)) <= kClusterGap * std::max({std::abs(lambda(i)), std::abs(lambda(j)), 1e-300}))
        return true;
  return false;
}

bool FrequencyResponse::SpansDecades(const Eigen::VectorXcd& lambda) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    const double r = std::abs(lambda(i));
    if (r > 0.0) lo = std::min(lo, r), hi = std::max(hi, r);
  }
  return hi > kVerifySpan * lo;
}

bool FrequencyResponse::AgreesNear(const FrequencyResponse& other, const Eigen::VectorXcd& lambda) const {
  std::vector<double> w;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    if (std::abs(lambda(i)) > 0.0) w.push_back(std::abs(lambda(i)));
  if (w.empty()) return true;
  std::sort(w.begin(), w.end());
  // At most kMaxChecks / 3 pole magnitudes, spread over the sorted list.
  std::vector<double> f_hz;
  const std::size_t picks = std::min<std::size_t>(w.size(), kMaxChecks / 3);
  for (std::size_t i = 0; i < picks; ++i) {
    const double x = w[picks == 1 ? 0 : i * (w.size() - 1) / (picks - 1)];
    for (const double r : {0.5, 1.0, 2.0}) f_hz.push_back(r * x / (2.0 * kPi));
  }
  f_hz.push_back(0.01 * w.front() / (2.0 * kPi));
  f_hz.push_back(100.0 * w.back() / (2.0 * kPi));
  std::vector<std::pair<Eigen::MatrixXcd, Eigen::MatrixXcd>> values;
  double largest = 0.0;
  for (double f : f_hz) {
    try {
      values.emplace_back(At(f), other.At(f));
      largest = std::max(largest, values.back().second.norm());
    } catch (const InputError&) {
      // A check frequency on a pole (an undamped one): not a place to compare.
    }
  }
  for (const auto& [a, b] : values)
    if (!((a - b).norm() <= kAgreement * std::max(b.norm(), 1e-8 * largest))) return false;
  return true;
}

std::string FrequencyResponse::Describe() const {
  std::ostringstream os;
  if (n_ == 0) return "a static gain";
  switch (method_) {
    case Method::kSchur: {
      int largest = 0;
      for (const Term& t : terms_) largest = std::max(largest, t.size);
      os << "the block-diagonal form (" << terms_.size() << (terms_.size() == 1 ? " group" : " groups")
         << ", the largest of " << largest << (largest == 1 ? " state" : " states") << "; cond(Y) " << condition_
         << ")";
      break;
    }
    case Method::kModal:
      os << "the modal form (eigenvector condition " << condition_ << ")";
      break;
    default:
      os << "the Hessenberg solve at every frequency (" << hessenberg_reason_ << ")";
  }
  return os.str();
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
  if (method_ == Method::kHessenberg || columns_ == 0) {
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
    return;
  }
  // Frequencies in blocks: G of a block is residues_ [w_r(f_0), w_i(f_0),
  // w_r(f_1), ...], one matrix product that reads the residues once per
  // block instead of once per frequency (which made the sum bound by memory:
  // 6.4 MB per frequency at 2000 states and 20 x 20). The blocks are fixed by
  // the frequency count alone and handed out whole, so that the last digits
  // do not depend on the thread count (see ModalResponse::ForEach).
  const Eigen::Index size = static_cast<Eigen::Index>(rows_) * cols_;
  const std::size_t block = static_cast<std::size_t>(
      std::clamp(std::floor(kMaxBlockSums / std::max(1.0, 2.0 * static_cast<double>(size))), 1.0,
                 static_cast<double>(kFrequencyBlock)));
  const std::size_t blocks = (f_hz.size() + block - 1) / block;
  const bool blas = BlasProductIsFaster();
  ParallelFor(
      blocks,
      [&](std::size_t b0, std::size_t b1) {
        Workspace w(*this);
        Eigen::MatrixXd weights, sums;
        Eigen::MatrixXcd h(p_, m_);
        std::vector<double> omega;
        for (std::size_t b = b0; b < b1; ++b) {
          const std::size_t k0 = b * block;
          const int count = static_cast<int>(std::min(block, f_hz.size() - k0));
          weights.resize(columns_, 2 * count);
          omega.resize(static_cast<std::size_t>(count));
          for (int i = 0; i < count; ++i) {
            omega[static_cast<std::size_t>(i)] = CheckedOmega(f_hz[k0 + i]);
            ComputeWeights(omega[static_cast<std::size_t>(i)], weights.col(2 * i).data(), weights.col(2 * i + 1).data());
          }
          sums.resize(residues_.rows(), 2 * count);
          if (blas)
            BlasProduct(residues_, weights, sums);
          else
            sums.noalias() = residues_ * weights;
          for (int i = 0; i < count; ++i) {
            Complex* g = transposed_ ? w.g.data() : h.data();
            const double* re = sums.col(2 * i).data();
            const double* im = sums.col(2 * i + 1).data();
            const double* d = d_.data();
            for (Eigen::Index e = 0; e < size; ++e) g[e] = Complex(d[e] + re[e], im[e]);
            if (largest_block_ > kMaxExpandedBlock)
              for (const Term& t : terms_)
                if (t.kind == TermKind::kLargeBlock) AddLargeBlock(t, omega[static_cast<std::size_t>(i)], w, g);
            if (transposed_) h = w.g.transpose();
            fn(k0 + i, h);
          }
        }
      },
      threads, 1);
}

void FrequencyResponse::EvaluateInto(double f_hz, Workspace& w, Eigen::MatrixXcd& h) const {
  const double omega = CheckedOmega(f_hz);
  if (method_ == Method::kHessenberg) {
    SolveHessenberg(omega, w, h);
    return;
  }
  ComputeWeights(omega, w.wr.data(), w.wi.data());
  // G = D + sum_c weight_c residues_.col(c), then the large blocks.
  Complex* g = transposed_ ? w.g.data() : h.data();
  const Eigen::Index size = static_cast<Eigen::Index>(rows_) * cols_;
  const double* res = residues_.data();
  const double* wr = w.wr.data();
  const double* wi = w.wi.data();
  Eigen::Index e = AccumulateChunks<8>(0, size, columns_, res, d_.data(), wr, wi, g);
  e = AccumulateChunks<2>(e, size, columns_, res, d_.data(), wr, wi, g);
  AccumulateChunks<1>(e, size, columns_, res, d_.data(), wr, wi, g);
  if (largest_block_ > kMaxExpandedBlock)
    for (const Term& t : terms_)
      if (t.kind == TermKind::kLargeBlock) AddLargeBlock(t, omega, w, g);
  if (transposed_) h = w.g.transpose();
}

void FrequencyResponse::ComputeWeights(double omega, double* wr, double* wi) const {
  const double tol = pole_tolerance_ + kPoleSlack * kEps * std::abs(omega);
  const double tol2 = tol * tol;  // squared distances: no hypot in the loop
  int c = 0;
  for (const Term& t : terms_) {
    switch (t.kind) {
      case TermKind::kRealPole: {
        // 1 / (j omega - re) = (-re - j omega) / (re^2 + omega^2)
        const double den = t.re * t.re + omega * omega;
        if (den <= tol2) ThrowOnPole(omega / kTwoPi, {t.re, 0.0});
        wr[c] = -t.re / den;
        wi[c] = -omega / den;
        c += 1;
        break;
      }
      case TermKind::kPolePair: {
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
        break;
      }
      case TermKind::kBlock: {
        // W = (j omega I - T_c)^-1, upper triangular, column by column:
        //   W_bb = 1/(s - t_bb),  W_ab = sum_{a<q<=b} t_aq W_qb / (s - t_aa).
        // Column pair (Re, Im) of L_a R_b gets weights W_ab and j W_ab.
        Complex inv_diag[kMaxExpandedBlock], col[kMaxExpandedBlock];
        for (int i = 0; i < t.size; ++i) {
          const int d = t.start + i;
          const double zr = -tr_(d, d), zi = omega - ti_(d, d), zz = zr * zr + zi * zi;
          if (zz <= tol2) ThrowOnPole(omega / kTwoPi, {tr_(d, d), ti_(d, d)});
          inv_diag[i] = Complex(zr / zz, -zi / zz);
        }
        for (int b = 0; b < t.size; ++b) {
          for (int a = b; a >= 0; --a) {
            Complex v = a == b ? Complex(1.0) : Complex(0.0);
            for (int q = a + 1; q <= b; ++q)
              v += Complex(tr_(t.start + a, t.start + q), ti_(t.start + a, t.start + q)) * col[q];
            col[a] = v * inv_diag[a];
            wr[c] = col[a].real();
            wi[c] = col[a].imag();
            wr[c + 1] = -col[a].imag();
            wi[c + 1] = col[a].real();
            c += 2;
          }
        }
        break;
      }
      case TermKind::kLargeBlock:
        for (int i = t.start; i < t.start + t.size; ++i)
          if (tr_(i, i) * tr_(i, i) + (omega - ti_(i, i)) * (omega - ti_(i, i)) <= tol2)
            ThrowOnPole(omega / kTwoPi, {tr_(i, i), ti_(i, i)});
        break;
    }
  }
  DEB_DEMAND(c == columns_);
}

void FrequencyResponse::AddLargeBlock(const Term& term, double omega, Workspace& w,
                                      Complex* g) const {
  const int r = rows_, k = term.size, s0 = term.start;
  // Y = L_c (sI - T_c)^-1 by forward substitution on Y (sI - T_c) = L_c:
  //   y_i = (l_i + sum_{q<i} t_qi y_q) / (s - t_ii).
  double* yr = w.yr.data();
  double* yi = w.yi.data();
  for (int i = 0; i < k; ++i) {
    double* ur = yr + static_cast<Eigen::Index>(i) * r;
    double* ui = yi + static_cast<Eigen::Index>(i) * r;
    for (int q = 0; q < r; ++q) {
      ur[q] = lr_(q, s0 + i);
      ui[q] = li_(q, s0 + i);
    }
    for (int j = 0; j < i; ++j) {
      const double a = tr_(s0 + j, s0 + i), b = ti_(s0 + j, s0 + i);
      const double* vr = yr + static_cast<Eigen::Index>(j) * r;
      const double* vi = yi + static_cast<Eigen::Index>(j) * r;
      for (int q = 0; q < r; ++q) {
        ur[q] += a * vr[q] - b * vi[q];
        ui[q] += a * vi[q] + b * vr[q];
      }
    }
    // 1 / (s - t_ii) = conj(z) / |z|^2
    const double zr = -tr_(s0 + i, s0 + i), zi = omega - ti_(s0 + i, s0 + i);
    const double zz = zr * zr + zi * zi, cr = zr / zz, ci = -zi / zz;
    for (int q = 0; q < r; ++q) {
      const double vr = ur[q], vi = ui[q];
      ur[q] = cr * vr - ci * vi;
      ui[q] = cr * vi + ci * vr;
    }
  }
  // G += Y R_c, column by column.
  for (int j = 0; j < cols_; ++j) {
    Complex* gj = g + static_cast<Eigen::Index>(j) * r;
    for (int q = 0; q < r; ++q) {
      double sr = 0.0, si = 0.0;
      for (int i = 0; i < k; ++i) {
        const double a = rr_(s0 + i, j), b = ri_(s0 + i, j);
        const double vr = yr[static_cast<Eigen::Index>(i) * r + q];
        const double vi = yi[static_cast<Eigen::Index>(i) * r + q];
        sr += a * vr - b * vi;
        si += a * vi + b * vr;
      }
      gj[q] += Complex(sr, si);
    }
  }
}

void FrequencyResponse::ThrowOnPole(double f_hz, std::complex<double> pole) const {
  const double omega = kTwoPi * f_hz;
  std::ostringstream os;
  os << "frequency response: frequency " << f_hz << " Hz coincides with a pole of the path at "
     << pole.real() << (pole.imag() < 0.0 ? "" : "+") << pole.imag() << "j rad/s: it is "
     << std::abs(Complex(0.0, omega) - pole) << " rad/s from it, within the "
     << pole_tolerance_ + kPoleSlack * kEps * std::abs(omega)
     << " rad/s to which the pole is known; H is unbounded there, leave this frequency out of the grid";
  throw InputError(os.str());
}

}  // namespace deb
