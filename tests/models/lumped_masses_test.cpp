#include "deb/models/lumped_masses.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <utility>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/systems/frequency_response.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

using Complex = std::complex<double>;

Eigen::MatrixXcd Response(const StateSpace& s, double f_hz) {
  const Eigen::Index n = s.states();
  const Eigen::MatrixXcd m =
      Complex(0.0, kTwoPi * f_hz) * Eigen::MatrixXcd::Identity(n, n) - s.A().cast<Complex>();
  return s.C().cast<Complex>() * m.partialPivLu().solve(s.B().cast<Complex>()) + s.D().cast<Complex>();
}

// The two-mass optical table: a 400 kg table on 1.2 Hz mounts (zeta 0.08), a
// 20 kg head on a 60 Hz flexure (zeta 0.01); inputs floor acceleration, a
// force on the head, an actuator between head and table; output the gap.
struct Table {
  double m1 = 400.0, m2 = 20.0, k1, c1, k2, c2;
  Table() {
    k1 = m1 * std::pow(kTwoPi * 1.2, 2);
    c1 = 2.0 * 0.08 * std::sqrt(k1 * m1);
    k2 = m2 * std::pow(kTwoPi * 60.0, 2);
    c2 = 2.0 * 0.01 * std::sqrt(k2 * m2);
  }
  LumpedMasses Model() const {
    LumpedMasses m;
    m.names = {"table", "head"};
    m.mass_kg = {m1, m2};
    m.couplings = {{0, LumpedMasses::kGround, k1, c1}, {1, 0, k2, c2}};
    return m;
  }
  StateSpace Realised() const {
    return Model().Realise({{LumpedMasses::kGround, LumpedMasses::kGround}, {1, LumpedMasses::kGround}, {1, 0}},
                           {{1, 0, false}});
  }
};

}  // namespace

TEST_CASE("two masses: the gap's response to the floor, a force on the head and an actuator between them, against the closed form") {
  // With P1 = m1 s^2 + c1 s + k1, Z2 = c2 s + k2 and
  // D = P1 (m2 s^2 + Z2) + m2 s^2 Z2 (the determinant of the dynamic stiffness):
  //   gap / a_floor = -m2 (c1 s + k1) / D, gap / F_head = P1 / D, gap / F_act = (P1 + m2 s^2) / D.
  // H from deb's frequency response (the engine's evaluator); a dense
  // resolvent solve loses digits where H falls as 1/s^3 above the flexure.
  const Table t;
  const StateSpace s = t.Realised();
  CHECK(s.states() == 4);
  const FrequencyResponse response(s);
  // The floor's response falls as 1/f^3 above the flexure, and a sum of
  // partial fractions cancels there (docs/method.md, "Frequency responses"):
  // it is checked relative to its peak, the forces' relative to |H|.
  double worst = 0.0, worst_floor = 0.0, floor_peak = 0.0;
  std::vector<std::pair<double, Complex>> floor;
  for (double f = 0.01; f < 1e4; f *= 1.0116) {  // 200 points per decade
    const Complex p(0.0, kTwoPi * f);
    const Complex p1 = t.m1 * p * p + t.c1 * p + t.k1, z2 = t.c2 * p + t.k2;
    const Complex d = p1 * (t.m2 * p * p + z2) + t.m2 * p * p * z2;
    const Eigen::MatrixXcd h = response.At(f);
    const Complex expected[3] = {-t.m2 * (t.c1 * p + t.k1) / d, p1 / d, (p1 + t.m2 * p * p) / d};
    for (int j = 1; j < 3; ++j) worst = std::max(worst, std::abs(h(0, j) - expected[j]) / std::abs(expected[j]));
    floor_peak = std::max(floor_peak, std::abs(expected[0]));
    floor.push_back({std::abs(h(0, 0) - expected[0]), expected[0]});
  }
  for (const auto& [error, expected] : floor) worst_floor = std::max(worst_floor, error / floor_peak);
  CHECK(worst_floor <= 5e-12);  // measured 1.9e-12 of the peak (2e-12 relative at low f, 1.7e-8 relative at 10 kHz)
  CHECK(worst <= 1e-12);
}

TEST_CASE("two masses equal the state space an engineer derived by hand (published to 8 digits)") {
  // The realisation in an independent walk-through of this table (states: table and gap displacements, then
  // their velocities), its coefficients printed to 8 significant digits.
  Eigen::MatrixXd a(4, 4), b(4, 3), c(1, 4);
  a << 0, 0, 1, 0, 0, 0, 0, 1, -56.848921, 7106.1152, -1.2063716, 0.37699112, 56.848921, -149228.42, 1.2063716,
      -7.9168135;
  b << 0, 0, 0, 0, 0, 0, -1, 0, -0.0025, 0, 0.05, 0.0525;
  c << 0, 1, 0, 0;
  const StateSpace hand(a, b, c, Eigen::MatrixXd::Zero(1, 3));
  const StateSpace s = Table().Realised();
  double worst = 0.0;
  for (double f : {0.1, 1.0, 1.2, 10.0, 60.0, 100.0, 1000.0}) {
    const Eigen::MatrixXcd h = Response(s, f), r = Response(hand, f);
    for (int j = 0; j < 3; ++j) worst = std::max(worst, std::abs(h(0, j) - r(0, j)) / std::abs(r(0, j)));
  }
  CHECK(worst <= 1e-6);  // the printed coefficients' own rounding, through a 60 Hz resonance with zeta 0.01
}

TEST_CASE("a velocity output and one relative to the ground; a single free mass is a double integrator") {
  LumpedMasses m;
  m.names = {"mass"};
  m.mass_kg = {2.0};
  m.couplings = {{0, LumpedMasses::kGround, 800.0, 0.0}};
  const StateSpace s = m.Realise({{0, LumpedMasses::kGround}}, {{0, LumpedMasses::kGround, false}, {0, LumpedMasses::kGround, true}});
  for (double f : {0.5, 3.0, 50.0}) {
    const Complex p(0.0, kTwoPi * f), x = 1.0 / (2.0 * p * p + 800.0);
    const Eigen::MatrixXcd h = Response(s, f);
    CHECK(std::abs(h(0, 0) - x) <= 1e-13 * std::abs(x));
    CHECK(std::abs(h(1, 0) - p * x) <= 1e-13 * std::abs(p * x));
  }
  LumpedMasses free;
  free.names = {"stage"};
  free.mass_kg = {25.0};
  const StateSpace g = free.Realise({{0, LumpedMasses::kGround}}, {{0, LumpedMasses::kGround, false}});
  const Complex p(0.0, kTwoPi * 10.0);
  CHECK(std::abs(Response(g, 10.0)(0, 0) - 1.0 / (25.0 * p * p)) <= 1e-15);
}

TEST_CASE("bad masses and couplings are refused with the mass or coupling named") {
  const auto error = [](const LumpedMasses& m) {
    try {
      m.Validate();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  LumpedMasses m = Table().Model();
  m.mass_kg[1] = 0.0;
  CHECK(test::Contains(error(m), "mass 'head' must be > 0 kg"));
  m = Table().Model();
  m.couplings[1].k_n_per_m = -1.0;
  CHECK(test::Contains(error(m), "coupling 2 ('head' to 'table'): k and c must be >= 0"));
  m = Table().Model();
  m.couplings[1].b = 1;
  CHECK(test::Contains(error(m), "coupling 2 joins 'head' to itself"));
  m = Table().Model();
  m.couplings[0].k_n_per_m = m.couplings[0].c_n_s_per_m = 0.0;
  CHECK(test::Contains(error(m), "has neither k nor c"));
}

}  // namespace deb
