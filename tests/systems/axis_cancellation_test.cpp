#include "deb/systems/axis_cancellation.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "deb/core/math_constants.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/transfer_function.h"
#include "tests/systems/test_util.h"

namespace deb {
namespace {

StateSpace Tf(std::vector<double> num, std::vector<double> den) {
  return ToStateSpace(TransferFunction(std::move(num), std::move(den)));
}

std::complex<double> At(const StateSpace& s, double w_rad_s) {
  const Eigen::Index n = s.states();
  const Eigen::MatrixXcd a = s.A().cast<std::complex<double>>();
  const Eigen::MatrixXcd m = std::complex<double>(0.0, w_rad_s) * Eigen::MatrixXcd::Identity(n, n) - a;
  const Eigen::MatrixXcd h = s.C().cast<std::complex<double>>() * m.partialPivLu().solve(s.B().cast<std::complex<double>>()) +
                             s.D().cast<std::complex<double>>();
  return h(0, 0);
}

// The reduced realisation has the same transfer as the original at every
// frequency away from the cancelled poles.
void CheckSameTransfer(const StateSpace& full, const StateSpace& reduced) {
  for (double w : {1e-3, 0.1, 1.0, 7.0, 100.0, 1e4}) {
    const std::complex<double> a = At(full, w), b = At(reduced, w);
    CHECK(std::abs(a - b) <= 1e-10 * std::abs(a));
  }
}

}  // namespace

TEST_CASE("an integrator before a zero at the origin cancels: 1/s * s/(s+a) = 1/(s+a), variance W/(2a)") {
  const double a = 3.0, w = 2.5;
  const StateSpace full = Series(Tf({1.0}, {1.0, 0.0}), Tf({1.0, 0.0}, {1.0, a}));
  const auto c = CancelAxisPoles(full);
  REQUIRE(c);
  CHECK(c->system.states() == 1);
  REQUIRE(c->cancelled.size() == 1);
  CHECK(std::abs(c->cancelled(0)) <= 1e-12);
  CHECK(c->residual < 1e-14);
  CHECK(c->system.Poles()(0).real() == doctest::Approx(-a).epsilon(1e-14));
  CheckSameTransfer(full, c->system);
  // One-sided variance of a first-order low-pass under two-sided white w: w/(2a).
  const double variance = OutputCovariance(c->system, Eigen::MatrixXd::Constant(1, 1, w))(0, 0);
  CHECK(variance == doctest::Approx(w / (2.0 * a)).epsilon(1e-13));
}

TEST_CASE("an undamped resonance cancelled by zeros at +-j w0 is removed, both poles") {
  const double w0 = 2.0 * kPi * 50.0;
  // (1/(s^2 + w0^2)) then (s^2 + w0^2)/((s + 10)(s + 20)) = 1/((s + 10)(s + 20)).
  const StateSpace full = Series(Tf({1.0}, {1.0, 0.0, w0 * w0}), Tf({1.0, 0.0, w0 * w0}, {1.0, 30.0, 200.0}));
  const auto c = CancelAxisPoles(full);
  REQUIRE(c);
  CHECK(c->system.states() == 2);
  CHECK(c->cancelled.size() == 2);
  // Against the closed form, relative to its peak |H(0)| = 1/200: the
  // realisation's rounding (terms of w0^2 = 1e5) leaves 4.4e-13 of the peak
  // (measured), and 5e-10 of |H| where |H| has fallen by 1e6 (1e4 rad/s).
  for (double w : {1e-3, 0.1, 1.0, 7.0, 100.0, 1e4}) {
    const std::complex<double> s(0.0, w), closed = 1.0 / ((s + 10.0) * (s + 20.0));
    CHECK(std::abs(At(c->system, w) - closed) <= 1e-12 / 200.0);
  }
  // Variance of 1/((s+p)(s+q)) under two-sided white w: w / (2 p q (p + q)).
  const double variance = OutputCovariance(c->system, Eigen::MatrixXd::Constant(1, 1, 1.0))(0, 0);
  CHECK(variance == doctest::Approx(1.0 / (2.0 * 10.0 * 20.0 * 30.0)).epsilon(1e-12));
}

TEST_CASE("an integrator the input does not reach, or the output does not see, is removed") {
  // x1' = -x1 + u, x2' = 0 (no input); y = x1 + x2.
  Eigen::MatrixXd a(2, 2), b(2, 1), cm(1, 2), d(1, 1);
  a << -1, 0, 0, 0;
  b << 1, 0;
  cm << 1, 1;
  d << 0;
  const auto unreached = CancelAxisPoles(StateSpace(a, b, cm, d));
  REQUIRE(unreached);
  CHECK(unreached->system.states() == 1);
  // x2' = u but y = x1 only.
  b << 1, 1;
  cm << 1, 0;
  const auto unseen = CancelAxisPoles(StateSpace(a, b, cm, d));
  REQUIRE(unseen);
  CHECK(unseen->system.states() == 1);
}

TEST_CASE("axis poles that reach the output are kept: nothing is removed") {
  // 1/s * (s + 1)/(s + 3): residue 1/3 at 0.
  CHECK_FALSE(CancelAxisPoles(Series(Tf({1.0}, {1.0, 0.0}), Tf({1.0, 1.0}, {1.0, 3.0}))));
  // A double integrator with only one zero at the origin: one pole at 0 stays.
  CHECK_FALSE(CancelAxisPoles(Series(Tf({1.0}, {1.0, 0.0, 0.0}), Tf({1.0, 0.0}, {1.0, 3.0}))));
  // A small but real coupling (residue 1e-6 of the scale) is not rounding.
  CHECK_FALSE(CancelAxisPoles(Series(Tf({1.0}, {1.0, 0.0}), Tf({1.0, 1e-6}, {1.0, 3.0}))));
  // No axis poles, or an unstable one: nothing to do.
  CHECK_FALSE(CancelAxisPoles(Tf({1.0}, {1.0, 3.0})));
  CHECK_FALSE(CancelAxisPoles(Series(Tf({1.0}, {1.0, -1.0}), Tf({1.0, -1.0}, {1.0, 3.0}))));
  CHECK_FALSE(CancelAxisPoles(StateSpace::Gain(Eigen::MatrixXd::Identity(2, 2))));
}

TEST_CASE("a PID's integrator in series with the process sensitivity of a loop it closes: -C P S = -T") {
  // Plant P = 1/(m s^2) (a free mass), PID C = kp (1 + w_i/s + s/w_d)/(1 + s/w_lp).
  const double m = 25.0, fc = 80.0, wc = 2.0 * kPi * fc;
  const double kp = m * wc * wc / 3.0, wi = wc / 5.0, wd = wc / 3.0, wlp = 3.0 * wc;
  const StateSpace plant = Tf({1.0 / m}, {1.0, 0.0, 0.0});
  // kp (s^2/w_d + s + w_i) / (s (1 + s/w_lp)) = kp w_lp (s^2/w_d + s + w_i) / (s^2 + w_lp s).
  const StateSpace pid = Tf({kp * wlp / wd, kp * wlp, kp * wlp * wi}, {1.0, wlp, 0.0});
  const StateSpace ps = Feedback(plant, pid, -1);
  const StateSpace noise = Series(Series(StateSpace::Gain(Eigen::MatrixXd::Constant(1, 1, -1.0)), pid), ps);
  const StateSpace t = Feedback(Series(pid, plant), StateSpace::Gain(Eigen::MatrixXd::Identity(1, 1)), -1);
  const auto c = CancelAxisPoles(noise);
  REQUIRE(c);
  CHECK(c->cancelled.size() == 1);
  CHECK(c->system.IsStable());
  CheckSameTransfer(noise, c->system);
  // The independent figure: T's own exact variance (the same transfer up to sign).
  const Eigen::MatrixXd one = Eigen::MatrixXd::Constant(1, 1, 1e-18);
  const double reduced = OutputCovariance(c->system, one)(0, 0), direct = OutputCovariance(t, one)(0, 0);
  CHECK(reduced == doctest::Approx(direct).epsilon(1e-10));
}

}  // namespace deb
