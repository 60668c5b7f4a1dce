// The linear 6-DOF model of a rigid-body active vibration isolation system,
// assembled from its physical parameters (Nizamoglu 2015, ch. 3), and the
// paths a budget needs from it as state-space systems: floor velocity, sensor
// noise and actuator force to the CoG motion, open and closed loop.
//
// Coordinates q = (x, y, z, alpha, beta, gamma): CoG translation and small
// rotations about the body axes x, y, z. Equations of motion (eq. 3-14, 3-18)
//   M q'' + D q' + K q = B_a f + (floor terms),
// with, per isolator i (position r_i, R_0i = [r_i]x, R_phi_i of eq. 3-9),
//   K_xi = R_phi_i K_pi R_phi_i^T,  T_i = [I; R_0i],
//   K = sum T_i K_xi T_i^T + diag(0, 0, 0, sum F_i z_i, sum F_i z_i, 0)  (eq. 3-13),
//   D = sum T_i C_xi T_i^T (no gravity term).
// F_i is the static force in isolator i's vertical spring. The rotational term
// is eq. 3-13's diag(-m g h, -m g h, 0) generalised to isolators at different
// heights (z_i = -h_i): a vertical dead load F_i at r_i gives the moment
// change F_i z_i per unit rotation about x or y.
//
// Static pre-stress: the body settles on its vertical springs by a rigid
// displacement (w, a, b), so F_i = k_ri (w + a y_i + b x_i); the three follow
// from sum F_i = m g and no moment about the CoG (sum F_i x_i = sum F_i y_i = 0).
// For 3 supports this is the statics alone; for the thesis' 4 (k_r per eq. 3-4, 3-5) it is
// eq. 3-6. The small static tilt itself is not linearised about.
//
// Floor input (eq. 3-22..3-24): a rigid, non-rotating floor with velocity
// v_f = (x_f', y_f', z_f'); every isolator transmits (c s + k) times the floor
// displacement along its axes. Written with the floor displacement as the
// rigid-body translation E x_f, E = [I3; 0], the isolators act on q_r = q - E x_f
// only (the gravity terms act on rotations, which the floor does not have), so
//   M q'' + D (q' - E v_f) + K q_r = 0,   q_r' = q' - E v_f.
// The states are (q_r, q'): the floor velocity enters without differentiation
// or integration, A is the usual [0 I; -M^-1 K, -M^-1 D] with only the
// physical poles, and the transmissibility is (c s + k)/(m s^2 + c s + k) in
// the one-axis case (eq. 3-20). Position outputs are then q_r: the body's
// displacement relative to the floor; for the force and noise paths the floor
// is still, so they are absolute.
//
// Closed loop (eq. 3-43, 3-44): sensors read y = H q' + n (n: sensor noise),
// actuators apply f = -M K_v F y. Velocity from force is strictly proper, so
// the loop has no algebraic part: A_cl = A - [0; M^-1 B_a M K_v F H] [0 I].
#pragma once

#include <string>
#include <vector>

#include "deb/models/isolation_system.h"
#include "deb/systems/modes.h"
#include "deb/systems/state_space.h"

namespace deb {

// "x", "y", "z", "alpha", "beta", "gamma".
const std::vector<std::string>& CogDofNames();

// One open-loop mode from the undamped problem K phi = omega^2 M phi (as the
// thesis' natural frequencies).
struct IsolationMode {
  // omega / 2 pi; negative (-sqrt(-omega^2) / 2 pi) when K makes the mode
  // diverge (net negative stiffness).
  double f_hz = 0.0;
  // phi^T D phi / (2 omega) with phi^T M phi = 1: exact for proportional
  // damping, the usual estimate otherwise. NaN for a divergent or rigid mode.
  double damping_ratio = 0.0;
  // Kinetic-energy share of each DOF, phi_j (M phi)_j / phi^T M phi (sums to
  // 1; unit-free, unlike the shape, which mixes lengths and angles).
  Vector6d energy_share = Vector6d::Zero();
  int dominant_dof = 0;               // index into CogDofNames(): largest energy share
  Vector6d shape = Vector6d::Zero();  // phi scaled so that its dominant component is 1
};

struct IsolationModelSummary {
  std::vector<std::string> isolators;
  Eigen::VectorXd static_forces;                     // F_i, vertical spring pre-stress
  // Ascending in f. "Without gravity": the same system with g = 0; where
  // k_p, k_q are given as net values only the rotational term is dropped.
  std::vector<IsolationMode> modes;                  // gravity terms as modelled
  std::vector<IsolationMode> modes_without_gravity;
  bool has_control = false;
  // Poles of A_cl as modes (deb/systems/modes.h); empty without control.
  std::vector<Mode> closed_loop_modes;
  bool closed_loop_stable = false;

