// Internal: not part of the public API.
// The block-diagonal real Schur form of a dense state matrix:
//   A = S D S^-1,  S = U Y,
// U orthogonal (the real Schur form A = U T U^T, LAPACK dgees), Y unit upper
// triangular, D block diagonal: each diagonal block of D is a group of T's
// 1x1 (real pole) and standardised 2x2 (pole pair) blocks that could not be
// decoupled from the blocks above it without a large Y.
//
// Why: a finite-element model handed over in physical coordinates, or any
// closed loop around one, is a dense A whose poles are a modal model's. Its
// eigenvector matrix can be ill conditioned without any pole being close to
// another (a lightly damped pair [0 1; -w^2 -2 zeta w] in x = [q, q'] has two
// nearly parallel eigenvectors, condition ~ w), so the modal form loses
// digits. The block-diagonal form keeps each pair in its real 2x2 block and
// inverts only the couplings between blocks, which are small where poles are
// apart: per frequency it costs what the modal form costs, and the error of
// H computed on it is at most cond(Y) times that of a backward-stable solve
// on A (frequency_response.h).
//
// Algorithm (after Bavely & Stewart, SIAM J. Numer. Anal. 16, 1979): the
// blocks of T whose poles are within `cluster_gap` of each other (relative)
// are first made adjacent (dtrexc swaps); then, from the top, block group J
// of rows [s, e) is decoupled from everything above it by the column block
//   Y(0:s, s:e) = X,  T(0:s, 0:s) X - X T(s:e, s:e) = -T(0:s, s:e)
// (dtrsyl). If max |X| exceeds `max_coupling` the group is merged with the
// group above it and solved again: the merged group keeps its own
// upper-triangular coupling, evaluated exactly by its callers.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <vector>

namespace deb {

struct RealBlockDiagonalForm {
  Eigen::MatrixXd t;  // real Schur form; only its diagonal blocks (groups) are D
  Eigen::MatrixXd u;  // orthogonal: A = U T U^T
  Eigen::MatrixXd y;  // unit upper triangular; T = Y D Y^-1
  // Group g covers rows and columns [start[g], start[g + 1]) of T; start.back() = n.
  std::vector<int> start;
  Eigen::VectorXcd eigenvalues;  // in the order of T's diagonal
  double condition = 1.0;        // estimated 1-norm condition number of Y (and so of S)
  int swaps_failed = 0;          // clusters left apart because dtrexc could not swap

  int groups() const { return static_cast<int>(start.size()) - 1; }
  int group_size(int g) const { return start[g + 1] - start[g]; }
  int largest_group() const;
  // C S = (C U) Y (outputs x n) and S^-1 B = Y^-1 (U^T B) (n x inputs).
  Eigen::MatrixXd Left(const Eigen::MatrixXd& c) const;
  Eigen::MatrixXd Right(const Eigen::MatrixXd& b) const;
};

inline constexpr double kDefaultMaxCoupling = 1e3;
inline constexpr double kDefaultClusterGap = 1e-3;

// @throws InputError if A is not square or not finite, or the QR iteration
//         does not converge (lapack.h).
RealBlockDiagonalForm RealBlockDiagonal(const Eigen::MatrixXd& a, double max_coupling = kDefaultMaxCoupling,
                                        double cluster_gap = kDefaultClusterGap);

// RealBlockDiagonal(a) with the default bounds, shared: the forms of the
// last two matrices of at least kSharedFormStates states reduced are kept,
// so that a path's frequency response and its exact variance, which reduce
// the same balanced A, pay the O(n^3) reduction once (1000 modes: 8 s).
// Thread-safe; a matrix equal entry for entry to a kept one gets its form.
inline constexpr int kSharedFormStates = 200;
std::shared_ptr<const RealBlockDiagonalForm> SharedRealBlockDiagonal(const Eigen::MatrixXd& a);

}  // namespace deb
