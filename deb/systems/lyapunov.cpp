#include "deb/systems/lyapunov.h"

#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/block_triangular.h"
#include "deb/systems/lapack.h"
#include "deb/systems/parallel_product.h"
#include "deb/systems/real_block_diagonal.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// OutputCovariance refuses a variance whose estimated relative error is larger.
constexpr double kMaxRelativeError = 1e-6;

// "+0.3 rad/s", "-0.1+2j rad/s", or "-0.1±2j rad/s" for a conjugate pair.
std::string FormatPole(Complex p, bool pair = false) {
  std::ostringstream os;
  os << std::showpos << p.real();
  if (p.imag() != 0.0) {
    if (pair) os << std::noshowpos << "\u00b1" << std::abs(p.imag()) << "j";
    else os << p.imag() << "j";
  }
  os << " rad/s";
  return os.str();
}

void RequireFinite(const Eigen::MatrixXd& m, const char* where, const char* name) {
  if (!m.allFinite()) {
    std::ostringstream os;
    os << where << ": " << name << " has an entry that is not finite";
    throw InputError(os.str());
  }
}

// "SolveLyapunov: singular equation, ...", naming poles a and b of A with
// a + b ~ 0.
[[noreturn]] void ThrowSingular(Complex a, Complex b) {
  std::ostringstream os;
  os << "SolveLyapunov: singular equation, poles " << FormatPole(a) << " and " << FormatPole(b)
     << " sum to zero (no unique solution; is a pole on the imaginary axis?)";
  throw InputError(os.str());
}

