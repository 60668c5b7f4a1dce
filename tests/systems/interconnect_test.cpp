#include "deb/systems/interconnect.h"

#include <doctest/doctest.h>

#include <complex>
#include <random>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/transfer_function.h"
#include "test_util.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
using Eigen::MatrixXcd;
using testing::Contains;
using testing::MessageOf;
constexpr double kTwoPi = 2.0 * M_PI;
const std::vector<double> kFrequencies = {0.0, 0.013, 0.2, 0.31, 1.0, 2.7, 15.0, 400.0};

// G = (s + 3)/(s^2 + s + 4), K = (2 s + 1)/(s + 5): both SISO, K with D = 2.
const TransferFunction kG({1.0, 3.0}, {1.0, 1.0, 4.0});
const TransferFunction kK({2.0, 1.0}, {1.0, 5.0});

Complex Eval(const TransferFunction& tf, double f_hz) {
  return tf.Evaluate(Complex(0.0, kTwoPi * f_hz));
}

// All interconnection checks: 1e-10 relative to max(1, |H|).
void CheckClose(const MatrixXcd& x, const MatrixXcd& ref) {
  REQUIRE(x.rows() == ref.rows());
  REQUIRE(x.cols() == ref.cols());
  CHECK((x - ref).norm() <= 1e-10 * std::max(1.0, ref.norm()));
}

MatrixXcd Scalar(Complex v) { return MatrixXcd::Constant(1, 1, v); }

TEST_CASE("series of G then K responds as K(jw) G(jw)") {
  const FrequencyResponse h(Series(ToStateSpace(kG), ToStateSpace(kK)));
  for (double f : kFrequencies) CheckClose(h.At(f), Scalar(Eval(kK, f) * Eval(kG, f)));
}

TEST_CASE("series of MIMO systems multiplies responses in signal order") {
  std::mt19937 rng(11);
  const StateSpace first = testing::RandomSystem({{-1.0, -20.0}, {{5.0, 0.1}}}, 3, 2, rng);
  const StateSpace second = testing::RandomSystem({{-4.0}, {{30.0, 0.2}}}, 4, 3, rng);
  const FrequencyResponse h(Series(first, second)), h1(first), h2(second);
  for (double f : kFrequencies) CheckClose(h.At(f), h2.At(f) * h1.At(f));
}

TEST_CASE("parallel connection responds as G(jw) + K(jw)") {
  const FrequencyResponse h(Parallel(ToStateSpace(kG), ToStateSpace(kK)));
  for (double f : kFrequencies) CheckClose(h.At(f), Scalar(Eval(kG, f) + Eval(kK, f)));
}

TEST_CASE("negative feedback responds as G/(1 + G K)") {
  const FrequencyResponse h(Feedback(ToStateSpace(kG), ToStateSpace(kK)));
  for (double f : kFrequencies) {
    const Complex g = Eval(kG, f), k = Eval(kK, f);
    CheckClose(h.At(f), Scalar(g / (1.0 + g * k)));
  }
}

TEST_CASE("positive feedback responds as G/(1 - G K)") {
  const FrequencyResponse h(Feedback(ToStateSpace(kG), ToStateSpace(kK), +1));
  for (double f : kFrequencies) {
    const Complex g = Eval(kG, f), k = Eval(kK, f);
    CheckClose(h.At(f), Scalar(g / (1.0 - g * k)));
  }
}

TEST_CASE("MIMO feedback with feedthrough in plant and controller is (I + G K)^-1 G") {
  std::mt19937 rng(5);
  const StateSpace g = testing::RandomSystem({{-2.0, -9.0}, {{12.0, 0.05}}}, 3, 2, rng);
  StateSpace k = testing::RandomSystem({{-30.0}, {}}, 2, 3, rng);
  k = StateSpace(k.A(), k.B(), k.C(), 0.2 * k.D());  // keep I + D_k D_p invertible
  const FrequencyResponse h(Feedback(g, k)), hg(g), hk(k);
  for (double f : kFrequencies) {
    const MatrixXcd gf = hg.At(f), kf = hk.At(f);
    const MatrixXcd expected =
        (MatrixXcd::Identity(2, 2) + kf * gf).partialPivLu().solve(MatrixXcd::Identity(2, 2));
    CheckClose(h.At(f), gf * expected);
  }
}

