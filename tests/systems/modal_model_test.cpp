// The modal realisation of finite-element modes against closed forms:
// frequency responses to 1e-12 relative, exact variances to 1e-9 relative.
#include "deb/systems/modal_model.h"

#include <doctest/doctest.h>

#include <complex>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/lyapunov.h"
#include "test_util.h"

namespace deb {
namespace {

using cd = std::complex<double>;
using testing::Contains;
using testing::MessageOf;

constexpr double kTwoPi = 6.283185307179586476925286766559;

// One mode at 42 Hz, zeta 0.02, phi_in = 0.31, phi_out = -0.7 (1/sqrt(kg)).
ModalModel OneMode(ModalQuantity q = ModalQuantity::kDisplacement) {
  ModalModel m;
  m.f_hz = {42.0};
  m.zeta = {0.02};
  m.phi_in = Eigen::MatrixXd::Constant(1, 1, 0.31);
  m.phi_out = Eigen::MatrixXd::Constant(1, 1, -0.7);
  m.input_names = {"F"};
  m.output_names = {"z"};
  m.quantity = q;
  return m;
}

// Two modes, two inputs, three outputs.
ModalModel TwoModes(ModalQuantity q) {
  ModalModel m;
  m.f_hz = {12.5, 80.0};
  m.zeta = {0.01, 0.05};
  m.phi_in.resize(2, 2);
  m.phi_in << 0.4, -0.2, 0.1, 0.9;
  m.phi_out.resize(3, 2);
  m.phi_out << 1.0, 0.5, -0.3, 0.8, 0.0, -1.2;
  m.input_names = {"F1", "F2"};
  m.output_names = {"z1", "z2", "z3"};
  m.quantity = q;
  return m;
}

// sum_k phi_out(:,k) phi_in(:,k)^T / (w_k^2 - w^2 + 2 j zeta_k w_k w), times (j w)^n.
Eigen::MatrixXcd ClosedForm(const ModalModel& m, double f_hz) {
  const double w = kTwoPi * f_hz;
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(m.phi_out.rows(), m.phi_in.rows());
  for (int k = 0; k < m.modes(); ++k) {
    const double wn = kTwoPi * m.f_hz[k];
    const cd den(wn * wn - w * w, 2.0 * m.zeta[k] * wn * w);
    h += (m.phi_out.col(k) * m.phi_in.col(k).transpose()).cast<cd>() / den;
  }
  return h * std::pow(cd(0.0, w), DerivativeOrder(m.quantity));
}

const std::vector<double> kFrequencies = {0.1, 3.0, 12.5, 41.0, 42.0, 42.0 * std::sqrt(1 - 2 * 0.02 * 0.02), 43.0,
                                          80.0, 500.0, 1e4};

// deb's evaluation (FrequencyResponse, as a budget uses it) to 1e-12 relative.
// An acceleration output is D + C (sI - A)^-1 B, and below the modes the two
// terms cancel to (w/w_n)^2 of |D|: there the error is bounded by rounding
// of D, so its bound is 1e-12 |H| + 1e-15 |D| (observed: 2e-11 relative =
// 1e-16 |D| at 0.1 Hz). The dense LU reference of test_util.h agrees to 1e-11.
void CheckResponse(const ModalModel& m) {
  const StateSpace sys = ModalStateSpace(m);
  CHECK(sys.states() == 2 * m.modes());
  const FrequencyResponse fr(sys);
  for (double f : kFrequencies) {
    CAPTURE(f);
    const Eigen::MatrixXcd ref = ClosedForm(m, f);
    const double bound = 1e-12 * ref.norm() + 1e-15 * sys.D().norm();
    CHECK((fr.At(f) - ref).norm() <= bound);
    CHECK((testing::DenseResponse(sys, f) - ref).norm() <= 10 * bound);
  }
}

TEST_CASE("one mode: H = phi_out phi_in / (w_n^2 - w^2 + 2 j zeta w_n w), times j w per derivative") {
  for (ModalQuantity q : {ModalQuantity::kDisplacement, ModalQuantity::kVelocity, ModalQuantity::kAcceleration}) {
    CAPTURE(ToString(q));
    CheckResponse(OneMode(q));
  }
}

TEST_CASE("two modes, two inputs, three outputs: the responses of the modes add") {
  for (ModalQuantity q : {ModalQuantity::kDisplacement, ModalQuantity::kVelocity, ModalQuantity::kAcceleration}) {
    CAPTURE(ToString(q));
    CheckResponse(TwoModes(q));
  }
}

TEST_CASE("the realisation is block-diagonal and only acceleration has feedthrough") {
  const ModalModel m = TwoModes(ModalQuantity::kAcceleration);
  const StateSpace acc = ModalStateSpace(m);
  const double w1 = kTwoPi * 12.5;
  CHECK(acc.A()(0, 1) == 1.0);
  CHECK(acc.A()(1, 0) == doctest::Approx(-w1 * w1).epsilon(1e-15));
  CHECK(acc.A()(1, 1) == doctest::Approx(-2 * 0.01 * w1).epsilon(1e-15));
  CHECK(acc.A().block(0, 2, 2, 2).isZero());
  CHECK(acc.B().row(0).isZero());
  CHECK(acc.B().row(1) == m.phi_in.col(0).transpose());
  CHECK(acc.D().isApprox(m.phi_out * m.phi_in.transpose(), 1e-15));
  CHECK(ModalStateSpace(TwoModes(ModalQuantity::kDisplacement)).D().isZero());
  CHECK(ModalStateSpace(TwoModes(ModalQuantity::kVelocity)).D().isZero());
}

TEST_CASE("exact variance of one mode under a white force: S0 phi^2 / (8 zeta w_n^3), velocity / (8 zeta w_n)") {
  // deb: one-sided white S0 -> sigma^2 = S0 ||H||_2^2 / 2, W = S0/2;
  // ||1/(s^2 + 2 zeta w s + w^2)||_2^2 = 1/(4 zeta w^3), ||s/(...)||_2^2 = 1/(4 zeta w).
  // Tolerance 1e-9 relative.
  const double s0 = 2.5, phi2 = 0.31 * 0.31 * 0.7 * 0.7, wn = kTwoPi * 42.0, zeta = 0.02;
  const Eigen::MatrixXd w = Eigen::MatrixXd::Constant(1, 1, s0 / 2);
  CHECK(OutputCovariance(ModalStateSpace(OneMode()), w)(0, 0) ==
        doctest::Approx(s0 * phi2 / (8 * zeta * wn * wn * wn)).epsilon(1e-9));
  CHECK(OutputCovariance(ModalStateSpace(OneMode(ModalQuantity::kVelocity)), w)(0, 0) ==
        doctest::Approx(s0 * phi2 / (8 * zeta * wn)).epsilon(1e-9));
  // Acceleration has feedthrough of white force: infinite variance, said so.
  CHECK(Contains(MessageOf([&] { OutputCovariance(ModalStateSpace(OneMode(ModalQuantity::kAcceleration)), w); }),
                 "feedthrough"));
}

TEST_CASE("a rigid-body mode is a double integrator: -phi_out phi_in / w^2, poles at 0, no exact variance") {
  ModalModel m = OneMode();
  m.f_hz = {0.0};
  m.zeta = {0.0};
  const StateSpace sys = ModalStateSpace(m);
  for (double f : {0.1, 1.0, 100.0}) {
    const double w = kTwoPi * f;
    CHECK(std::abs(FrequencyResponse(sys).At(f)(0, 0) - cd(-(-0.7 * 0.31) / (w * w), 0.0)) <
          1e-12 * 0.7 * 0.31 / (w * w));
  }
  CHECK(sys.Poles().cwiseAbs().maxCoeff() < 1e-12);
  CHECK(Contains(MessageOf([&] { OutputCovariance(sys, Eigen::MatrixXd::Constant(1, 1, 1.0)); }),
                 "exact variance needs a stable path; poles at +0 rad/s, +0 rad/s"));
}

TEST_CASE("Truncated keeps the modes at or below the limit, with their shape columns") {
  const ModalModel t = TwoModes(ModalQuantity::kDisplacement).Truncated(50.0);
  CHECK(t.modes() == 1);
  CHECK(t.f_hz[0] == 12.5);
  CHECK(t.phi_in.cols() == 1);
  CHECK(t.phi_out.col(0) == TwoModes(ModalQuantity::kDisplacement).phi_out.col(0));
  CHECK(TwoModes(ModalQuantity::kDisplacement).Truncated(1.0).modes() == 0);
}

TEST_CASE("Validate names the mode, the DOF or the size that breaks a rule") {
  auto message = [](auto change) {
    ModalModel m = TwoModes(ModalQuantity::kDisplacement);
    change(m);
    return MessageOf([&] { m.Validate(); });
  };
  CHECK(message([](ModalModel&) {}) == "(no InputError)");
  CHECK(Contains(message([](ModalModel& m) { m.f_hz[1] = -1.0; }), "mode 2: natural frequency -1 Hz is negative"));
  CHECK(Contains(message([](ModalModel& m) { m.f_hz[0] = std::nan(""); }), "mode 1: natural frequency nan Hz is not finite"));
  CHECK(Contains(message([](ModalModel& m) { m.zeta[0] = 0.0; }), "mode 1: damping ratio 0 of a mode at 12.5 Hz must be > 0"));
  CHECK(Contains(message([](ModalModel& m) { m.zeta[1] = 1.0; }), "mode 2: damping ratio 1 is >= 1"));
  CHECK(Contains(message([](ModalModel& m) { m.zeta[1] = INFINITY; }), "not finite"));
  CHECK(Contains(message([](ModalModel& m) { m.f_hz[0] = 0.0, m.zeta[0] = -0.1; }), "damping ratio -0.1 is negative"));
  CHECK(message([](ModalModel& m) { m.f_hz[0] = 0.0, m.zeta[0] = 0.0; }) == "(no InputError)");  // rigid mode
  CHECK(Contains(message([](ModalModel& m) { m.zeta.pop_back(); }), "1 damping ratio(s) for 2 mode(s)"));
  CHECK(Contains(message([](ModalModel& m) { m.phi_in.conservativeResize(2, 1); }), "input shapes have 1 mode(s)"));
  CHECK(Contains(message([](ModalModel& m) { m.output_names[2] = "z1"; }), "output DOF 'z1' is given twice"));
  CHECK(Contains(message([](ModalModel& m) { m.input_names[0] = ""; }), "input DOF name is empty"));
  CHECK(Contains(message([](ModalModel& m) { m.input_names.pop_back(); }), "1 input DOF name(s) for 2 row(s)"));
  CHECK(Contains(message([](ModalModel& m) { m.phi_out(1, 1) = INFINITY; }),
                 "output shape of DOF 'z2' in mode 2 is not finite"));
  CHECK(Contains(message([](ModalModel& m) { m = m.Truncated(1.0); }), "at least one mode"));
  CHECK(Contains(MessageOf([] { ParseModalQuantity("jerk"); }),
                 "unknown output quantity 'jerk'; allowed: displacement, velocity, acceleration"));
  CHECK(ParseModalQuantity("velocity") == ModalQuantity::kVelocity);
  {
    ModalModel big;
    const int n = limits::kMaxModes + 1;
    big.f_hz.assign(n, 10.0);
    big.zeta.assign(n, 0.01);
    big.phi_in = Eigen::MatrixXd::Ones(1, n);
    big.phi_out = Eigen::MatrixXd::Ones(1, n);
    big.input_names = {"F"};
    big.output_names = {"z"};
    CHECK(Contains(MessageOf([&] { big.Validate(); }), "at most " + std::to_string(limits::kMaxModes)));
  }
}

}  // namespace
}  // namespace deb
