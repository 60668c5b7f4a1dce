// A continuous-time linear time-invariant system in state space,
//   x' = A x + B u,   y = C x + D u,
// the one representation every path is converted to: transfer functions,
// interconnections and physical models all end here, so frequency responses
// and exact (Lyapunov) variances are computed one way.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace deb {

class StateSpace {
 public:
  // @throws InputError if sizes disagree or any entry is not finite.
  StateSpace(Eigen::MatrixXd a, Eigen::MatrixXd b, Eigen::MatrixXd c, Eigen::MatrixXd d);

  // A static gain y = D u (no states).
  static StateSpace Gain(Eigen::MatrixXd d);

  int states() const { return static_cast<int>(a_.rows()); }
  int inputs() const { return static_cast<int>(d_.cols()); }
  int outputs() const { return static_cast<int>(d_.rows()); }

  const Eigen::MatrixXd& A() const { return a_; }
  const Eigen::MatrixXd& B() const { return b_; }
  const Eigen::MatrixXd& C() const { return c_; }
  const Eigen::MatrixXd& D() const { return d_; }

  // Eigenvalues of A [rad/s], found block by block on its block triangular
  // form (block_triangular.h): those of a cascade are its stages' own.
  Eigen::VectorXcd Poles() const;
  // All poles strictly in the open left half plane.
  bool IsStable() const;

  // Subsystem with the given output rows / input columns (indices may repeat).
  StateSpace SelectOutputs(const std::vector<int>& rows) const;
  StateSpace SelectInputs(const std::vector<int>& cols) const;

  // The same input-output map under the state scaling x = T x_b, T diagonal
  // with powers of two (exact in floating point), chosen so that rows and
  // columns of A have similar norms (Parlett & Reinsch, Numer. Math. 13, 1969).
  // Companion forms and models in mixed units (mm next to um) have entries
  // spanning many decades; balancing makes their eigenvalues and
  // eigenvectors better conditioned.
  StateSpace Balanced() const;

 private:
  Eigen::MatrixXd a_, b_, c_, d_;
};

// The diagonal of the scaling T used by StateSpace::Balanced(): powers of two
// with T^-1 A T balanced. For other solvers on A (Lyapunov).
Eigen::VectorXd BalancingScale(const Eigen::MatrixXd& a);

// For the reductions of a balanced state matrix (frequency responses,
// Lyapunov): @throws InputError "the state matrix is too badly scaled ..."
// if |A|_F exceeds limits::kMaxStateMatrixNorm.
void RequireWellScaled(const Eigen::MatrixXd& balanced_a);

// @throws InputError "the state matrix is too badly scaled ...", for an
//         eigenvalue or Schur iteration on `a` that did not converge.
[[noreturn]] void ThrowNotConverged(const Eigen::MatrixXd& a);

}  // namespace deb
