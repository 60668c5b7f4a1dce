// Pole-zero cancellation on the imaginary axis. A controller's integrator in
// series with a closed loop whose sensitivity is 0 at DC (the noise path
// -C P S, written as `series [minus, pid, force_to_position]`), or any other
// composition where a pole on the axis meets a zero at the same place,
// leaves a state space with poles on the axis that the inputs never carry to
// the outputs: the transfer is stable, but the realisation is not, so it
// would get no exact variance and a warning that its variance depends on the
// grid's ends. Removing those modes gives a stable realisation of the same
// transfer.
//
// Method: the real Schur form of the balanced A, reordered with the strictly
// stable poles first (ClassifyPoles' rule), T = [T11 T12; 0 T22]; the
// Sylvester equation T11 X - X T22 = -T12 decouples the blocks, so that
//   H(s) = C1 (sI - T11)^-1 B1s + Cm (sI - T22)^-1 B2 + D,
// B1s = B1 - X B2, Cm = C1 X + C2 (the additive split of H by pole location,
// which is unique). The axis part is zero, and is dropped, when each entry
// of each of its Markov parameters Cm T22^k B2 (k < its order) is within
// kCancellationTolerance of the terms it sums, the same entry of
// (|C| |U1| |X| + |C| |U2|) |T22|^k |U2|^T |B| (entrywise absolute values,
// U = [U1 U2] the Schur vectors): what rounding makes of a true zero,
// whatever the scaling of the states.
// All of the axis poles or none: a transfer with one left still has no
// finite variance.
#pragma once

#include <Eigen/Dense>
#include <optional>

#include "deb/systems/state_space.h"

namespace deb {

// Relative size, against the terms they sum, below which the axis part's
// Markov parameters count as zero. A true cancellation measures about 1e-15
// (rounding); a coupling that small against its own terms would be below
// the precision of the model itself.
inline constexpr double kCancellationTolerance = 1e-9;
// The decoupling X beyond which nothing is removed: the split would lose
// more than the tolerance to rounding (stable poles too close to the axis).
inline constexpr double kMaxDecoupling = 1e6;

struct AxisCancellation {
  StateSpace system;           // the same transfer without the axis poles
  Eigen::VectorXcd cancelled;  // the poles removed [rad/s]
  double residual = 0.0;       // the largest relative Markov parameter entry measured
};

// The realisation without its poles on the imaginary axis, if sys has some,
// none unstable, and all of them cancel as above; otherwise nullopt.
std::optional<AxisCancellation> CancelAxisPoles(const StateSpace& sys);

}  // namespace deb
