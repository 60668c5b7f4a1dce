#include "tests/support/thesis_layout.h"

namespace deb {

std::vector<Isolator> ThesisIsolators(const ThesisGeometry& g) {
  const double k_right = 15.38, k_left = 19.7;  // eq. 3-5: k_zR on P1, P4; k_zL on P2, P3
  const struct {
    const char* name;
    double x, y, kr;
  } points[] = {{"P1", g.d, g.w1, k_right},
                {"P2", g.d, -g.w2, k_left},
                {"P3", -g.d, -g.w2, k_left},
                {"P4", -g.d, g.w1, k_right}};
  std::vector<Isolator> isolators;
  for (const auto& p : points) {
    Isolator iso;
    iso.name = p.name;
    iso.position = Eigen::Vector3d(p.x, p.y, -g.h);
    iso.stiffness = Eigen::Vector3d(12.0, 12.0, p.kr);
    iso.damping = Eigen::Vector3d::Constant(0.1);
    isolators.push_back(iso);
  }
  return isolators;
}

std::vector<VelocitySensor> ThesisGeophones() {
  return {{"x1", "P1", BodyAxis::kX}, {"z1", "P1", BodyAxis::kZ}, {"y2", "P2", BodyAxis::kY},
          {"x3", "P3", BodyAxis::kX}, {"z3", "P3", BodyAxis::kZ}, {"y4", "P4", BodyAxis::kY},
          {"z4", "P4", BodyAxis::kZ}};
}

std::vector<ForceActuator> ThesisActuators() {
  return {{"x1", "P1", LocalAxis::kP}, {"z1", "P1", LocalAxis::kR},
          {"y2", "P2", LocalAxis::kQ}, {"z2", "P2", LocalAxis::kR},
          {"x3", "P3", LocalAxis::kP}, {"z3", "P3", LocalAxis::kR},
          {"y4", "P4", LocalAxis::kQ}, {"z4", "P4", LocalAxis::kR}};
}

Eigen::MatrixXd ThesisSensingMatrix() {
  Eigen::MatrixXd f(6, 7);
  //     x1    z1    y2    x3    z3    y4    z4
  f << 0.5,  0.0,  0.0,  0.5,  0.0,  0.0,  0.0,   // x_L
       0.0,  0.0,  0.5,  0.0,  0.0,  0.5,  0.0,   // y_L
       0.0,  0.5,  0.0,  0.0,  0.5,  0.0,  0.0,   // z_L
       0.0,  0.0,  0.0,  0.0, -0.5,  0.0,  0.5,   // alpha_L
       0.0, -0.5,  0.0,  0.0,  0.0,  0.0,  0.5,   // beta_L
      -0.5,  0.0,  0.0,  0.5,  0.0,  0.0,  0.0;   // gamma_L
  return f;
}

Eigen::MatrixXd ThesisMotorMatrix() {
  Eigen::MatrixXd m(8, 6);
  //     U_x   U_y   U_z   U_a    U_b    U_g
  m << 0.5,  0.0,  0.0,   0.0,   0.0, -0.5,   // x1
       0.0,  0.0,  0.25,  0.25, -0.25, 0.0,   // z1
       0.0,  0.5,  0.0,   0.0,   0.0,  0.0,   // y2
       0.0,  0.0,  0.25, -0.25, -0.25, 0.0,   // z2
       0.5,  0.0,  0.0,   0.0,   0.0,  0.5,   // x3
       0.0,  0.0,  0.25, -0.25,  0.25, 0.0,   // z3
       0.0,  0.5,  0.0,   0.0,   0.0,  0.0,   // y4
       0.0,  0.0,  0.25,  0.25,  0.25, 0.0;   // z4
  return m;
}

IsolationSystem ThesisCaseStudy(const ThesisGeometry& geometry) {
  IsolationSystem s;
  s.body.mass = 2.1;
  s.body.inertia = Eigen::Vector3d(4.8e5, 5.0e5, 6.4e5).asDiagonal();
  s.body.gravity = 9810.0;
  s.isolators = ThesisIsolators(geometry);
  s.sensors = ThesisGeophones();
  s.actuators = ThesisActuators();
  s.control.sensing = ThesisSensingMatrix();
  s.control.motor = ThesisMotorMatrix();
  s.control.gains = Vector6d::Constant(50.0);
  return s;
}

}  // namespace deb
