// Internal: not part of the public API.
// The block triangular form of a state matrix: the states permuted so that
// A(perm, perm) is block upper triangular with irreducible diagonal blocks,
// the strongly connected components of the graph "state j drives state i if
// A(i, j) != 0" (Tarjan, SIAM J. Comput. 1, 1972). A series connection, and
// so every transfer function of order 3 or more (a cascade of sections,
// transfer_function.h), has one block per stage.
//
// Why: the eigenvalues of A are those of its diagonal blocks, exactly, and
// each block's are as well conditioned as the stage's own. A dense
// eigenvalue solver on the whole of a non-normal cascade spreads rounding of
// size eps |A| across the stages: ten lightly damped modes 1 % apart
// (zeta 1e-3), one order-20 transfer function, got six poles with Re > 0
// (+0.13 to +0.37 rad/s at 64-67 rad/s) and the path was refused as
// unstable although every section's poles have Re = -0.065 rad/s.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace deb {

struct BlockTriangularForm {
  // A(perm, perm) is block upper triangular; block b covers rows and columns
  // [start[b], start[b + 1]) of it, start.back() = n.
  std::vector<int> perm, start;
  int blocks() const { return static_cast<int>(start.size()) - 1; }
};

// The finest block triangular form of a square matrix (exact: a
// permutation, decided by which entries are exactly zero).
BlockTriangularForm BlockTriangular(const Eigen::MatrixXd& a);

// True if A is reducible and some entry couples two of its blocks (a
// cascade: a stage drives the next); false for an irreducible A and for one
// whose blocks stand apart (a modal realisation, blockdiag of 2x2 blocks).
bool HasCoupledBlocks(const Eigen::MatrixXd& a);
// The same, for A's block triangular form already found.
bool HasCoupledBlocks(const Eigen::MatrixXd& a, const BlockTriangularForm& form);

// The eigenvalues of a square matrix, found block by block on its block
// triangular form (complex pairs as exact conjugates, real eigenvalues with
// Im = 0 exactly). @throws InputError (ThrowNotConverged) if an eigenvalue
// iteration does not converge.
Eigen::VectorXcd BlockEigenvalues(const Eigen::MatrixXd& a);

}  // namespace deb
