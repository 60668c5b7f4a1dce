// Physical parameters of a rigid-body active vibration isolation system
// (Nizamoglu 2015, ch. 3): a rigid body on any number of isolators (parallel
// springs and dampers along local axes p, q, r), absolute-velocity sensors
// (geophones) and force actuators at the isolators, and a skyhook controller
// acting on six "logical axes". Plain structs with defaults, so a YAML loader
// can fill them field by field; Validate() names the offending field.
//
// Units: any consistent set. The thesis uses tonne, mm, s, N; then stiffness is
// in N/mm, damping in N/(mm/s), inertia in t*mm^2, gravity in mm/s^2 and the
// skyhook gains in N/(mm/s) per logical axis. Nothing in the model assumes a
// particular set; results come out in the same units (velocities in mm/s etc.).
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"

namespace deb {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct RigidBody {
  double mass = 0.0;                                  // m
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // J about the CoG, body axes
  // Gravity acceleration along -z. 0 switches all gravity effects off (static
  // pre-stress, inverted-pendulum and rotational terms, eq. 3-7, 3-13).
  double gravity = 0.0;

  // @throws InputError "body.mass: ..." etc. when m <= 0, J is not symmetric
  //         positive definite, or g < 0 / not finite.
  void Validate() const;
};

// One isolator: three orthogonal springs and dampers along its local axes
// p, q, r; r is vertical (parallel to z), p and q are x and y rotated by
// rotation_rad about the vertical (R_phi of eq. 3-9).
struct Isolator {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // r_i from the CoG; z = -h below it
  Eigen::Vector3d stiffness = Eigen::Vector3d::Zero();  // k_p, k_q, k_r
  Eigen::Vector3d damping = Eigen::Vector3d::Zero();    // c_p, c_q, c_r
  double rotation_rad = 0.0;                            // phi_i
  // Loaded length L of the vertical spring. Unset: k_p and k_q are net values,
  // the inverted pendulum's negative stiffness already included (the thesis'
  // case study). Set: -F_i / L is added to k_p and k_q (eq. 3-7), F_i the
  // static pre-stress of this isolator's vertical spring.
  std::optional<double> spring_length;
};

// Body axes (sensor directions) and isolator-local axes (actuator directions).
enum class BodyAxis { kX, kY, kZ };
enum class LocalAxis { kP, kQ, kR };
inline constexpr EnumName<BodyAxis> kBodyAxisNames[] = {{BodyAxis::kX, "x"}, {BodyAxis::kY, "y"}, {BodyAxis::kZ, "z"}};
constexpr EnumNames<BodyAxis> NamesOf(BodyAxis) { return kBodyAxisNames; }
inline constexpr EnumName<LocalAxis> kLocalAxisNames[] = {
    {LocalAxis::kP, "p"}, {LocalAxis::kQ, "q"}, {LocalAxis::kR, "r"}};
constexpr EnumNames<LocalAxis> NamesOf(LocalAxis) { return kLocalAxisNames; }
// @throws InputError listing the allowed values.
inline BodyAxis ParseBodyAxis(const std::string& text) { return ParseEnum<BodyAxis>(text, "body axis"); }
inline LocalAxis ParseLocalAxis(const std::string& text) { return ParseEnum<LocalAxis>(text, "isolator axis"); }

// A geophone on an isolator's point of action: measures the absolute velocity
// of that point along a body axis, v_P = v_CoG + omega x r_i (eq. 3-38..3-41).
// Its own dynamics are ignored (unit gain, as in the thesis, sec. 3-4-2).
struct VelocitySensor {
  std::string name;
  std::string isolator;  // Isolator::name
  BodyAxis axis = BodyAxis::kZ;
};

// A force actuator at an isolator's point of action, along one of its local
// axes (so rotated with the isolator), unit gain from command to force.
struct ForceActuator {
  std::string name;
  std::string isolator;  // Isolator::name
  LocalAxis axis = LocalAxis::kR;
};

// Skyhook control in logical axes (eq. 3-32..3-37): the actuator forces are
//   f = -M K_v F y,  y = sensor signals (velocities), K_v = diag(gains).
struct SkyhookControl {
  // F: six logical-axis velocities from the sensor signals (6 x sensors).
  // Empty: F = H^+ (pseudo-inverse of the sensor kinematics, which needs the
  // sensors to observe all six DOF); the logical axes are then the CoG DOF
  // x, y, z, alpha, beta, gamma themselves.
  Eigen::MatrixXd sensing;
  // M: actuator forces from logical-axis forces (actuators x 6). Empty:
  // M = B_a^+ (pseudo-inverse of the map from actuator forces to CoG forces
  // and moments); logical forces are then CoG forces and moments.
  Eigen::MatrixXd motor;
  // Diagonal of K_v, one gain per logical axis. With derived F and M the last
  // three are rotational gains (moment per angular velocity).
  Vector6d gains = Vector6d::Zero();
};

struct IsolationSystem {
  RigidBody body;
  std::vector<Isolator> isolators;
  std::vector<VelocitySensor> sensors;
  std::vector<ForceActuator> actuators;
  SkyhookControl control;

  // Checks every field and cross-reference; messages start with the field's
  // path, e.g. "isolators[2].position: ...".
  // @throws InputError for: body rules (RigidBody::Validate); fewer than 3
  //   isolators, or supports all on one line seen from above; empty or
  //   duplicate names; k_r <= 0, negative damping, L <= 0, non-finite values;
  //   a sensor or actuator naming an unknown isolator; F or M of the wrong size.
  void Validate() const;

  // Index of the isolator with this name, or -1.
  int IsolatorIndex(const std::string& name) const;
};

}  // namespace deb
