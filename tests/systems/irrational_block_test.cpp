// Delays and sampled blocks (irrational_block.h): the exact responses against
// e^(-j w tau), H(e^(j w T)) and the hold's formula evaluated directly; the
// rational approximations against their closed forms (the Pade approximants
// written out, the inverse Tustin map) at 1e-12 relative on a log grid.
#include "deb/systems/irrational_block.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/frequency_model.h"
#include "deb/systems/loop_margins.h"
#include "tests/support/contains.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
using test::Contains;
constexpr double kPi = 3.14159265358979323846;

std::vector<double> LogGrid(double lo, double hi, int n) {
  std::vector<double> f;
  for (int i = 0; i < n; ++i) f.push_back(lo * std::pow(hi / lo, i / (n - 1.0)));
  return f;
}

double RelativeError(Complex a, Complex b) { return std::abs(a - b) / std::abs(b); }

TEST_CASE("a delay is e^(-j w tau) on the grid, and its Pade approximants are the written-out closed forms") {
  const double tau = 1e-4;
  const IrrationalBlock d1 = Delay(tau, 1), d2 = Delay(tau, 2), d6 = Delay(tau, 6);
  for (double f : LogGrid(0.1, 2e4, 60)) {
    CAPTURE(f);
    const double w = 2 * kPi * f;
    CHECK(std::abs(d6.At(f) - std::polar(1.0, -w * tau)) < 1e-15);
    const Complex x(0.0, w * tau);
    // (1 - x/2) / (1 + x/2) and (1 - x/2 + x^2/12) / (1 + x/2 + x^2/12).
    CHECK(RelativeError(d1.ApproximationAt(f), (1.0 - x / 2.0) / (1.0 + x / 2.0)) < 1e-12);
    CHECK(RelativeError(d2.ApproximationAt(f), (1.0 - x / 2.0 + x * x / 12.0) / (1.0 + x / 2.0 + x * x / 12.0)) <
          1e-12);
    // c_k = (2n-k)! n! / ((2n)! k! (n-k)!) for n = 6: 1, 1/2, 5/44, 1/66, 1/792, 1/15840, 1/665280.
    const double c[] = {1.0, 1.0 / 2, 5.0 / 44, 1.0 / 66, 1.0 / 792, 1.0 / 15840, 1.0 / 665280};
    Complex num = 0.0, den = 0.0;
    for (int k = 6; k >= 0; --k) {
      num = num * (-x) + c[k];
      den = den * x + c[k];
    }
    CHECK(RelativeError(d6.ApproximationAt(f), num / den) < 1e-12);
    CHECK(std::abs(std::abs(d6.ApproximationAt(f)) - 1.0) < 1e-12);  // an all-pass, like the delay
  }
  CHECK(d6.approximation.states() == 6);
  CHECK(d6.approximation.IsStable());
  // Phase error of (6, 6) at w tau = 1: tiny; at w tau = 10 the approximant is far off.
  CHECK(std::abs(ApproximationErrorAt(d6, 1.0 / (2 * kPi * tau)).phase_deg) < 1e-9);
  CHECK(std::abs(ApproximationErrorAt(d6, 10.0 / (2 * kPi * tau)).phase_deg) > 1.0);
}

TEST_CASE("a zero delay is a unit gain") {
  const IrrationalBlock d = Delay(0.0);
  CHECK(d.approximation.states() == 0);
  CHECK(d.At(123.0) == Complex(1.0, 0.0));
  CHECK(d.ApproximationAt(123.0) == Complex(1.0, 0.0));
}

TEST_CASE("a sampled block is H(e^(j w T)), its hold (1 - e^(-j w T)) / (j w T)") {
  // A discrete integrator with a lag: H(z) = 0.1 z / ((z - 1)(z - 0.5)) at 10 kHz.
  const double fs = 1e4, t = 1.0 / fs;
  const IrrationalBlock plain = Discrete(fs, {0.1, 0.0}, {1.0, -1.5, 0.5}, false);
  const IrrationalBlock held = Discrete(fs, {0.1, 0.0}, {1.0, -1.5, 0.5}, true);
  for (double f : LogGrid(0.5, 4999.0, 60)) {
    CAPTURE(f);
    const double w = 2 * kPi * f;
    const Complex z = std::exp(Complex(0.0, w * t));
    const Complex h = 0.1 * z / ((z - 1.0) * (z - 0.5));
    CHECK(RelativeError(plain.At(f), h) < 1e-12);
    const Complex hold = (1.0 - std::exp(Complex(0.0, -w * t))) / Complex(0.0, w * t);
    CHECK(RelativeError(held.At(f), h * hold) < 1e-9);  // the direct form loses digits to 1 - e^(-jwT)
    // Inverse Tustin: the equivalent at s = j w is H at z = e^(j 2 atan(w T / 2)).
    const Complex zt = std::exp(Complex(0.0, 2.0 * std::atan(w * t / 2.0)));
    CHECK(RelativeError(plain.ApproximationAt(f), 0.1 * zt / ((zt - 1.0) * (zt - 0.5))) < 1e-12);
  }
  CHECK(plain.nyquist_hz() == 5e3);
  // The pole at z = 1 is one at s = 0: a marginal pole, as the integrator is.
  const Eigen::VectorXcd poles = plain.approximation.Poles();
  double nearest = HUGE_VAL;
  for (Eigen::Index i = 0; i < poles.size(); ++i) nearest = std::min(nearest, std::abs(poles(i)));
  CHECK(nearest < 1e-9);
}

