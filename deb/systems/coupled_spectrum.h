// Internal: not part of the public API.
// Poles and exact variance of a coupled realisation (coupled_realisation.h),
//   A = blockdiag(A_1, ..., A_k) + U V^T,  rank r,
// without reducing a dense A (O(n^3): 4.6 s for a PID loop around 1000
// modes). In the basis that diagonalises the blocks, A = D + U V^T with D
// diagonal, and
//   det(z - A) = prod_k (z - d_k) det M(z),   M(z) = I_r - V^T (z - D)^-1 U,
// so the poles are the roots of a polynomial whose logarithmic derivative
//   p'/p(z) = sum_k 1 / (z - d_k) + tr(M(z)^-1 V^T (z - D)^-2 U)
// costs O(n r^2); they are found together by the Aberth-Ehrlich iteration
// (Aberth, Math. Comp. 27, 1973; Bini, Numer. Algorithms 13, 1996), started
// at the blocks' own poles, which a weak coupling moves little. Each pole's
// eigenvectors follow from the r x r M at the pole: v = (mu - D)^-1 U y with
// M(mu) y = 0, w^T = x^T V^T (mu - D)^-1 with x^T M(mu) = 0, scaled to
// w^T v = 1. The exact variance is then the closed form on them,
//   C P C^T = C~ (G o (B~ W B~^H)) C~^H,  G_ij = -1 / (mu_i + conj mu_j),
// C~ = C V, B~ = W^T B, O(n^2 (m + p)).
//
// A mode the loop does not drive (its row of U is zero, after rows at the
// level of rounding in A are made so) or does not see (V) keeps its block's
// pole exactly; it stays out of the iteration, and its eigenvectors come
// from one r x r solve at that pole.
//
// Accuracy is not assumed. The poles are checked against two invariants of
// A (sum mu = tr A, sum mu^2 = tr A^2). The covariance carries an estimate
// of its own error, from the computed eigenvectors' residuals: A v - mu v =
// U (-M(mu) y) lies in U's range, and so do the left ones in V's, so the
// Lyapunov residual of the computed P and its first-order correction
// L^-1(-R), seen through C, cost O(n^2 (m + p + r)) as well. Two terms are
// added for what that first-order correction does not see:
//   - rounding: 4 eps times the sum of the closed form's terms' absolute
//     values (each term's relative error, without the cancellation between
//     terms; not the growth with the sums' lengths, which rounding to
//     nearest keeps statistical: with it the estimate was 1e-6 on a loop
//     around 2000 modes whose variances agree with numpy's eigenvector form
//     to 1e-13);
//   - the eigenvectors' own accuracy where poles nearly coincide, 16 eps
//     times the largest eigenvalue condition (a loop around a mode repeated
//     exactly: 6.1e-11 off a 40-digit reference, where the other terms
//     estimated 3.8e-11).
// A result whose estimate exceeds the stated tolerance is refused, and the
// caller solves the dense realisation instead (a loop kept as parts, path.h,
// has none).
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "deb/systems/coupled_realisation.h"

namespace deb {

// Largest condition number of a block's eigenvector matrix: beyond it the
// block (a rigid-body mode's double integrator, a Jordan-like cluster of a
// part) is not diagonalisable well; its diagonal is then kept and the rest
// of it joins the coupling (a double integrator adds 1 to the rank).
inline constexpr double kMaxCoupledBlockCondition = 1e8;
// Largest Aberth-Ehrlich sweeps before the coupled form gives up.
inline constexpr int kMaxAberthSweeps = 200;
// Largest estimated relative error of a variance from the coupled form: the
// bound lyapunov.h holds every exact variance to.
inline constexpr double kCoupledVarianceTolerance = 1e-6;

struct CoupledSpectrum {
  Eigen::VectorXcd poles;
  int blocks = 0, rank = 0;  // of the realisation solved
  int sweeps = 0;
  // Largest eigenvalue condition number |v| |w| / |w^T v| over the poles.
  double eigenvalue_condition = 1.0;

  // With the right eigenvectors v_i (columns of V) and left ones w_i^T
  // (rows of W^T, w_i^T v_i = 1) in the basis X that diagonalises the
  // blocks (n states, N = n poles), which are not kept (O(n^2) memory):
  Eigen::MatrixXcd c_tilde;     // C X V (p x N)
  Eigen::MatrixXd abs_c_tilde;  // |C X| |V| (p x N), for the rounding
  Eigen::MatrixXcd b_tilde;     // W^T X^-1 B (N x m)
  Eigen::MatrixXd abs_b_tilde;  // |W^T| |X^-1 B| (N x m)
  Eigen::MatrixXcd wu;          // W^T X^-1 U (N x r)
  Eigen::MatrixXd d;            // D (p x m)
  // Per pole (r x N): y_i, x_i (scaled with w_i), rho_i = -M(mu_i) y_i,
  // sigma_i = -M(mu_i)^H x_i: the eigenvectors' residuals.
  Eigen::MatrixXcd y, x, rho, sigma;
};

struct CoupledSolve {
  std::optional<CoupledSpectrum> spectrum;
  std::string why_not;  // when spectrum is empty: why, for `deb check`
};

// threads <= 0: the default count.
CoupledSolve SolveCoupled(const CoupledRealisation& sys, int threads = 0);

struct CoupledCovariance {
  Eigen::MatrixXd covariance;     // rows x rows
  Eigen::VectorXd relative_error; // estimated, per row's variance
};
// C_rows P C_rows^T under white input noise of two-sided intensity W (inputs
// x inputs). The caller checks the poles' stability and D W D^T = 0 first.
CoupledCovariance CoupledOutputCovariance(const CoupledSpectrum& spectrum, const std::vector<int>& rows,
                                          const Eigen::MatrixXd& w_two_sided);

}  // namespace deb
