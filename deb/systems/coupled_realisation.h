// Internal: not part of the public API.
// A realisation kept as small diagonal blocks joined by a low-rank coupling:
//   x' = A x + B u,  y = C x + D u,  A = blockdiag(A_1, ..., A_k) + U V^T,
// U and V (states x r) of a rank r far below the states. It is the shape of
// every loop closed around a modal plant: the plant's 2x2 mode blocks and the
// controller's few states, coupled only through the loop's few actuated and
// sensed channels. A dense realisation of the same loop has lost that shape
// (its plant block is modal + rank r, dense), and reducing it costs O(n^3);
// kept, it gives the poles and the exact variance in O(n^2 r)
// (coupled_spectrum.h).
//
// The blocks are built from the diagram's parts, in the order of the dense
// realisation's states (interconnect.h: first operand first), so that the
// two describe the same system:
//   series    A = [A1 0; B2 C1 A2]:  coupling [0; B2] [C1 0]
//   parallel  A = blockdiag(A1, A2): no coupling
//   feedback  u_p = F (u + s D_k C_g x_g + s C_k x_k),  F = (I - s D_k D_g)^-1,
//             A = blockdiag(A_g, A_k) + [B_g; B_k D_g] F [s D_k C_g, s C_k] + [0; B_k] [C_g, 0]
// and each coupling is recompressed to its numerical rank (a thin QR of U
// and V, then the SVD of the small core: singular values at or below
// 8 eps times the largest block or coupling norm are dropped).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "deb/systems/modal_model.h"
#include "deb/systems/state_space.h"

namespace deb {

struct CoupledRealisation {
  std::vector<Eigen::MatrixXd> blocks;  // square, in state order
  Eigen::MatrixXd u, v;                 // states x rank
  Eigen::MatrixXd b, c, d;

  int states() const { return static_cast<int>(b.rows()); }
  int inputs() const { return static_cast<int>(b.cols()); }
  int outputs() const { return static_cast<int>(c.rows()); }
  int rank() const { return static_cast<int>(u.cols()); }
  int largest_block() const;
  // The dense A (for tests and references).
  Eigen::MatrixXd DenseA() const;
};

// States of one block of a rational part kept as it is; a larger part is not
// split (the caller reduces the dense realisation instead).
inline constexpr int kMaxCoupledBlock = 32;

// One block of a rational system (none if it has no states); nullopt-free:
// the caller checks states() <= kMaxCoupledBlock first.
CoupledRealisation CoupledOf(const StateSpace& rational);
// 2x2 blocks, one per mode, in the states x = [w q, q'] (w = 2 pi f; [q, q']
// for a rigid mode): the modal realisation of modal_model.h scaled so that
// each block [0 w; -w -2 zeta w] is balanced. Calls Validate().
CoupledRealisation CoupledOf(const ModalModel& modal);

CoupledRealisation CoupledSeries(const CoupledRealisation& first, const CoupledRealisation& second);
CoupledRealisation CoupledParallel(const CoupledRealisation& a, const CoupledRealisation& b);
// @throws InputError if the algebraic loop I - sign D_k D_g is singular.
CoupledRealisation CoupledFeedback(const CoupledRealisation& plant, const CoupledRealisation& controller, int sign);
CoupledRealisation CoupledSelectOutputs(const CoupledRealisation& sys, const std::vector<int>& rows);

}  // namespace deb
