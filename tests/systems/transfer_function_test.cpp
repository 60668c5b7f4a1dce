#include "deb/systems/transfer_function.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <string>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "test_util.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * M_PI;

using testing::Contains;
using testing::MessageOf;

TEST_CASE("a first-order low-pass 1/(tau s + 1) has |H|^2 = 1/(1 + (2 pi f tau)^2)") {
  // Tolerance 1e-12 relative.
  const double tau = 0.037;
  const StateSpace ss = ToStateSpace(TransferFunction({1.0}, {tau, 1.0}));
  CHECK(ss.states() == 1);
  const FrequencyResponse h(ss);
  for (double f : {0.0, 0.01, 1.0, 4.3, 100.0, 1e4}) {
    const double expected = 1.0 / (1.0 + std::pow(kTwoPi * f * tau, 2));
    CHECK(std::norm(h.At(f)(0, 0)) == doctest::Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("a fourth-order transfer function responds as num(jw)/den(jw)") {
  // Poles at 1.6 Hz (zeta 0.01) and 32 Hz (zeta 0.05): coefficients span
  // eight decades. Tolerance 1e-10 relative, 200 frequencies 0.01-1000 Hz.
  const double w1 = kTwoPi * 1.6, w2 = kTwoPi * 32.0, z1 = 0.01, z2 = 0.05;
  // (s^2 + 2 z1 w1 s + w1^2)(s^2 + 2 z2 w2 s + w2^2), expanded.
  const double a1 = 2 * z1 * w1, b1 = w1 * w1, a2 = 2 * z2 * w2, b2 = w2 * w2;
  const std::vector<double> den = {1.0, a1 + a2, b1 + b2 + a1 * a2, a1 * b2 + a2 * b1, b1 * b2};
  for (const std::vector<double>& num :
       {std::vector<double>{3.0, -2.0, 500.0, 7e4}, std::vector<double>{0.5, 2.0, 1e3, 2e4, 1e6}}) {
    const TransferFunction tf(num, den);
    const StateSpace ss = ToStateSpace(tf);
    CHECK(ss.states() == 4);
    const FrequencyResponse h(ss);
    double worst = 0.0;
    for (double f : testing::LogSpace(0.01, 1000.0, 200)) {
      const Complex expected = tf.Evaluate(Complex(0.0, kTwoPi * f));
      worst = std::max(worst, std::abs(h.At(f)(0, 0) - expected) / std::abs(expected));
    }
    CHECK(worst <= 1e-10);
  }
}

TEST_CASE("leading zeros of numerator and denominator are trimmed") {
  const TransferFunction tf({0.0, 0.0, 2.0}, {0.0, 1.0, 3.0});
  CHECK(tf.num() == std::vector<double>{2.0});
  CHECK(tf.den() == std::vector<double>{1.0, 3.0});
  CHECK(tf.order() == 1);
}

TEST_CASE("a biproper transfer function keeps its direct feedthrough in D") {
  // (2s + 1)/(s + 5): D = 2 exactly, H(0) = 0.2 (1e-14).
  const StateSpace ss = ToStateSpace(TransferFunction({2.0, 1.0}, {1.0, 5.0}));
  CHECK(ss.D()(0, 0) == 2.0);
  CHECK(FrequencyResponse(ss).At(0.0)(0, 0).real() == doctest::Approx(0.2).epsilon(1e-14));
}

TEST_CASE("a constant transfer function is a static gain without states") {
  const StateSpace ss = ToStateSpace(TransferFunction({6.0}, {0.0, 2.0}));
  CHECK(ss.states() == 0);
  CHECK(ss.D()(0, 0) == 3.0);
  CHECK(ToStateSpace(TransferFunction::Gain(-1.5)).D()(0, 0) == -1.5);
}

TEST_CASE("an improper transfer function is rejected with both degrees") {
  const std::string msg = MessageOf([] { TransferFunction({1.0, 0.0, 0.0}, {1.0, 1.0}); });
  CHECK(msg.find("improper") != std::string::npos);
  CHECK(msg.find("numerator degree 2") != std::string::npos);
  CHECK(msg.find("denominator degree 1") != std::string::npos);
}

TEST_CASE("a zero or empty denominator is rejected") {
  CHECK(MessageOf([] { TransferFunction({1.0}, {0.0, 0.0}); }).find("denominator") !=
        std::string::npos);
  CHECK_THROWS_AS(TransferFunction({1.0}, {}), InputError);
  CHECK_THROWS_AS(TransferFunction({NAN}, {1.0}), InputError);
}

TEST_CASE("a transfer matrix stacks its entries block-diagonally") {
  // 2 outputs x 3 inputs; each entry's response must match its own
  // num/den (1e-12 relative), and the state count is the sum of orders.
  const std::vector<std::vector<TransferFunction>> g = {
      {TransferFunction({1.0}, {1.0, 1.0}), TransferFunction({2.0, 0.0}, {1.0, 0.4, 9.0}),
       TransferFunction::Gain(0.0)},
      {TransferFunction({1.0, 3.0}, {1.0, 2.0}), TransferFunction({5.0}, {1.0, 7.0}),
       TransferFunction({1.0}, {1.0, 0.1, 4.0, 1.0})}};
  const StateSpace ss = ToStateSpace(g);
  CHECK(ss.states() == 1 + 2 + 0 + 1 + 1 + 3);
  CHECK(ss.outputs() == 2);
  CHECK(ss.inputs() == 3);
  const FrequencyResponse h(ss);
  for (double f : {0.05, 0.3, 1.0, 7.0}) {
    const Eigen::MatrixXcd hf = h.At(f);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j) {
        const Complex expected = g[i][j].Evaluate(Complex(0.0, kTwoPi * f));
        CHECK(std::abs(hf(i, j) - expected) <= 1e-12 * std::max(1.0, std::abs(expected)));
      }
  }
}

TEST_CASE("a ragged or empty transfer matrix is rejected") {
  const TransferFunction one = TransferFunction::Gain(1.0);
  CHECK(MessageOf([&] { ToStateSpace({{one, one}, {one}}); }).find("row 2 has 1") !=
        std::string::npos);
  CHECK_THROWS_AS(ToStateSpace(std::vector<std::vector<TransferFunction>>{}), InputError);
}

}  // namespace
}  // namespace deb
