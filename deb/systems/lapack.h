// Dense real eigenvalue problems and quasi-triangular Sylvester equations
// through LAPACK (its C interface LAPACKE). This is the only code in deb that
// talks to LAPACK: callers see Eigen types only. Every LAPACK status is
// checked: an illegal argument is a programming error (DEB_DEMAND), a QR
// iteration that does not converge throws, and no result is returned that
// LAPACK did not vouch for.
//
// Why LAPACK and not Eigen's solvers: dgeev and dgees (Francis QR with
// aggressive early deflation, blocked Hessenberg reduction) are faster than
// Eigen's EigenSolver for dense A of hundreds of states and more, and the
// real Schur form with dtrsyl keeps the Lyapunov solver in real arithmetic
// (Eigen's ComplexSchur runs complex QR iterations; tools/bench/bench_dense).
//
// Conjugate pairs: LAPACK takes each complex pair from one standardised 2x2
// block of the real Schur form, so real eigenvalues have imaginary part 0
// exactly, and complex ones come as exact conjugates, the one with imaginary
// part > 0 first; their eigenvectors are exact conjugates too.
#pragma once

#include <Eigen/Dense>

namespace deb {

// A = U T U^T with U orthogonal and T quasi upper triangular (real Schur
// form, dgees, no reordering): 1x1 blocks for real eigenvalues, standardised
// 2x2 blocks [a b; c a] with b c < 0 for the pairs a +- j sqrt(-b c).
struct RealSchurForm {
  Eigen::MatrixXd t;
  Eigen::MatrixXd u;
  // The eigenvalues in the order of T's diagonal: a pair's 2x2 block gives
  // the +j member first.
  Eigen::VectorXcd eigenvalues;
};

// @throws InputError if A is not square or not finite, or if the QR
//         iteration does not converge.
RealSchurForm RealSchur(const Eigen::MatrixXd& a);

// The eigenvalues of a square A (dgeev, balanced), in LAPACK's order.
// @throws InputError as RealSchur.
Eigen::VectorXcd Eigenvalues(const Eigen::MatrixXd& a);

// Eigenvalues and right eigenvectors A v_k = lambda_k v_k (dgeev, balanced),
// each v_k of unit 2-norm; column k of `vectors` belongs to values(k). For a
// defective A the vectors are numerically dependent (the caller checks).
struct EigenDecomposition {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;
};

// @throws InputError as RealSchur.
EigenDecomposition Eigendecompose(const Eigen::MatrixXd& a);

// X with T1 X + X T2^T = C, T1 (n1 x n1) and T2 (n2 x n2) in real Schur form,
// C n1 x n2 (dtrsyl). dtrsyl returns X scaled by a factor <= 1 chosen to
// avoid overflow; the scale is divided out, so an X too large for double has
// infinite entries, and a C with an entry that is not finite gives X = NaN.
// `near_singular` is set when T1 and -T2 have (nearly)
// common eigenvalues: LAPACK then perturbed them to get a solution, which is
// not a solution of the given equation and must not be used.
struct SylvesterSolution {
  Eigen::MatrixXd x;
  bool near_singular = false;
};

SylvesterSolution SolveQuasiTriangularSylvester(const Eigen::MatrixXd& t1,
                                                const Eigen::MatrixXd& t2,
                                                const Eigen::MatrixXd& c);

}  // namespace deb
