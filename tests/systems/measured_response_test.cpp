#include "deb/systems/measured_response.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "test_util.h"

namespace deb {
namespace {

using testing::Contains;
using testing::MessageOf;
constexpr double kPi = 3.141592653589793238462643383279502884;

Eigen::MatrixXcd Scalar(std::complex<double> v) { return Eigen::MatrixXcd::Constant(1, 1, v); }

// H(f) of a mass-spring-damper, 1/(m s^2 + c s + k) at s = j 2 pi f.
std::complex<double> Sdof(double f_hz) {
  const std::complex<double> s(0.0, 2.0 * kPi * f_hz);
  return 1.0 / (s * s + 2.0 * s + 400.0);
}

TEST_CASE("a power-law response is interpolated exactly between its points") {
  // A double integrator 1/s^2: |H| falls as f^-2 and the phase stays at -180 degrees.
  const auto h = [](double f) { return 1.0 / std::pow(std::complex<double>(0.0, 2.0 * kPi * f), 2); };
  const MeasuredResponse r({1.0, 10.0, 100.0}, {Scalar(h(1.0)), Scalar(h(10.0)), Scalar(h(100.0))});
  for (double f : {1.7, 3.16, 42.0, 99.0}) {
    const std::complex<double> got = r.At(f)(0, 0);
    CHECK(std::abs(got - h(f)) <= 1e-12 * std::abs(h(f)));
  }
  CHECK(r.At(10.0)(0, 0) == h(10.0));  // a data point returns its value
}

TEST_CASE("the phase is unwrapped, so it turns through -180 degrees instead of cutting across") {
  // -170 and -190 degrees: arg() gives -170 and +170; the chord in the complex
  // plane would pass near 0, the unwrapped phase passes -180 at the log midpoint.
  const auto at = [](double deg) { return Scalar(std::polar(1.0, deg * kPi / 180.0)); };
  const MeasuredResponse r({1.0, 4.0}, {at(-170.0), at(-190.0)});
  const std::complex<double> mid = r.At(2.0)(0, 0);
  CHECK(mid.real() == doctest::Approx(-1.0).epsilon(1e-12));
  CHECK(std::abs(mid.imag()) < 1e-12);
}

TEST_CASE("a resonance measured at 200 points per decade is reproduced between its points to 1e-2") {
  std::vector<double> f;
  std::vector<Eigen::MatrixXcd> h;
  // 200 points per decade, 0.1-10 Hz; f_n = 3.18 Hz, zeta = 0.05: 9 points
  // across the half-power band. The error is largest at the peak, where log |H|
  // is most curved in log f, and falls as the square of the spacing.
  for (int i = 0; i <= 400; ++i) {
    f.push_back(std::pow(10.0, -1.0 + i / 200.0));
    h.push_back(Scalar(Sdof(f.back())));
  }
  const MeasuredResponse r(f, h);
  double worst = 0.0;
  for (int i = 0; i < 400; ++i) {
    const double mid = std::sqrt(f[i] * f[i + 1]);
    worst = std::max(worst, std::abs(r.At(mid)(0, 0) - Sdof(mid)) / std::abs(Sdof(mid)));
  }
  MESSAGE("largest relative error between points: " << worst);
  CHECK(worst < 1e-2);
}

TEST_CASE("outside the data: an error by default, or zero, or the end value held") {
  const MeasuredResponse err({1.0, 10.0}, {Scalar({1, 1}), Scalar({2, -1})}, Extrapolation::kError, "plant.csv");
  const std::string m = MessageOf([&] { err.At(20.0); });
  CHECK(Contains(m, "'plant.csv'"));
  CHECK(Contains(m, "20 Hz is outside the data range 1-10 Hz"));
  const MeasuredResponse zero({1.0, 10.0}, {Scalar({1, 1}), Scalar({2, -1})}, Extrapolation::kZero);
  CHECK(zero.At(0.5)(0, 0) == std::complex<double>(0, 0));
  const MeasuredResponse hold({1.0, 10.0}, {Scalar({1, 1}), Scalar({2, -1})}, Extrapolation::kHold);
  CHECK(hold.At(0.5)(0, 0) == std::complex<double>(1, 1));
  CHECK(hold.At(50.0)(0, 0) == std::complex<double>(2, -1));
}

TEST_CASE("a zero magnitude falls back to linear interpolation of re and im") {
  const MeasuredResponse r({1.0, 3.0}, {Scalar({0, 0}), Scalar({2, 4})});
  CHECK(std::abs(r.At(2.0)(0, 0) - std::complex<double>(1, 2)) < 1e-15);
}

TEST_CASE("selected rows keep their values and order") {
  Eigen::MatrixXcd a(3, 1), b(3, 1);
  a << 1.0, 2.0, 3.0;
  b << 4.0, 5.0, 6.0;
  const MeasuredResponse r({1.0, 2.0}, {a, b});
  const MeasuredResponse s = r.SelectOutputs({2, 0});
  CHECK(s.outputs() == 2);
  CHECK(s.At(2.0)(0, 0) == std::complex<double>(6, 0));
  CHECK(s.At(2.0)(1, 0) == std::complex<double>(4, 0));
}

TEST_CASE("bad tables are rejected naming the rule") {
  CHECK(Contains(MessageOf([] { MeasuredResponse({1.0}, {Scalar(1.0)}); }), "at least 2 frequencies"));
  CHECK(Contains(MessageOf([] { MeasuredResponse({2.0, 1.0}, {Scalar(1.0), Scalar(1.0)}); }),
                 "must increase strictly"));
  CHECK(Contains(MessageOf([] { MeasuredResponse({0.0, 1.0}, {Scalar(1.0), Scalar(1.0)}); }), "finite and > 0"));
  CHECK(Contains(MessageOf([] { MeasuredResponse({1.0, 2.0}, {Scalar(1.0), Eigen::MatrixXcd::Ones(2, 1)}); }),
                 "point 2 is 2x1, the first is 1x1"));
  CHECK(Contains(MessageOf([] { MeasuredResponse({1.0, 2.0}, {Scalar(1.0), Scalar(NAN)}); }), "not finite"));
}

}  // namespace
}  // namespace deb