// Block Bartels-Stewart for a scaled A, reusable for several right-hand sides.
// The states are first permuted so that A is block upper triangular with
// irreducible diagonal blocks (block_triangular.h; a series connection gives
// one block per stage). Each diagonal block gets its own real Schur form A_ii =
// U_i T_i U_i^T (LAPACK dgees) and P is found block by block from the
// Sylvester equations
//   A_ii P_ij + P_ij A_jj^T = -Q_ij - sum_{k>i} A_ik P_kj - sum_{k>j} P_ik A_jk^T,
// i.e. T_i Y + Y T_j^T = U_i^T (right-hand side) U_j with P_ij = U_i Y U_j^T,
// each solved by LAPACK's quasi-triangular dtrsyl: real arithmetic
// throughout, conjugate pole pairs kept together in 2x2 blocks.
// The structural zeros of A stay exactly zero: a dense Schur form would
// spread rounding of size eps |A| into them, i.e. feedback from the
// large states of a cascade's last stages into the small states of its first.
class BlockLyapunov {
 public:
  // @throws InputError if lambda_i + conj(lambda_j) ~ 0 (when check_singular).
  BlockLyapunov(const Eigen::MatrixXd& ab, bool check_singular) {
    const Eigen::Index n = ab.rows();
    const BlockTriangularForm form = BlockTriangular(ab);
    perm_ = form.perm;
    start_ = form.start;
    ap_ = ab(perm_, perm_);
    const int blocks = static_cast<int>(start_.size()) - 1;
    schur_.reserve(blocks);
    for (int b = 0; b < blocks; ++b) {
      const Eigen::Index at = start_[b], size = start_[b + 1] - at;
      schur_.push_back(RealSchur(ap_.block(at, at, size, size)));
    }
    if (!check_singular) return;
    Eigen::VectorXcd lambda(n);
    for (int b = 0; b < blocks; ++b)
      lambda.segment(start_[b], schur_[b].eigenvalues.size()) = schur_[b].eigenvalues;
    const double tol = 1e3 * kEps * std::max(ab.norm(), std::numeric_limits<double>::min());
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = i; j < n; ++j)
        if (std::abs(lambda(i) + std::conj(lambda(j))) <= tol)
          ThrowSingular(lambda(i), std::conj(lambda(j)));
  }

  int blocks() const { return static_cast<int>(start_.size()) - 1; }

  // The two eigenvalues a, b of A_b (b may be a) whose sum a + conj(b) is
  // smallest in modulus: the pair nearest to making the equation singular.
  std::pair<Complex, Complex> NearestPair() const {
    std::vector<Complex> lambda;
    for (const RealSchurForm& f : schur_)
      for (Eigen::Index k = 0; k < f.eigenvalues.size(); ++k) lambda.push_back(f.eigenvalues(k));
    std::pair<Complex, Complex> best{lambda.front(), lambda.front()};
    for (std::size_t i = 0; i < lambda.size(); ++i)
      for (std::size_t j = i; j < lambda.size(); ++j)
        if (std::abs(lambda[i] + std::conj(lambda[j])) < std::abs(best.first + std::conj(best.second)))
          best = {lambda[i], lambda[j]};
    return best;
  }

  // X with A_b X + X A_b^T + Q_b = 0.
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& qb) const {
    const Eigen::Index n = ap_.rows();
    const Eigen::MatrixXd qp = qb(perm_, perm_);
    Eigen::MatrixXd xp = Eigen::MatrixXd::Zero(n, n);
    const int nb = blocks();
    for (int i = nb - 1; i >= 0; --i) {
      const Eigen::Index ri = start_[i], ni = start_[i + 1] - ri, after_i = n - ri - ni;
      for (int j = nb - 1; j >= 0; --j) {
        const Eigen::Index rj = start_[j], nj = start_[j + 1] - rj, after_j = n - rj - nj;
        Eigen::MatrixXd r = -qp.block(ri, rj, ni, nj);
        if (after_i > 0)
          r.noalias() -= ap_.block(ri, ri + ni, ni, after_i) * xp.block(ri + ni, rj, after_i, nj);
        if (after_j > 0)
          r.noalias() -=
              xp.block(ri, rj + nj, ni, after_j) * ap_.block(rj, rj + nj, nj, after_j).transpose();
        const RealSchurForm &si = schur_[i], &sj = schur_[j];
        // dtrsyl's "perturbed values were used" (near_singular) is not a
        // verdict: it compares each pivot with eps times the larger norm of
        // the two blocks, which a non-normal block (a stiff section in graded
        // coordinates) exceeds by far while the equation is well posed. The
        // perturbation is of the size of the rounding, so the solution is as
        // good as any other; the residual and error estimate of the callers
        // judge it, and a pair of poles that truly sums to zero was refused
        // in the constructor.
        const SylvesterSolution y =
            SolveQuasiTriangularSylvester(si.t, sj.t, si.u.transpose() * r * sj.u);
        xp.block(ri, rj, ni, nj) = si.u * y.x * sj.u.transpose();
      }
    }
    Eigen::MatrixXd x(n, n);
    x(perm_, perm_) = xp;
    if (qb == qb.transpose()) x = 0.5 * (x + x.transpose()).eval();
    return x;
  }

 private:
  std::vector<int> perm_, start_;
  Eigen::MatrixXd ap_;
  std::vector<RealSchurForm> schur_;  // of each diagonal block
};

// The solution in the scaled coordinates x = diag(scale) x_b:
//   A_b P_b + P_b A_b^T + Q_b = 0,  A_b = T^-1 A T,  Q_b = T^-1 Q T^-1,
// and P = T P_b T.
struct ScaledLyapunov {
  Eigen::VectorXd scale;
  Eigen::MatrixXd ab, qb, pb;
  std::optional<BlockLyapunov> solver;
  double residual = 0.0, residual_bound = 0.0;  // |A_b P_b + P_b A_b^T + Q_b|_F
  // Largest estimated relative error |dP_ii| / P_ii over the excited states
  // (symmetric Q only; invariant under diagonal scaling, so the passes can be
  // compared by it).
  double diagonal_error = 0.0;
  bool Reliable() const { return pb.allFinite() && residual <= residual_bound; }
};

