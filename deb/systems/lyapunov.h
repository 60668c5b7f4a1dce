// Exact variances of linear systems driven by white noise. For a stable path
//   x' = A x + B w,  y = C x,  w white with two-sided intensity W
// (E[w(t) w(t')^T] = W delta(t - t'), i.e. W = S0 / 2 for a one-sided PSD S0),
// the stationary state covariance P solves the Lyapunov equation
//   A P + P A^T + B W B^T = 0,
// and the output covariance is C P C^T (docs/method.md, convention 3). This is the
// independent check of every grid-integrated budget: no frequency grid, no
// truncation at f_max, no missed resonance. It is solved by the real-Schur
// Bartels-Stewart method (Bartels & Stewart, Comm. ACM 15, 1972): LAPACK's
// real Schur form (dgees) and quasi-triangular Sylvester solver (dtrsyl),
// real arithmetic throughout (deb/systems/lapack.h).
//
// Accuracy: Bartels-Stewart is backward stable only normwise, so its forward
// error is about eps times the condition number of the Lyapunov operator in
// the coordinates it is given, and that depends strongly on the state scaling.
// A cascade of lightly damped resonators (series realisation, or a companion
// form of the expanded polynomial) has state variances spanning ~16 decades and
// a condition number ~1e17: the variance came out 1-30 % wrong, or negative.
// The solver therefore (1) permutes A to block triangular form (strongly
// connected components; one block per stage of a cascade) and solves block by
// block, so the structural zeros of A are never perturbed, and (2) rescales
// the states (exact powers of two) until diag(P) is ~1 and solves again,
// keeping the solution whose estimated error is smallest.
//
// An irreducible A (a dense model in physical coordinates, a closed loop
// around one) is first tried on its block-diagonal form A = S D S^-1
// (real_block_diagonal.h): with D's 1x1 and 2x2 blocks the equation splits
// into one Sylvester equation of at most 4 unknowns per pair of blocks,
// O(n^2 (m + p)) after the O(n^3) reduction instead of the whole Schur solve
// (1000 states: 1.7 s against 9.4 s, bench/bench_dense --fe). It is used where
// cond(Y) <= 100 and its error estimate (the reduction's own residual carried
// through the same block solves, times ten) is below 1e-6; else the solve
// above decides.
#pragma once

#include <Eigen/Dense>

#include "deb/systems/state_space.h"

namespace deb {

// P with A P + P A^T + Q = 0, for square A and Q of the same size. P is
// symmetric when Q is. The solution is unique iff no two eigenvalues of A sum
// to zero; A need not be stable (P is then not a covariance). For symmetric Q
// the states are first balanced (Parlett-Reinsch on A), permuted to block
// triangular form (exact, a permutation), then rescaled by
// 2^round(log2 sqrt(P_ii)) and the equation solved again (up to 3 times) so
// that diag(P) is equilibrated; the pass whose estimated error of diag(P)
// is smallest is kept (a rescaling can make a stiff block non-normal);
// non-symmetric Q gets the balancing only.
// @throws InputError if sizes differ, an entry is not finite,
//         |lambda_i + conj(lambda_j)| <= 1e3 eps |A| for some pair of
//         eigenvalues (singular equation; names the pair), or the residual
//         of the computed P is not small (the solution is not reliable).
Eigen::MatrixXd SolveLyapunov(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q);

// C P C^T with A P + P A^T + B W B^T = 0: the output covariance of `sys`
// under white input noise of two-sided intensity `w_two_sided` (inputs x
// inputs, symmetric, non-negative diagonal). Its diagonal holds the output
// variances. A path without states gives a zero matrix (when D W D^T = 0).
// A negative or non-finite variance is never returned: the result is checked
// against the Lyapunov residual, and its error is estimated by solving the
// equation once more for the residual (L^-1 R); an output variance whose
// estimated relative error exceeds 1e-6 is refused.
// @throws InputError if W has the wrong size or is not symmetric, if A has a
//         pole with Re >= 0 (the message lists them), if an output has
//         direct feedthrough of noise (D W D^T != 0: infinite variance), or
//         "exact variance is not reliable for this realisation: ..." if a
//         computed variance is negative or not finite, the residual check
//         fails, or the error estimate exceeds 1e-6 relative.
Eigen::MatrixXd OutputCovariance(const StateSpace& sys, const Eigen::MatrixXd& w_two_sided);

}  // namespace deb