  // Plain-text tables: pre-stress per isolator, modes with and without
  // gravity terms (f, damping, dominant DOF, signed energy shares), closed-loop
  // modes.
  std::string Report() const;
};

class IsolationModel {
 public:
  enum class Loop { kOpen, kClosed };
  enum class Outputs {
    kVelocity,             // q' (6 outputs)
    kVelocityAndPosition,  // q', then q (floor path: q relative to the floor)
  };

  // Validates and assembles.
  // @throws InputError for any rule of IsolationSystem::Validate(); when F or M
  //   is to be derived and the sensors do not observe (or the actuators do not
  //   reach) all six DOF.
  explicit IsolationModel(IsolationSystem system);

  const IsolationSystem& system() const { return system_; }
  const Matrix6d& mass_matrix() const { return mass_; }
  const Matrix6d& damping_matrix() const { return damping_; }
  const Matrix6d& stiffness_matrix() const { return stiffness_; }
  // K of the same system with g = 0 (no pre-stress, no gravity terms).
  const Matrix6d& stiffness_without_gravity() const { return stiffness_no_gravity_; }
  // F_i per isolator (0 when g = 0).
  const Eigen::VectorXd& static_forces() const { return static_forces_; }
  // H: sensor signals from CoG velocities (sensors x 6), eq. 3-38..3-41.
  const Eigen::MatrixXd& sensor_kinematics() const { return sensor_kinematics_; }
  // B_a: CoG forces and moments from actuator forces (6 x actuators), eq. 3-18.
  const Eigen::MatrixXd& actuator_map() const { return actuator_map_; }
  // F and M in use, given or derived (empty without sensors / actuators).
  const Eigen::MatrixXd& sensing_matrix() const { return sensing_; }
  const Eigen::MatrixXd& motor_matrix() const { return motor_; }
  // True when there are sensors and actuators, so a closed loop exists.
  bool has_control() const { return sensing_.size() > 0 && motor_.size() > 0; }

  // Floor velocity (x_f', y_f', z_f') -> CoG motion: transmissibility
  // G G_d (eq. 3-25) open loop, G_wz (eq. 3-43) closed loop.
  // @throws InputError for a closed loop without control or not stable.
  StateSpace FloorToCog(Loop loop, Outputs outputs = Outputs::kVelocity) const;
  // Sensor noise, one input per sensor in velocity units -> CoG motion,
  // G_nz (eq. 3-44). @throws InputError without control or if not stable.
  StateSpace SensorNoiseToCog(Outputs outputs = Outputs::kVelocity) const;
  // Force added at each actuator -> CoG motion (open loop: G restricted to the
  // actuators, eq. 3-16; closed loop: with the skyhook feedback).
  // @throws InputError for a closed loop without control or not stable.
  StateSpace ActuatorToCog(Loop loop, Outputs outputs = Outputs::kVelocity) const;

  // Output names of the paths: "x_dot", ..., "gamma_dot", then "x", ..., "gamma".
  static std::vector<std::string> OutputNames(Outputs outputs);
  // Input names: "floor_x_dot", "floor_y_dot", "floor_z_dot"; sensors and
  // actuators go by their own names.
  static std::vector<std::string> FloorInputNames();

  IsolationModelSummary Summary() const;

 private:
  StateSpace Path(Loop loop, const Eigen::MatrixXd& b, Outputs outputs, const char* what) const;

  IsolationSystem system_;
  Matrix6d mass_, damping_, stiffness_, stiffness_no_gravity_;
  Eigen::VectorXd static_forces_;
  Eigen::MatrixXd sensor_kinematics_, actuator_map_, sensing_, motor_;
  Eigen::MatrixXd a_open_, a_closed_;
};

// Names for YAML and CLI.
inline constexpr EnumName<IsolationModel::Loop> kLoopNames[] = {{IsolationModel::Loop::kOpen, "open"},
                                                                 {IsolationModel::Loop::kClosed, "closed"}};
constexpr EnumNames<IsolationModel::Loop> NamesOf(IsolationModel::Loop) { return kLoopNames; }
inline constexpr EnumName<IsolationModel::Outputs> kOutputsNames[] = {
    {IsolationModel::Outputs::kVelocity, "velocity"},
    {IsolationModel::Outputs::kVelocityAndPosition, "velocity_and_position"}};
constexpr EnumNames<IsolationModel::Outputs> NamesOf(IsolationModel::Outputs) { return kOutputsNames; }
// @throws InputError listing the allowed values.
inline IsolationModel::Loop ParseLoop(const std::string& text) { return ParseEnum<IsolationModel::Loop>(text, "loop"); }
inline IsolationModel::Outputs ParseOutputs(const std::string& text) {
  return ParseEnum<IsolationModel::Outputs>(text, "outputs");
}

}  // namespace deb
