// Internal: not part of the public API.
// Block-diagonal Schur form A = S T S^-1: T block diagonal with upper
// triangular blocks, each block a cluster of eigenvalues that cannot be
// separated from the others without an ill-conditioned S. It sits between the
// eigendecomposition (all blocks 1x1, but S = V may be arbitrarily ill
// conditioned for defective or nearly repeated poles) and the Schur form (S
// unitary, one n x n block): frequency responses evaluated on it cost about as
// much as modal ones, yet stay accurate for double poles, Jordan chains and
// close modes.
//
// Algorithm (Bavely & Stewart, SIAM J. Numer. Anal. 16, 1979): complex Schur
// form A = U T U^H; then, from the top, a block T11 is split from the rest T22
// by solving the Sylvester equation T11 X - X T22 = -T12 and applying
// [I X; 0 I]. If X exceeds `max_coupling`, the eigenvalue of T22 nearest to
// the block is moved next to it (unitary swaps of adjacent diagonal entries)
// and the block grows by one; the split is tried again.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace deb {

struct BlockSchurForm {
  Eigen::MatrixXcd t;      // block diagonal, blocks upper triangular
  Eigen::MatrixXcd s;      // A = s t s_inv
  Eigen::MatrixXcd s_inv;
  // Block i covers rows and columns [block_start[i], block_start[i+1]);
  // block_start.back() = n.
  std::vector<int> block_start;

  int blocks() const { return static_cast<int>(block_start.size()) - 1; }
  int block_size(int i) const { return block_start[i + 1] - block_start[i]; }
  int largest_block() const;
  // |s|_1 |s_inv|_1: the growth of rounding errors caused by the splits.
  double condition() const;
};

// Block-diagonal Schur form of a square matrix. max_coupling bounds the
// largest entry of each splitting X (S's condition grows like its square per
// split), so it trades block size against accuracy.
// @throws InputError if the Schur form's QR iteration does not converge (a
//         matrix with entries spanning hundreds of decades).
BlockSchurForm BlockDiagonalSchur(const Eigen::MatrixXd& a, double max_coupling = 1e3);

}  // namespace deb