// Residual and error estimate of the pass in s. The computed P_b solves the
// equation with right-hand side Q_b - R, R the residual, so its error is
// L^-1(R): one more solve with the same Schur forms.
void Assess(ScaledLyapunov& s, bool symmetric) {
  const Eigen::Index n = s.ab.rows();
  const Eigen::MatrixXd r = s.ab * s.pb + s.pb * s.ab.transpose() + s.qb;
  // Bartels-Stewart is backward stable: the residual is a few eps relative to
  // |A||P| + |Q|; a larger one means the computed P is not a solution.
  s.residual = r.norm();
  s.residual_bound = 1e-10 * std::sqrt(static_cast<double>(n)) *
                     (2.0 * s.ab.norm() * s.pb.norm() + s.qb.norm());
  s.diagonal_error = 0.0;
  if (!symmetric) return;
  if (!s.pb.allFinite()) {
    s.diagonal_error = std::numeric_limits<double>::infinity();
    return;
  }
  const Eigen::MatrixXd e = s.solver->Solve(-r);
  const double largest = s.pb.diagonal().cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(std::abs(s.pb(i, i)) > kEps * kEps * largest)) continue;  // not excited
    const double rel = s.pb(i, i) > 0.0 ? std::abs(e(i, i)) / s.pb(i, i)
                                        : std::numeric_limits<double>::infinity();
    s.diagonal_error = std::max(s.diagonal_error, std::isfinite(rel) ? rel : HUGE_VAL);
  }
}

ScaledLyapunov SolveScaled(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q) {
  const Eigen::Index n = a.rows();
  const bool symmetric = q == q.transpose();
  // Pass 0: balancing A (exact powers of two), which helps models in mixed
  // units. Later passes (symmetric Q only) equilibrate P itself: state i is
  // rescaled by 2^round(log2 sqrt(P_b,ii)) so that diag(P_b) ~ 1 (within a
  // factor n of the best diagonal scaling for P_b's condition; van der Sluis,
  // Numer. Math. 14, 1969). Bartels-Stewart is backward stable only normwise,
  // so graded state scales cost accuracy: for the ten-resonator cascade as one
  // dense block (variances 1e-3 ... 1e13) the condition number |L^-1| |A_b| of
  // L(P) = A_b P + P A_b^T is ~1e17 before and ~1e6 ... 1e8 after this
  // rescaling. The block-triangular solve (BlockLyapunov) already keeps a
  // cascade exact; the rescaling is for graded dense blocks, and it needs a
  // pass-0 P that is right to a factor ~2. Powers of two keep scalings exact.
  // Equilibrating P can also hurt: a 1e4 Hz section driven by a 1e-3 Hz one
  // has position and velocity variances in the ratio of the slow section's
  // frequency, not its own, and scaling them equal makes its block of A_b
  // non-normal by ~1e7. So every pass is assessed (its estimated relative
  // error of diag P, which diagonal scaling leaves comparable) and the best
  // one is kept.
  std::optional<ScaledLyapunov> best;
  Eigen::VectorXd scale = BalancingScale(a);
  constexpr int kMaxRefinements = 3;
  for (int pass = 0;; ++pass) {
    ScaledLyapunov s;
    s.scale = scale;
    const Eigen::VectorXd inv = s.scale.cwiseInverse();
    s.ab = inv.asDiagonal() * a * s.scale.asDiagonal();
    s.qb = inv.asDiagonal() * q * inv.asDiagonal();
    s.solver.emplace(s.ab, pass == 0);
    s.pb = s.solver->Solve(s.qb);
    Assess(s, symmetric);
    const bool better = !best || (s.Reliable() && !best->Reliable()) ||
                        (s.Reliable() == best->Reliable() && s.diagonal_error < best->diagonal_error);
    if (better) best = s;
    if (!symmetric || pass == kMaxRefinements || !s.pb.allFinite() || !better) break;
    const double largest = s.pb.diagonal().maxCoeff();
    if (!(largest > 0.0)) break;
    // States with P_ii ~ 0 (not excited) keep their scale.
    Eigen::VectorXi e = Eigen::VectorXi::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i)
      if (s.pb(i, i) > kEps * kEps * largest)
        e(i) = static_cast<int>(std::lround(0.5 * std::log2(s.pb(i, i))));
    if (e.cwiseAbs().maxCoeff() <= 1) break;  // already within a factor 2
    for (Eigen::Index i = 0; i < n; ++i) scale(i) = std::ldexp(scale(i), e(i));
  }
  return *std::move(best);
}

}  // namespace

