#include "deb/systems/modes.h"

#include <doctest/doctest.h>

#include "deb/systems/interconnect.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

TEST_CASE("a mass-spring-damper has f_n = sqrt(k/m)/2pi and zeta = c/(2 sqrt(k m))") {
  // Tolerance 1e-12 relative.
  const double m = 2.1, c = 0.1, k = 12.0;
  const std::vector<Mode> modes = Modes(ToStateSpace(TransferFunction({1.0}, {m, c, k})));
  REQUIRE(modes.size() == 1);
  CHECK(modes[0].pair);
  CHECK(modes[0].f_n_hz == doctest::Approx(std::sqrt(k / m) / kTwoPi).epsilon(1e-12));
  CHECK(modes[0].damping_ratio == doctest::Approx(c / (2 * std::sqrt(k * m))).epsilon(1e-12));
  CHECK(modes[0].damped_f_hz() ==
        doctest::Approx(modes[0].f_n_hz * std::sqrt(1 - std::pow(modes[0].damping_ratio, 2)))
            .epsilon(1e-12));
}

TEST_CASE("modes are one per real pole or pair, sorted by natural frequency") {
  // Poles: integrator, -3, 40 Hz pair (zeta 0.02), 1 Hz pair (zeta 1e-4).
  const double w1 = kTwoPi * 40.0, w2 = kTwoPi * 1.0;
  const StateSpace sys = BlockDiagonal(
      {ToStateSpace(TransferFunction({1.0}, {1.0, 0.0})),
       ToStateSpace(TransferFunction({1.0}, {1.0, 3.0})),
       ToStateSpace(TransferFunction({1.0}, {1.0, 2 * 0.02 * w1, w1 * w1})),
       ToStateSpace(TransferFunction({1.0}, {1.0, 2 * 1e-4 * w2, w2 * w2}))});
  const std::vector<Mode> modes = Modes(sys);
  REQUIRE(modes.size() == 4);
  CHECK(modes[0].f_n_hz == doctest::Approx(0.0));
  CHECK(modes[0].damping_ratio == 1.0);
  CHECK_FALSE(modes[0].pair);
  CHECK(modes[1].f_n_hz == doctest::Approx(3.0 / kTwoPi).epsilon(1e-12));
  CHECK(modes[1].damping_ratio == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(modes[2].f_n_hz == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(modes[2].damping_ratio == doctest::Approx(1e-4).epsilon(1e-9));
  CHECK(modes[3].f_n_hz == doctest::Approx(40.0).epsilon(1e-12));
  CHECK(modes[3].damping_ratio == doctest::Approx(0.02).epsilon(1e-10));
}

TEST_CASE("an unstable real pole has damping ratio -1") {
  Eigen::VectorXcd poles(3);
  poles << std::complex<double>(0.5, 0.0), std::complex<double>(-1.0, 2.0),
      std::complex<double>(-1.0, -2.0);
  const std::vector<Mode> modes = ModesFromPoles(poles);
  REQUIRE(modes.size() == 2);
  CHECK(modes[0].damping_ratio == -1.0);
  CHECK(modes[1].f_n_hz == doctest::Approx(std::sqrt(5.0) / kTwoPi).epsilon(1e-14));
  CHECK(modes[1].damping_ratio == doctest::Approx(1.0 / std::sqrt(5.0)).epsilon(1e-14));
}

}  // namespace
}  // namespace deb
