// Shared helpers for tests/systems: reproducible random systems, a dense
// reference frequency response, and capturing InputError messages.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <string>
#include <random>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/state_space.h"
#include "tests/support/contains.h"

namespace deb::testing {

inline Eigen::MatrixXd RandomMatrix(int rows, int cols, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = n(rng);
  return m;
}

// A real block-diagonal matrix with the given real poles and pairs
// -zeta w +- j w sqrt(1-zeta^2), made dense by a random similarity transform
// (well conditioned: identity plus a scaled random matrix).
struct ModalSpec {
  std::vector<double> real_poles_rad_s;
  std::vector<std::pair<double, double>> pairs;  // (omega_n rad/s, zeta)
};

inline Eigen::MatrixXd DenseFromModes(const ModalSpec& spec, std::mt19937& rng) {
  const int n = static_cast<int>(spec.real_poles_rad_s.size() + 2 * spec.pairs.size());
  Eigen::MatrixXd blocks = Eigen::MatrixXd::Zero(n, n);
  int at = 0;
  for (double p : spec.real_poles_rad_s) blocks(at, at) = p, ++at;
  for (const auto& [w, z] : spec.pairs) {
    const double re = -z * w, im = w * std::sqrt(1.0 - z * z);
    blocks(at, at) = re;
    blocks(at, at + 1) = im;
    blocks(at + 1, at) = -im;
    blocks(at + 1, at + 1) = re;
    at += 2;
  }
  const Eigen::MatrixXd s = Eigen::MatrixXd::Identity(n, n) + 0.3 * RandomMatrix(n, n, rng);
  return s * blocks * s.inverse();
}

inline StateSpace RandomSystem(const ModalSpec& spec, int outputs, int inputs, std::mt19937& rng,
                               bool with_d = true) {
  const Eigen::MatrixXd a = DenseFromModes(spec, rng);
  const int n = static_cast<int>(a.rows());
  Eigen::MatrixXd d = with_d ? RandomMatrix(outputs, inputs, rng)
                             : Eigen::MatrixXd::Zero(outputs, inputs).eval();
  return StateSpace(a, RandomMatrix(n, inputs, rng), RandomMatrix(outputs, n, rng), d);
}

// The 12-state test system: a lightly damped pair (zeta = 1e-4 at 10 Hz), an
// integrator, and ordinary stable poles.
inline ModalSpec TwelveStateSpec() {
  const double two_pi = 2.0 * M_PI;
  return {{0.0, -3.0, -40.0, -700.0},
          {{two_pi * 10.0, 1e-4}, {two_pi * 2.0, 0.05}, {two_pi * 55.0, 0.02},
           {two_pi * 300.0, 0.3}}};
}

// H(j 2 pi f) by a dense LU solve per frequency: the reference.
inline Eigen::MatrixXcd DenseResponse(const StateSpace& sys, double f_hz) {
  const int n = sys.states();
  const std::complex<double> s(0.0, 2.0 * M_PI * f_hz);
  const Eigen::MatrixXcd m = s * Eigen::MatrixXcd::Identity(n, n) - sys.A().cast<std::complex<double>>();
  const Eigen::MatrixXcd x = m.partialPivLu().solve(sys.B().cast<std::complex<double>>());
  return sys.C().cast<std::complex<double>>() * x + sys.D().cast<std::complex<double>>();
}

inline std::vector<double> LogSpace(double f_lo, double f_hi, int count) {
  std::vector<double> f(count);
  for (int k = 0; k < count; ++k)
    f[k] = f_lo * std::pow(f_hi / f_lo, static_cast<double>(k) / (count - 1));
  return f;
}

inline double RelativeError(const Eigen::MatrixXcd& x, const Eigen::MatrixXcd& ref) {
  return (x - ref).norm() / ref.norm();
}

// The message of the InputError thrown by f, or "(no InputError)".
inline std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

using test::Contains;

}  // namespace deb::testing
