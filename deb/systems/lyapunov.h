// Exact variances of linear systems driven by white noise. For a stable path
//   x' = A x + B w,  y = C x,  w white with two-sided intensity W
// (E[w(t) w(t')^T] = W delta(t - t'), i.e. W = S0 / 2 for a one-sided PSD S0),
// the stationary state covariance P solves the Lyapunov equation
//   A P + P A^T + B W B^T = 0,
// and the output covariance is C P C^T (METHOD.md, convention 3). This is the
// independent check of every grid-integrated budget: no frequency grid, no
// truncation at f_max, no missed resonance. Eigen has no Lyapunov solver in its
// supported modules, so it is solved here (Bartels & Stewart, Comm. ACM 15,
// 1972, on the complex Schur form).
#pragma once

#include <Eigen/Dense>

#include "deb/systems/state_space.h"

namespace deb {

// P with A P + P A^T + Q = 0, for square A and Q of the same size. P is
// symmetric when Q is. The solution is unique iff no two eigenvalues of A sum
// to zero; A need not be stable (P is then not a covariance).
// @throws InputError if sizes differ, an entry is not finite, or
//         lambda_i + lambda_j ~ 0 for some pair of eigenvalues (singular
//         equation; names the pair).
Eigen::MatrixXd SolveLyapunov(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q);

// C P C^T with A P + P A^T + B W B^T = 0: the output covariance of `sys`
// under white input noise of two-sided intensity `w_two_sided` (inputs x
// inputs, symmetric, non-negative diagonal). Its diagonal holds the output
// variances. A path without states gives a zero matrix (when D W D^T = 0).
// @throws InputError if W has the wrong size or is not symmetric, if A has a
//         pole with Re >= 0 (the message lists them), or if an output has
//         direct feedthrough of noise (D W D^T != 0: infinite variance).
Eigen::MatrixXd OutputCovariance(const StateSpace& sys, const Eigen::MatrixXd& w_two_sided);

}  // namespace deb
