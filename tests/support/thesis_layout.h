// The isolation layout of Nizamoglu 2015 (fig. 3-3, 3-11; Table 5-3): four
// isolators P1..P4 below the CoG, seven geophones x1 z1 y2 x3 z3 y4 z4, eight
// actuators x1 z1 y2 z2 x3 z3 y4 z4, and the sensing and motor matrices of
// eq. 3-34..3-37. The reference case for tests and the starting point of a
// user's own layout. Units: tonne, mm, s, N.
#pragma once

#include <vector>

#include "deb/models/isolation_system.h"

namespace deb {

// Geometry of fig. 3-3 [mm]: P1 (d, w1, -h), P2 (d, -w2, -h), P3 (-d, -w2, -h),
// P4 (-d, w1, -h).
struct ThesisGeometry {
  double d = 615.0;
  double w1 = 570.0;
  double w2 = 445.0;
  double h = 210.0;
};

// The four isolators "P1".."P4" with the case study's springs and dampers:
// k_p = k_q = 12 N/mm (net, negative stiffness included), k_r = 15.38 N/mm on
// P1, P4 and 19.7 N/mm on P2, P3, c = 0.1 N/(mm/s) on every axis, phi = 0.
std::vector<Isolator> ThesisIsolators(const ThesisGeometry& geometry = {});

// Geophones "x1", "z1", "y2", "x3", "z3", "y4", "z4" on P1..P4 (fig. 3-11).
std::vector<VelocitySensor> ThesisGeophones();

// Actuators "x1", "z1", "y2", "z2", "x3", "z3", "y4", "z4" on P1..P4 (local
// axes p, q, r = x, y, z since phi = 0).
std::vector<ForceActuator> ThesisActuators();

// F of eq. 3-35 (6 x 7): logical axes from the geophones above.
Eigen::MatrixXd ThesisSensingMatrix();

// M of eq. 3-36/3-37 restricted to the eight actuators above (8 x 6); the
// thesis' four all-zero rows (y1, x2, y3, x4 have no actuator) are dropped.
Eigen::MatrixXd ThesisMotorMatrix();

// The complete case study of ch. 5: m = 2.1 t, J = diag(4.8e5, 5.0e5, 6.4e5)
// t mm^2 (the thesis' code; its Table 5-3 prints 48000...), g = 9810 mm/s^2,
// the parts above, K_v = 50 N/(mm/s) on all six logical axes.
IsolationSystem ThesisCaseStudy(const ThesisGeometry& geometry = {});

}  // namespace deb
