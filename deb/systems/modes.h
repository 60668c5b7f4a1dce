// Modal summary of a path: natural frequency and damping ratio of each pole.
// Lightly damped modes carry most of the variance in a narrow band, so the
// automatic frequency grid refines around them, and `deb model` prints them so
// the user can check a model against known resonances.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

// One real pole or one complex-conjugate pair lambda = -zeta w_n +- j w_n
// sqrt(1 - zeta^2):
//   f_n_hz = |lambda| / (2 pi),   damping_ratio = -Re(lambda) / |lambda|.
// A real pole has damping_ratio = 1 (stable) or -1 (unstable); a pole at the
// origin (an integrator) has f_n_hz = 0 and damping_ratio = 1 by convention.
struct Mode {
  double f_n_hz = 0.0;
  double damping_ratio = 1.0;
  std::complex<double> pole_rad_s;  // the member with Im >= 0
  bool pair = false;                // true for a complex-conjugate pair

  // Frequency of the peak of |1/(s - lambda)(s - conj lambda)|: Im(lambda)/2pi.
  double damped_f_hz() const;
};

// Modes from a list of eigenvalues [rad/s] that is closed under conjugation
// (as those of a real matrix): one Mode per real eigenvalue, one per pair
// (the Im < 0 members are dropped), sorted by f_n_hz, then by damping ratio.
std::vector<Mode> ModesFromPoles(const Eigen::VectorXcd& poles_rad_s);

// True for a pole with Re < -1e-9 max(1, |p|): neither unstable nor on the
// imaginary axis (the rule of ClassifyPoles).
bool IsStrictlyStable(std::complex<double> pole_rad_s);

// Poles with Re > 1e-9 max(1, |p|) (unstable) and with |Re| within that
// (on the imaginary axis: marginal), for the stability checks.
struct PoleStability {
  std::vector<std::complex<double>> unstable;
  std::vector<std::complex<double>> marginal;
};
PoleStability ClassifyPoles(const Eigen::VectorXcd& poles_rad_s);

// ModesFromPoles(sys.Poles()).
std::vector<Mode> Modes(const StateSpace& sys);

}  // namespace deb