TEST_CASE("feedback through a static controller gain needs no controller states") {
  const StateSpace loop = Feedback(ToStateSpace(kG), StateSpace::Gain(Eigen::MatrixXd::Constant(1, 1, 50.0)));
  CHECK(loop.states() == 2);
  const FrequencyResponse h(loop);
  for (double f : kFrequencies) {
    const Complex g = Eval(kG, f);
    CheckClose(h.At(f), Scalar(g / (1.0 + 50.0 * g)));
  }
}

TEST_CASE("append, block diagonal and stacked outputs place responses in blocks") {
  std::mt19937 rng(3);
  const StateSpace a = testing::RandomSystem({{-1.0}, {{3.0, 0.1}}}, 2, 1, rng);
  const StateSpace b = testing::RandomSystem({{-7.0, -0.5}, {}}, 1, 3, rng);
  const StateSpace c = testing::RandomSystem({{-2.0}, {}}, 3, 1, rng);
  const FrequencyResponse ha(a), hb(b), hc(c);
  const FrequencyResponse app(Append(a, b)), diag(BlockDiagonal({a, b, c})),
      stack(StackOutputs(a, c));
  for (double f : kFrequencies) {
    MatrixXcd ab = MatrixXcd::Zero(3, 4);
    ab.topLeftCorner(2, 1) = ha.At(f);
    ab.bottomRightCorner(1, 3) = hb.At(f);
    CheckClose(app.At(f), ab);
    MatrixXcd abc = MatrixXcd::Zero(6, 5);
    abc.topLeftCorner(3, 4) = ab;
    abc.bottomRightCorner(3, 1) = hc.At(f);
    CheckClose(diag.At(f), abc);
    MatrixXcd ac(5, 1);
    ac << ha.At(f), hc.At(f);
    CheckClose(stack.At(f), ac);
  }
}

TEST_CASE("mismatched sizes are rejected naming both sizes") {
  const StateSpace g = StateSpace::Gain(Eigen::MatrixXd::Ones(2, 3));
  const StateSpace k = StateSpace::Gain(Eigen::MatrixXd::Ones(4, 2));
  const std::string series = MessageOf([&] { Series(k, g); });
  CHECK(Contains(series, "second.inputs = 3"));
  CHECK(Contains(series, "first.outputs = 4"));
  CHECK(Contains(MessageOf([&] { Parallel(g, k); }), "a.inputs = 3 but b.inputs = 2"));
  CHECK(Contains(MessageOf([&] { StackOutputs(g, k); }), "a.inputs = 3 but b.inputs = 2"));
  CHECK(Contains(MessageOf([&] { Feedback(g, k); }), "controller.outputs = 4 but plant.inputs = 3"));
  CHECK_THROWS_AS(BlockDiagonal({}), InputError);
  CHECK(Contains(MessageOf([&] { Feedback(g, StateSpace::Gain(Eigen::MatrixXd::Ones(3, 2)), 0); }),
                 "sign = 0"));
}

TEST_CASE("a singular algebraic loop is rejected") {
  // Unit gain in positive feedback with unit controller: I - D_k D_p = 0.
  const StateSpace one = StateSpace::Gain(Eigen::MatrixXd::Ones(1, 1));
  const std::string msg = MessageOf([&] { Feedback(one, one, +1); });
  CHECK(Contains(msg, "algebraic loop"));
  CHECK(Contains(msg, "singular"));
  // The same gains in negative feedback are fine: 1/(1 + 1).
  CHECK(Feedback(one, one).D()(0, 0) == doctest::Approx(0.5).epsilon(1e-15));
}

}  // namespace
}  // namespace deb
