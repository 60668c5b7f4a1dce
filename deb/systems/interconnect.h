// Block-diagram algebra on state-space models: series, parallel, stacking and
// feedback. Closed loops such as the thesis' G_wz = (I + G M K_v F H)^-1 G G_d
// (eq. 3-43) are assembled here in state space, never by multiplying
// transfer-function polynomials. The state of every result is the
// concatenation of the operands' states (first operand first); no state is
// removed, so results need not be minimal.
#pragma once

#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

// u -> first -> second: H = H_second * H_first.
// @throws InputError if second.inputs() != first.outputs().
StateSpace Series(const StateSpace& first, const StateSpace& second);

// Same input to both, outputs summed: H = H_a + H_b.
// @throws InputError if inputs or outputs differ.
StateSpace Parallel(const StateSpace& a, const StateSpace& b);

// Independent side by side: inputs (u_a, u_b), outputs (y_a, y_b),
// H = blockdiag(H_a, H_b).
StateSpace Append(const StateSpace& a, const StateSpace& b);
// blockdiag(H_1, ..., H_k). @throws InputError if `systems` is empty.
StateSpace BlockDiagonal(const std::vector<StateSpace>& systems);

// Same input to both, outputs concatenated: H = [H_a; H_b].
// @throws InputError if inputs differ.
StateSpace StackOutputs(const StateSpace& a, const StateSpace& b);

// Closed loop with input u at the plant input and the plant output y fed back
// through the controller:
//   u_p = u + sign * K y,   y = G u_p,   so   H = (I - sign G K)^-1 G.
// sign = -1 is negative feedback, H = G / (1 + G K) in the SISO case. Outputs
// are the plant outputs y. General direct feedthrough in G and K is handled;
// the loop is well posed only if I - sign D_k D_p is invertible.
// @throws InputError if sign is not +1 or -1, if controller.inputs() !=
//         plant.outputs() or controller.outputs() != plant.inputs(), or if
//         the algebraic loop through D_p and D_k is singular.
StateSpace Feedback(const StateSpace& plant, const StateSpace& controller, int sign = -1);

}  // namespace deb