TEST_CASE("the hold's approximation is (1 - Pade(e^(-sT))) / (sT): 1 at DC, close below a tenth of the rate") {
  const double fs = 1e3, t = 1.0 / fs;
  const IrrationalBlock held = Discrete(fs, {1.0}, {1.0}, true, 4);  // the hold alone
  CHECK(std::abs(held.ApproximationAt(0.0) - 1.0) < 1e-12);
  // e^(-x) ~ N(-x)/N(x), n = 4: c = 1, 1/2, 3/28, 1/84, 1/1680.
  const double c[] = {1.0, 1.0 / 2, 3.0 / 28, 1.0 / 84, 1.0 / 1680};
  for (double f : LogGrid(0.1, 499.0, 40)) {
    CAPTURE(f);
    const Complex y(0.0, 2 * kPi * f * t);
    Complex n = 0.0, d = 0.0;
    for (int k = 4; k >= 0; --k) {
      n = n * (-y) + c[k];
      d = d * y + c[k];
    }
    CHECK(RelativeError(held.ApproximationAt(f), (1.0 - n / d) / y) < 1e-9);
    if (f < fs / 10) CHECK(RelativeError(held.ApproximationAt(f), held.At(f)) < 1e-6);
  }
}

TEST_CASE("a loop with a delay loses 360 f_c tau degrees of phase margin, exactly") {
  // L = (f_c / f) e^(-j w tau) / j: |L| = 1 at f_c, PM 90 - 360 f_c tau.
  const double f_c = 200.0, tau = 3e-4;
  const IrrationalBlock d = Delay(tau);
  const std::vector<double> f = LogGrid(1.0, 1e4, 400);
  const auto margins = [&](bool delayed) {
    return ComputeLoopMargins(
        [&](double x) {
          const Complex l = (f_c / x) / Complex(0.0, 1.0) * (delayed ? d.At(x) : Complex(1.0, 0.0));
          return Eigen::MatrixXcd::Constant(1, 1, l);
        },
        f);
  };
  const LoopMargins without = margins(false), with = margins(true);
  REQUIRE(without.phase_margin);
  REQUIRE(with.phase_margin);
  CHECK(with.phase_margin->f_hz == doctest::Approx(f_c).epsilon(1e-10));
  CHECK(without.phase_margin->phase_margin_deg - with.phase_margin->phase_margin_deg ==
        doctest::Approx(360.0 * f_c * tau).epsilon(1e-9));
}

TEST_CASE("a frequency model holds a delay exactly and lists it") {
  const FrequencyModel m =
      FrequencyModel::Series(FrequencyModel(Delay(1e-3)), FrequencyModel(StateSpace::Gain(Eigen::MatrixXd::Constant(1, 1, 2.0))));
  CHECK_FALSE(m.HasData());
  REQUIRE(m.IrrationalBlocks().size() == 1);
  CHECK(m.IrrationalBlocks()[0].Describe() == "a delay of 1 ms");
  CHECK(std::abs(m.At(250.0)(0, 0) - 2.0 * std::polar(1.0, -kPi / 2)) < 1e-14);
}

TEST_CASE("bad delays and sampled blocks: the rule") {
  const auto error = [](auto&& make) { return test::InputErrorOf(make); };
  CHECK(Contains(error([] { Delay(-1e-3); }), "finite number of seconds >= 0"));
  CHECK(Contains(error([] { Delay(std::nan("")); }), "finite number of seconds >= 0"));
  CHECK(Contains(error([] { Delay(1e-3, 0); }), "Pade order must be 1 to 12, not 0"));
  CHECK(Contains(error([] { Delay(1e-3, 13); }), "not 13"));
  CHECK(Contains(error([] { Discrete(0.0, {1.0}, {1.0}, false); }), "sample_hz must be a finite number > 0"));
  CHECK(Contains(error([] { Discrete(1e3, {1.0, 0.0, 0.0}, {1.0, -0.5}, false); }), "not causal"));
  CHECK(Contains(error([] { Discrete(1e3, {1.0}, {0.0, 0.0}, false); }), "denominator is zero"));
  CHECK(Contains(error([] { Discrete(1e3, {1.0}, {1.0, 1.0}, false); }), "root at z = -1"));
  CHECK(Contains(error([] { Discrete(1e3, {HUGE_VAL}, {1.0, 1.0}, false); }), "not finite"));
}

}  // namespace
}  // namespace deb
