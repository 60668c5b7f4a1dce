#include "deb/systems/state_space.h"

#include <doctest/doctest.h>

#include <random>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "test_util.h"

namespace deb {
namespace {

using Eigen::MatrixXd;
using testing::Contains;
using testing::MessageOf;

TEST_CASE("a state space with inconsistent sizes is rejected naming the matrix") {
  const MatrixXd a = MatrixXd::Zero(2, 2), b = MatrixXd::Zero(2, 1), c = MatrixXd::Zero(1, 2),
                 d = MatrixXd::Zero(1, 1);
  CHECK(Contains(MessageOf([&] { StateSpace(MatrixXd::Zero(2, 3), b, c, d); }), "A must be square"));
  CHECK(Contains(MessageOf([&] { StateSpace(a, MatrixXd::Zero(3, 1), c, d); }), "B must have 2 rows"));
  CHECK(Contains(MessageOf([&] { StateSpace(a, b, MatrixXd::Zero(1, 3), d); }), "C must have 2 columns"));
  CHECK(Contains(MessageOf([&] { StateSpace(a, b, c, MatrixXd::Zero(2, 1)); }), "D must be 1x1"));
  MatrixXd bad = a;
  bad(1, 0) = NAN;
  CHECK(Contains(MessageOf([&] { StateSpace(bad, b, c, d); }), "A(2,1)"));
}

TEST_CASE("poles are the eigenvalues of A and decide stability") {
  MatrixXd a(2, 2);
  a << 0.0, 1.0, -4.0, -0.4;  // s^2 + 0.4 s + 4
  const StateSpace stable(a, MatrixXd::Zero(2, 1), MatrixXd::Zero(1, 2), MatrixXd::Zero(1, 1));
  const Eigen::VectorXcd p = stable.Poles();
  REQUIRE(p.size() == 2);
  CHECK(p(0).real() == doctest::Approx(-0.2).epsilon(1e-14));
  CHECK(std::abs(p(0).imag()) == doctest::Approx(std::sqrt(4.0 - 0.04)).epsilon(1e-14));
  CHECK(stable.IsStable());
  a(1, 1) = 0.0;  // undamped: not stable
  CHECK_FALSE(StateSpace(a, MatrixXd::Zero(2, 1), MatrixXd::Zero(1, 2), MatrixXd::Zero(1, 1)).IsStable());
}

TEST_CASE("selecting outputs and inputs keeps the chosen rows and columns") {
  std::mt19937 rng(1);
  const StateSpace sys = testing::RandomSystem({{-1.0, -2.0}, {{3.0, 0.1}}}, 3, 4, rng);
  const StateSpace sub = sys.SelectOutputs({2, 0}).SelectInputs({3, 3, 1});
  CHECK(sub.outputs() == 2);
  CHECK(sub.inputs() == 3);
  const Eigen::MatrixXcd h = FrequencyResponse(sys).At(0.7), hs = FrequencyResponse(sub).At(0.7);
  // Same A: the sub-response is an exact subset up to rounding (1e-13).
  CHECK(std::abs(hs(0, 0) - h(2, 3)) <= 1e-13 * h.norm());
  CHECK(std::abs(hs(0, 1) - h(2, 3)) <= 1e-13 * h.norm());
  CHECK(std::abs(hs(1, 2) - h(0, 1)) <= 1e-13 * h.norm());
}

TEST_CASE("balancing evens out a badly scaled A without changing the response") {
  // A model with states in mixed units (m next to um): the similarity
  // T = diag(1, 1e6, 1, 1e6) spreads the entries of A over 12 decades.
  std::mt19937 rng(4);
  const StateSpace sys = testing::RandomSystem({{}, {{2.0, 0.05}, {40.0, 0.01}}}, 2, 2, rng);
  Eigen::VectorXd scale(4);
  scale << 1.0, 1e6, 1.0, 1e6;
  const Eigen::MatrixXd t = scale.asDiagonal(), t_inv = scale.cwiseInverse().asDiagonal();
  const StateSpace skewed(t_inv * sys.A() * t, t_inv * sys.B(), sys.C() * t, sys.D());
  const StateSpace balanced = skewed.Balanced();
  const auto spread = [](const MatrixXd& a) {
    return a.cwiseAbs().maxCoeff() / (a.array() != 0.0).select(a.cwiseAbs(), 1e300).minCoeff();
  };
  CHECK(spread(skewed.A()) > 1e10);
  CHECK(spread(balanced.A()) < 1e4);
  // Powers of two: the scaling is exact, so the poles agree to rounding of
  // the eigen solver and the response to 1e-12 relative.
  const FrequencyResponse h(sys), hb(balanced);
  for (double f : {0.01, 0.3, 2.0, 6.4, 100.0})
    CHECK(testing::RelativeError(hb.At(f), h.At(f)) <= 1e-12);
}

TEST_CASE("a static gain has no states and passes D through") {
  const StateSpace g = StateSpace::Gain(MatrixXd::Constant(2, 3, 1.5));
  CHECK(g.states() == 0);
  CHECK(g.outputs() == 2);
  CHECK(g.inputs() == 3);
  CHECK(g.IsStable());
  CHECK(g.Balanced().D() == g.D());
}

}  // namespace
}  // namespace deb
