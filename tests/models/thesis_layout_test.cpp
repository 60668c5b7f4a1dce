#include "deb/models/thesis_layout.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "deb/models/isolation_model.h"
#include "model_test_support.h"

namespace deb {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNoisePsd = 20.0;  // (um/s)^2/Hz per geophone, two-sided reading (Table 5-4)

// z row of G_nz: sensor noise (velocity) -> CoG z velocity, dimensionless.
StateSpace NoiseToZVelocity(double h) {
  ThesisGeometry geometry;
  geometry.h = h;
  return IsolationModel(ThesisCaseStudy(geometry)).SensorNoiseToCog().SelectOutputs({2});
}

// Appends the thesis' leaky integrator 1/(s + 0.02 pi) (eq. 5-29) to a SISO-output path.
StateSpace ThroughLeakyIntegrator(const StateSpace& g) {
  const Eigen::Index n = g.states();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + 1, n + 1);
  a.topLeftCorner(n, n) = g.A();
  a.block(n, 0, 1, n) = g.C();
  a(n, n) = -0.02 * kPi;
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n + 1, g.inputs());
  b.topRows(n) = g.B();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(1, n + 1);
  c(0, n) = 1.0;
  return StateSpace(a, b, c, Eigen::MatrixXd::Zero(1, g.inputs()));
}

}  // namespace

TEST_CASE("the thesis' sensor-noise velocity RMS of Table 5-4 is reproduced to four decimals") {
  // sigma = ||G_nz,z sqrt(20)||_2 (thesis' two-sided reading); um/s since the
  // path is velocity -> velocity. Printed: 11.1981 (h = 210 mm), 11.2137 (h = 0).
  const double s210 = std::sqrt(kNoisePsd * test::H2NormSquared(NoiseToZVelocity(210.0)));
  const double s0 = std::sqrt(kNoisePsd * test::H2NormSquared(NoiseToZVelocity(0.0)));
  std::printf("z velocity RMS from sensor noise: h=210 %.6f um/s, h=0 %.6f um/s\n", s210, s0);
  CHECK(std::abs(s210 - 11.1981) < 5e-5);
  CHECK(std::abs(s0 - 11.2137) < 5e-5);
}

TEST_CASE("the thesis' sensor-noise position RMS of Table 5-5 is reproduced to four decimals") {
  // The velocity passes 1/(s + 0.02 pi) (eq. 5-29, 5-30). Printed: 1.9047 um
  // (h = 210 mm), 1.8972 um (h = 0).
  const double s210 = std::sqrt(
      kNoisePsd * test::H2NormSquared(ThroughLeakyIntegrator(NoiseToZVelocity(210.0))));
  const double s0 =
      std::sqrt(kNoisePsd * test::H2NormSquared(ThroughLeakyIntegrator(NoiseToZVelocity(0.0))));
  std::printf("z position RMS from sensor noise: h=210 %.6f um, h=0 %.6f um\n", s210, s0);
  CHECK(std::abs(s210 - 1.9047) < 5e-5);
  CHECK(std::abs(s0 - 1.8972) < 5e-5);
}

}  // namespace deb