Eigen::MatrixXd SolveLyapunov(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q) {
  const Eigen::Index n = a.rows();
  if (a.cols() != n || q.rows() != n || q.cols() != n) {
    std::ostringstream os;
    os << "SolveLyapunov: A is " << a.rows() << "x" << a.cols() << " and Q is " << q.rows()
       << "x" << q.cols() << "; both must be square of the same size";
    throw InputError(os.str());
  }
  RequireFinite(a, "SolveLyapunov", "A");
  RequireFinite(q, "SolveLyapunov", "Q");
  if (n == 0) return Eigen::MatrixXd(0, 0);
  const ScaledLyapunov s = SolveScaled(a, q);
  if (!s.Reliable()) {
    std::ostringstream os;
    os << "SolveLyapunov: the Schur solution is not reliable: residual |A P + P A^T + Q| = "
       << s.residual << " (scaled) exceeds " << s.residual_bound
       << (s.pb.allFinite() ? "" : ", P has an entry that is not finite");
    throw InputError(os.str());
  }
  return s.scale.asDiagonal() * s.pb * s.scale.asDiagonal();
}

namespace {

// Couplings of the block-diagonal form up to this condition number are used
// for the exact variance of an irreducible A (a dense model, a loop): the
// bound up to which the form is built at all (real_block_diagonal.h's
// coupling bound, and the response's check, frequency_response.h). Within
// it the solution is accepted only if its own error estimate, which grows
// with cond(Y), is below 1e-6 of each variance (BlockDiagonalCovariance).
constexpr double kMaxBlockCondition = 1e6;

// X with D_i X + X D_j^T + Q = 0 for two diagonal blocks of a real Schur
// form (1x1 or 2x2 each: the Kronecker system, at most 4x4; larger groups
// through dtrsyl).
Eigen::MatrixXd SolveGroupPair(const Eigen::MatrixXd& di, const Eigen::MatrixXd& dj, const Eigen::MatrixXd& q) {
  const Eigen::Index ki = di.rows(), kj = dj.rows();
  if (ki > 2 || kj > 2) return SolveQuasiTriangularSylvester(di, dj, -q).x;
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1>;
  Small k = Small::Zero(ki * kj, ki * kj);
  // vec(D_i X) = (I (x) D_i) vec X, vec(X D_j^T) = (D_j (x) I) vec X.
  for (Eigen::Index b = 0; b < kj; ++b)
    for (Eigen::Index a = 0; a < ki; ++a)
      for (Eigen::Index c = 0; c < ki; ++c) k(b * ki + a, b * ki + c) += di(a, c);
  for (Eigen::Index b = 0; b < kj; ++b)
    for (Eigen::Index d = 0; d < kj; ++d)
      for (Eigen::Index a = 0; a < ki; ++a) k(b * ki + a, d * ki + a) += dj(b, d);
  SmallVector rhs(ki * kj);
  for (Eigen::Index b = 0; b < kj; ++b)
    for (Eigen::Index a = 0; a < ki; ++a) rhs(b * ki + a) = -q(a, b);
  const SmallVector x = k.partialPivLu().solve(rhs);
  Eigen::MatrixXd out(ki, kj);
  for (Eigen::Index b = 0; b < kj; ++b)
    for (Eigen::Index a = 0; a < ki; ++a) out(a, b) = x(b * ki + a);
  return out;
}

// X with D X + X D^T + Q = 0 for the block-diagonal D of `form` and a
// symmetric Q: one SolveGroupPair per pair of groups i <= j, X_ji = X_ij^T.
Eigen::MatrixXd SolveGroupLyapunov(const RealBlockDiagonalForm& form, const Eigen::MatrixXd& q) {
  Eigen::MatrixXd x(q.rows(), q.cols());
  for (int i = 0; i < form.groups(); ++i) {
    const int si = form.start[i], ki = form.group_size(i);
    const Eigen::MatrixXd di = form.t.block(si, si, ki, ki);
    for (int j = i; j < form.groups(); ++j) {
      const int sj = form.start[j], kj = form.group_size(j);
      const Eigen::MatrixXd xij = SolveGroupPair(di, form.t.block(sj, sj, kj, kj), q.block(si, sj, ki, kj));
      x.block(si, sj, ki, kj) = xij;
      if (j != i) x.block(sj, si, kj, ki) = xij.transpose();
    }
  }
  return x;
}

// C P C^T on the block-diagonal form A = S D S^-1 (real_block_diagonal.h):
// with L = C S, R = S^-1 B, the state covariance is P = S X S^T where
//   D_i X_ij + X_ij D_j^T + R_i W R_j^T = 0
// for every pair of groups, a Sylvester equation of at most 4 unknowns for
// poles and pairs: O(n^2 (m + p)) in all instead of a Schur solve of the
// whole n x n equation.
//
// Its error is estimated from the residual of the reduction itself: in the
// coordinates of the form, A is D + E with E = Y^-1 (U^T A U) Y - D (the
// Schur form's backward error and the decoupling's rounding, formed in
// double: of the size of the rounding it measures), which moves X by dX with
//   D dX + dX D^T + E X + X E^T = 0,
// solved block by block as X is, and the variances by L dX L^T. Returns
// nothing if ten times that estimate, plus the rounding of the sums (8 n eps
// cond(Y) times the sum of the absolute terms), exceeds 1e-6 of a variance,
// or a variance is negative or not finite: the caller then solves the whole
// equation, which estimates its error from its own residual.
std::optional<Eigen::MatrixXd> BlockDiagonalCovariance(const RealBlockDiagonalForm& form, const StateSpace& bal,
                                                       const Eigen::MatrixXd& w) {
  const Eigen::MatrixXd l = form.Left(bal.C());
  const Eigen::MatrixXd r = form.Right(bal.B());
  const Eigen::MatrixXd q = r * w * r.transpose();
  const int n = static_cast<int>(q.rows()), groups = form.groups();
  const Eigen::MatrixXd x = SolveGroupLyapunov(form, q);
  if (!x.allFinite()) return std::nullopt;
  Eigen::MatrixXd y = l * (x * l.transpose());
  y = 0.5 * (y + y.transpose()).eval();
  const Eigen::MatrixXd abs_y = l.cwiseAbs() * (x.cwiseAbs() * l.cwiseAbs().transpose());
  // The n^3 products (ParallelProduct: Eigen's on all threads, or the
  // BLAS's AVX-512 one on one): most of this function's time at 2000 states.
  const auto upper = form.y.triangularView<Eigen::UnitUpper>();
  const Eigen::MatrixXd uau = ParallelProduct(form.u.transpose(), ParallelProduct(bal.A(), form.u));  // U^T A U
  // (U^T A U) Y, Y upper triangular (zero below its diagonal): a block of
  // Y's columns has entries in its first first + count rows only, half
  // the multiplications of the full product.
  const bool blas = BlasProductIsFaster();
  Eigen::MatrixXd e(n, n);
  ForColumnBlocks(n, [&](Eigen::Index first, Eigen::Index count) {
    const Eigen::Index rows = first + count;
    if (blas)
      BlasProduct(uau.leftCols(rows), form.y.block(0, first, rows, count), e.middleCols(first, count));
    else
      e.middleCols(first, count).noalias() = uau.leftCols(rows) * form.y.block(0, first, rows, count);
  });
  // Y^-1 (U^T A U) Y: one call to the BLAS (as ParallelProduct), or Eigen's
  // solve by blocks of columns on all threads.
  if (blas)
    BlasUnitUpperSolve(form.y, e);
  else
    ForColumnBlocks(n, [&](Eigen::Index first, Eigen::Index count) { upper.solveInPlace(e.middleCols(first, count)); });
  for (int g = 0; g < groups; ++g)
    e.block(form.start[g], form.start[g], form.group_size(g), form.group_size(g)) -=
        form.t.block(form.start[g], form.start[g], form.group_size(g), form.group_size(g));
  Eigen::MatrixXd ex = ParallelProduct(e, x);
  ex += ex.transpose().eval();
  const Eigen::MatrixXd dx = SolveGroupLyapunov(form, ex);
  const Eigen::MatrixXd dy = l * (dx * l.transpose());
  for (int i = 0; i < y.rows(); ++i) {
    const double rounding = 8.0 * n * kEps * form.condition * abs_y(i, i);
    if (!std::isfinite(y(i, i)) || y(i, i) < -rounding) return std::nullopt;
    if (abs_y(i, i) > 0.0 && !(rounding + 10.0 * std::abs(dy(i, i)) <= kMaxRelativeError * y(i, i)))
      return std::nullopt;
    if (y(i, i) < 0.0) y(i, i) = 0.0;
  }
  return y;
}

}  // namespace

