// A structure described by its modes, as a finite-element analysis gives
// them: per mode k a natural frequency f_k, a damping ratio zeta_k and the
// mass-normalised mode shape (Phi^T M Phi = I) at the input and output DOFs.
// Each modal coordinate obeys
//   q_k'' + 2 zeta_k w_k q_k' + w_k^2 q_k = sum_i phi_in(i,k) f_i,   w_k = 2 pi f_k,
// and the outputs are y = Phi_out q (displacement), Phi_out q' (velocity) or
// Phi_out q'' (acceleration), so that
//   H(s) = s^n sum_k phi_out(:,k) phi_in(:,k)^T / (s^2 + 2 zeta_k w_k s + w_k^2),  n = 0, 1, 2.
// With forces in N and shapes in 1/sqrt(kg), phi_out phi_in / w^2 is in m/N.
// A rigid-body mode (f = 0) is a double integrator: allowed, but the path
// then has poles at the origin (no exact variance; the grid must start > 0).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/systems/state_space.h"

namespace deb {

enum class ModalQuantity { kDisplacement, kVelocity, kAcceleration };

inline constexpr EnumName<ModalQuantity> kModalQuantityNames[] = {{ModalQuantity::kDisplacement, "displacement"},
                                                                  {ModalQuantity::kVelocity, "velocity"},
                                                                  {ModalQuantity::kAcceleration, "acceleration"}};
constexpr EnumNames<ModalQuantity> NamesOf(ModalQuantity) { return kModalQuantityNames; }
// @throws InputError naming the allowed words.
inline ModalQuantity ParseModalQuantity(const std::string& word) {
  return ParseEnum<ModalQuantity>(word, "output quantity");
}
// Time derivatives of the displacement: 0, 1, 2.
int DerivativeOrder(ModalQuantity q);

// The rules on one mode's numbers; "" when they hold, else what is wrong
// (for located messages by the readers, and for ModalModel::Validate):
//   f_hz finite and >= 0;
//   zeta finite, and 0 < zeta < 1 for f_hz > 0 (zeta = 0 would make the
//   exact variance infinite; zeta >= 1 is no oscillating mode); a rigid mode
//   (f_hz = 0) ignores zeta, which must still be finite and in [0, 1).
std::string ModeFrequencyProblem(double f_hz);
// The pole of a mode with Im >= 0: -zeta w + j w sqrt(1 - zeta^2), w = 2 pi f_hz [rad/s].
std::complex<double> ModalPole(double f_hz, double zeta);
std::string ModeDampingProblem(double f_hz, double zeta);

struct ModalModel {
  std::vector<double> f_hz;   // one per mode [Hz]
  std::vector<double> zeta;   // one per mode, damping ratio [-]
  Eigen::MatrixXd phi_in;     // inputs x modes: mode shape at each input DOF
  Eigen::MatrixXd phi_out;    // outputs x modes: mode shape at each output DOF
  std::vector<std::string> input_names, output_names;  // the DOFs, one per row
  ModalQuantity quantity = ModalQuantity::kDisplacement;
  // A feedthrough added to H (outputs x inputs, empty for none): the static
  // compliance of modes left out by Truncated(max_hz, true), so that the
  // truncated model keeps the full model's static response (displacement
  // outputs only).
  Eigen::MatrixXd residual;
  // What was done to the modes on loading them (normalised, modes dropped,
  // rigid-body modes kept or left out, units converted), one sentence each,
  // for `deb check`.
  std::vector<std::string> notes;

  int modes() const { return static_cast<int>(f_hz.size()); }

  // @throws InputError (not located: the caller knows where the data came
  //   from) if there are no modes or more than limits::kMaxModes, sizes
  //   disagree, a mode breaks ModeFrequencyProblem/ModeDampingProblem, a
  //   shape value is not finite, there are no (or more than
  //   limits::kMaxChannels) inputs or outputs, or a DOF name is empty or
  //   repeated.
  void Validate() const;

  // The modes with f_hz <= max_hz, in order (the shapes' columns with them).
  // With static_residual, the dropped modes' static compliance
  //   sum over dropped k of phi_out(:,k) phi_in(:,k)^T / w_k^2
  // is added to `residual` (the mode-displacement method's static
  // correction: exact at 0 Hz, and within (f / f_k)^2 of each dropped mode's
  // response well below it).
  // @throws InputError if static_residual is asked for a velocity or
  //   acceleration output (the correction would not be a constant).
  ModalModel Truncated(double max_hz, bool static_residual = false) const;
  // The first `count` modes (all if count >= modes()), in order, with the
  // same static correction of the dropped ones as Truncated.
  // @throws InputError as Truncated.
  ModalModel FirstModes(int count, bool static_residual = false) const;

 private:
  // The modes keep[k] says yes to.
  ModalModel Kept(const std::vector<bool>& keep, bool static_residual) const;
};

// The realisation with 2 n states x = [q_1, q_1', q_2, q_2', ...]:
//   A = blockdiag([[0, 1], [-w_k^2, -2 zeta_k w_k]]),  B rows (2k, 2k+1) = [0; phi_in(:,k)^T],
//   displacement: C(:,2k) = phi_out(:,k),                 D = 0
//   velocity:     C(:,2k+1) = phi_out(:,k),               D = 0
//   acceleration: C(:,2k) = -w_k^2 phi_out(:,k), C(:,2k+1) = -2 zeta_k w_k phi_out(:,k),
//                 D = Phi_out Phi_in^T   (q'' = -w^2 q - 2 zeta w q' + Phi_in^T f).
// Calls Validate().
StateSpace ModalStateSpace(const ModalModel& model);

// The same realisation without its 2n x 2n A (4 n^2 zeros): mode k's 2 x 2
// block [[0, 1], [-w_k^2, -2 zeta_k w_k]] and B, C, D as above, for the
// coupled form of models too large for a dense A (coupled_realisation.h).
// Calls Validate().
struct ModalRealisationParts {
  std::vector<Eigen::Matrix2d> blocks;
  Eigen::MatrixXd b, c, d;
};
ModalRealisationParts ModalRealisation(const ModalModel& model);

}  // namespace deb
