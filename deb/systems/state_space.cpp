#include "deb/systems/state_space.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/systems/block_triangular.h"

namespace deb {
namespace {

void RequireFinite(const Eigen::MatrixXd& m, const char* name) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j))) {
        std::ostringstream os;
        os << "state space: " << name << "(" << i + 1 << "," << j + 1 << ") = " << m(i, j)
           << " is not finite";
        throw InputError(os.str());
      }
}

}  // namespace

StateSpace::StateSpace(Eigen::MatrixXd a, Eigen::MatrixXd b, Eigen::MatrixXd c,
                       Eigen::MatrixXd d)
    : a_(std::move(a)), b_(std::move(b)), c_(std::move(c)), d_(std::move(d)) {
  const auto n = a_.rows();
  std::ostringstream os;
  if (a_.cols() != n) {
    os << "state space: A must be square, got " << a_.rows() << "x" << a_.cols();
  } else if (b_.rows() != n) {
    os << "state space: B must have " << n << " rows (states), got " << b_.rows();
  } else if (c_.cols() != n) {
    os << "state space: C must have " << n << " columns (states), got " << c_.cols();
  } else if (d_.rows() != c_.rows() || d_.cols() != b_.cols()) {
    os << "state space: D must be " << c_.rows() << "x" << b_.cols() << " (outputs x inputs), got "
       << d_.rows() << "x" << d_.cols();
  }
  if (!os.str().empty()) throw InputError(os.str());
  RequireFinite(a_, "A");
  RequireFinite(b_, "B");
  RequireFinite(c_, "C");
  RequireFinite(d_, "D");
}

StateSpace StateSpace::Gain(Eigen::MatrixXd d) {
  const auto p = d.rows(), m = d.cols();
  return StateSpace(Eigen::MatrixXd(0, 0), Eigen::MatrixXd(0, m), Eigen::MatrixXd(p, 0),
                    std::move(d));
}

Eigen::VectorXcd StateSpace::Poles() const {
  if (states() == 0) return Eigen::VectorXcd(0);
  return BlockEigenvalues(a_);
}

void RequireWellScaled(const Eigen::MatrixXd& balanced_a) {
  const double norm = balanced_a.stableNorm();  // |A| of 1e300 does not overflow
  if (norm <= limits::kMaxStateMatrixNorm) return;
  std::ostringstream os;
  os << "the state matrix is too badly scaled: its norm is " << norm
     << " after balancing, more than the " << limits::kMaxStateMatrixNorm
     << " deb can reduce (its poles would be known only to eps times that); rescale the "
        "model's states or units";
  throw InputError(os.str());
}

void ThrowNotConverged(const Eigen::MatrixXd& a) {
  std::ostringstream os;
  os << "the state matrix is too badly scaled for its poles to be computed: the QR iteration "
        "did not converge (entries of A up to "
     << (a.size() ? a.cwiseAbs().maxCoeff() : 0.0) << " in magnitude); rescale the model's "
        "states or units";
  throw InputError(os.str());
}

bool StateSpace::IsStable() const {
  const Eigen::VectorXcd p = Poles();
  for (Eigen::Index i = 0; i < p.size(); ++i)
    if (!(p(i).real() < 0.0)) return false;
  return true;
}

StateSpace StateSpace::SelectOutputs(const std::vector<int>& rows) const {
  for (const int r : rows) DEB_DEMAND(r >= 0 && r < outputs());
  // Indexed rows, not row(k) blocks: a row block of a matrix without columns
  // (no states, or no inputs) would offset its null data pointer.
  return StateSpace(a_, b_, c_(rows, Eigen::all), d_(rows, Eigen::all));
}

StateSpace StateSpace::SelectInputs(const std::vector<int>& cols) const {
  Eigen::MatrixXd b(states(), cols.size()), d(outputs(), cols.size());
  for (std::size_t k = 0; k < cols.size(); ++k) {
    DEB_DEMAND(cols[k] >= 0 && cols[k] < inputs());
    b.col(k) = b_.col(cols[k]);
    d.col(k) = d_.col(cols[k]);
  }
  return StateSpace(a_, std::move(b), c_, std::move(d));
}

Eigen::VectorXd BalancingScale(const Eigen::MatrixXd& a) {
  DEB_DEMAND(a.rows() == a.cols());
  const Eigen::Index n = a.rows();
  Eigen::MatrixXd ab = a;
  Eigen::VectorXd t = Eigen::VectorXd::Ones(n);
  const auto off_diagonal_norm = [&](const auto& v, Eigen::Index skip) {
    double sum = 0.0;
    for (Eigen::Index k = 0; k < v.size(); ++k)
      if (k != skip) sum += v(k) * v(k);
    return std::sqrt(sum);
  };
  // Each pass scales state i by a power of two f so that the off-diagonal
  // column norm (times f) and row norm (divided by f) approach each other.
  constexpr int kMaxPasses = 100;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double col = off_diagonal_norm(ab.col(i), i), row = off_diagonal_norm(ab.row(i), i);
      if (col == 0.0 || row == 0.0) continue;
      const int e = static_cast<int>(std::lround(0.5 * std::log2(row / col)));
      if (e == 0) continue;
      const double f = std::ldexp(1.0, e);
      // Only accept scalings that reduce the combined norm noticeably.
      if (col * f + row / f >= 0.95 * (col + row)) continue;
      ab.col(i) *= f;
      ab.row(i) /= f;
      t(i) *= f;
      changed = true;
    }
    if (!changed) break;
  }
  return t;
}

StateSpace StateSpace::Balanced() const {
  const Eigen::VectorXd t = BalancingScale(a_);
  const Eigen::VectorXd t_inv = t.cwiseInverse();  // exact: powers of two
  return StateSpace(t_inv.asDiagonal() * a_ * t.asDiagonal(), t_inv.asDiagonal() * b_,
                    c_ * t.asDiagonal(), d_);
}

}  // namespace deb