Eigen::MatrixXd OutputCovariance(const StateSpace& sys, const Eigen::MatrixXd& w_two_sided) {
  const Eigen::MatrixXd& w = w_two_sided;
  const int m = sys.inputs(), p = sys.outputs();
  if (w.rows() != m || w.cols() != m) {
    std::ostringstream os;
    os << "OutputCovariance: noise intensity W is " << w.rows() << "x" << w.cols()
       << " but the path has " << m << " inputs (W must be " << m << "x" << m << ")";
    throw InputError(os.str());
  }
  RequireFinite(w, "OutputCovariance", "W");
  const double w_scale = w.cwiseAbs().maxCoeff();
  for (int i = 0; i < m; ++i) {
    if (w(i, i) < 0.0) {
      std::ostringstream os;
      os << "OutputCovariance: W(" << i + 1 << "," << i + 1 << ") = " << w(i, i)
         << " is negative; an intensity must be >= 0";
      throw InputError(os.str());
    }
    for (int j = 0; j < i; ++j)
      if (std::abs(w(i, j) - w(j, i)) > 1e-12 * w_scale) {
        std::ostringstream os;
        os << "OutputCovariance: W is not symmetric, W(" << i + 1 << "," << j + 1
           << ") = " << w(i, j) << " but W(" << j + 1 << "," << i + 1 << ") = " << w(j, i);
        throw InputError(os.str());
      }
  }
  // White noise passed straight to an output has infinite variance.
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < m; ++j)
      if (sys.D()(i, j) != 0.0 && w(j, j) > 0.0) {
        std::ostringstream os;
        os << "OutputCovariance: infinite variance: direct feedthrough D != 0 under white "
              "noise (D("
           << i + 1 << "," << j + 1 << ") = " << sys.D()(i, j) << " and input " << j + 1
           << " has intensity " << w(j, j) << ")";
        throw InputError(os.str());
      }
  if (sys.states() == 0) return Eigen::MatrixXd::Zero(p, p);

  // Similarity-invariant: C P C^T is the same for the balanced realisation,
  // whose poles are better conditioned (SolveScaled rescales it further).
  const StateSpace bal = sys.Balanced();
  RequireWellScaled(bal.A());
  // An irreducible A (a dense model, a loop) is reduced to block-diagonal
  // form, which gives its poles too; a reducible one (a cascade) is solved
  // stage by stage below, since a Schur form of the whole A could round
  // away the couplings between stages (frequency_response.h).
  std::shared_ptr<const RealBlockDiagonalForm> form;
  if (!HasCoupledBlocks(bal.A())) form = SharedRealBlockDiagonal(bal.A());
  const Eigen::VectorXcd poles = form ? form->eigenvalues : bal.Poles();
  const double stable_margin = 64.0 * kEps * bal.A().norm();
  std::ostringstream unstable;
  int count = 0;
  for (Eigen::Index k = 0; k < poles.size(); ++k) {
    if (poles(k).real() < -stable_margin || poles(k).imag() < 0.0) continue;
    unstable << (count++ ? ", " : "") << FormatPole(poles(k), true);
  }
  if (count > 0) {
    std::ostringstream os;
    os << "OutputCovariance: exact variance needs a stable path; pole" << (count > 1 ? "s" : "")
       << " at " << unstable.str()
       << (count > 1 ? " are" : " is") << " not in the open left half plane";
    throw InputError(os.str());
  }
  if (form && form->condition <= kMaxBlockCondition)
    if (std::optional<Eigen::MatrixXd> y = BlockDiagonalCovariance(*form, bal, w)) return *y;
  const ScaledLyapunov s = SolveScaled(bal.A(), bal.B() * w * bal.B().transpose());
  const auto unreliable = [](const std::string& why) {
    return InputError("OutputCovariance: exact variance is not reliable for this realisation: " +
                      why);
  };
  if (!s.Reliable()) {
    std::ostringstream os;
    if (!s.pb.allFinite()) os << "the state covariance has an entry that is not finite";
    else
      os << "the Lyapunov residual " << s.residual << " exceeds " << s.residual_bound
         << " (the Schur solution failed)";
    throw unreliable(os.str());
  }
  const Eigen::MatrixXd cb = bal.C() * s.scale.asDiagonal();  // C x = C T x_b
  Eigen::MatrixXd y = cb * s.pb * cb.transpose();
  y = 0.5 * (y + y.transpose()).eval();
  // Error estimate: the computed P_b solves the equation with right-hand side
  // Q_b - R, R the residual, so its error is L^-1(R) (one solve with the same
  // Schur forms). R is formed in long double: in double its own rounding is
  // of the size of R, and the estimate missed errors of up to 4.1e-6 (cascades
  // of nearly repeated lightly damped pairs, tests/systems/lyapunov_test.cpp);
  // in long double it is 2^-11 of R. (Correcting P by the estimate, iterative
  // refinement, would need R in double-double: with R in long double it
  // stalled at errors of 1.7e-6 that the next estimate put at 1.4e-7.)
  using MatrixLD = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const MatrixLD abl = s.ab.cast<long double>(), pbl = s.pb.cast<long double>();
  const Eigen::MatrixXd residual =
      (abl * pbl + pbl * abl.transpose() + s.qb.cast<long double>()).cast<double>();
  const Eigen::MatrixXd dy = cb * s.solver->Solve(-residual) * cb.transpose();
  const Eigen::MatrixXd abs_y = cb.cwiseAbs() * s.pb.cwiseAbs() * cb.cwiseAbs().transpose();
  for (int i = 0; i < p; ++i) {
    // Rounding in C P C^T alone is a few eps of |C| |P| |C|^T.
    const double rounding = 64.0 * kEps * abs_y(i, i);
    std::ostringstream os;
    if (!std::isfinite(y(i, i))) {
      os << "output " << i + 1 << " variance " << y(i, i) << " is not finite";
      throw unreliable(os.str());
    }
    if (y(i, i) < -rounding) {
      os << "output " << i + 1 << " variance " << y(i, i) << " is negative";
      throw unreliable(os.str());
    }
    if (!(std::abs(dy(i, i)) <= kMaxRelativeError * y(i, i) + rounding)) {
      const auto [a, b] = s.solver->NearestPair();
      os << "output " << i + 1 << " variance " << y(i, i) << " has an estimated error of "
         << std::abs(dy(i, i)) << " (more than " << kMaxRelativeError
         << " relative; the Lyapunov equation is ill-conditioned even after rescaling the "
            "states; the two poles nearest to summing to zero, "
         << FormatPole(a) << " and " << FormatPole(std::conj(b)) << ", sum to "
         << FormatPole(a + std::conj(b)) << ")";
      throw unreliable(os.str());
    }
    if (y(i, i) < 0.0) y(i, i) = 0.0;  // rounding around a zero variance
  }
  return y;
}

}  // namespace deb
