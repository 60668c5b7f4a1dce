#include "deb/systems/loop_margins.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

namespace deb {
namespace {

using cd = std::complex<double>;
constexpr double kTwoPi = 2.0 * M_PI;

std::vector<double> LogGrid(double f_lo, double f_hi, int n) {
  std::vector<double> f(n);
  for (int k = 0; k < n; ++k) f[k] = f_lo * std::pow(f_hi / f_lo, static_cast<double>(k) / (n - 1));
  return f;
}

Eigen::MatrixXcd Scalar(cd v) {
  Eigen::MatrixXcd m(1, 1);
  m(0, 0) = v;
  return m;
}

// L(s) = k / (s (s + 1) (s + 2)).
cd ThirdOrder(double k, double f_hz) {
  const cd s(0.0, kTwoPi * f_hz);
  return k / (s * (s + 1.0) * (s + 2.0));
}

// The root x > 0 of x (x + 1) (x + 4) = k^2 (x = w^2 at |L| = 1), by Newton.
double GainCrossoverW2(double k) {
  double x = 1.0;
  for (int i = 0; i < 100; ++i) x -= (x * (x + 1) * (x + 4) - k * k) / (3 * x * x + 10 * x + 4);
  return x;
}

TEST_CASE("k/(s(s+1)(s+2)): phase crossover at w = sqrt 2 with gain margin 6/k; phase margin at the cubic's root") {
  // Closed forms: arg L = -90 - atan w - atan(w/2) = -180 at w^2 = 2, where
  // |L| = k/6; |L| = 1 at w^2 = x, x (x+1) (x+4) = k^2, where
  // PM = 90 - atan w - atan(w/2). Tolerance 1e-10 relative (bisection to 1e-13 in log f).
  const double k = 2.0;
  const LoopMargins m = ComputeLoopMargins([&](double f) { return Scalar(ThirdOrder(k, f)); }, LogGrid(0.001, 100.0, 120));
  CHECK(m.channels == 1);
  REQUIRE(m.phase_crossovers.size() == 1);
  CHECK(m.phase_crossovers[0].f_hz == doctest::Approx(std::sqrt(2.0) / kTwoPi).epsilon(1e-10));
  CHECK(m.phase_crossovers[0].gain_margin == doctest::Approx(6.0 / k).epsilon(1e-10));
  REQUIRE(m.upper_gain_margin);
  CHECK(m.upper_gain_margin->gain_margin == doctest::Approx(3.0).epsilon(1e-10));
  CHECK_FALSE(m.lower_gain_margin);
  CHECK(ToDecibel(m.upper_gain_margin->gain_margin) == doctest::Approx(20 * std::log10(3.0)).epsilon(1e-10));

  const double w = std::sqrt(GainCrossoverW2(k));
  REQUIRE(m.gain_crossovers.size() == 1);
  CHECK(m.gain_crossovers[0].f_hz == doctest::Approx(w / kTwoPi).epsilon(1e-10));
  const double pm = 90.0 - (std::atan(w) + std::atan(w / 2.0)) * 180.0 / M_PI;
  REQUIRE(m.phase_margin);
  CHECK(m.phase_margin->phase_margin_deg == doctest::Approx(pm).epsilon(1e-9));
  CHECK(pm > 0.0);
}

TEST_CASE("an unstable loop: gain above 6 gives a gain margin below 1 and a negative phase margin") {
  // k = 12: |L| = 2 at the phase crossover, GM = 0.5; the crossover moves past w = sqrt 2.
  const double k = 12.0;
  const LoopMargins m = ComputeLoopMargins([&](double f) { return Scalar(ThirdOrder(k, f)); }, LogGrid(0.001, 100.0, 120));
  CHECK_FALSE(m.upper_gain_margin);
  REQUIRE(m.lower_gain_margin);
  CHECK(m.lower_gain_margin->gain_margin == doctest::Approx(0.5).epsilon(1e-10));
  const double w = std::sqrt(GainCrossoverW2(k));
  REQUIRE(m.phase_margin);
  CHECK(m.phase_margin->phase_margin_deg ==
        doctest::Approx(90.0 - (std::atan(w) + std::atan(w / 2.0)) * 180.0 / M_PI).epsilon(1e-9));
  CHECK(m.phase_margin->phase_margin_deg < 0.0);
}

TEST_CASE("wc^2/(s(s+wc)): phase margin 90 - atan sqrt((sqrt5-1)/2) degrees, no phase crossover") {
  // |L| = 1 at (w/wc)^2 = (sqrt 5 - 1)/2; the phase tends to -180 only as f -> infinity.
  const double wc = kTwoPi * 3.0;
  const auto loop = [&](double f) {
    const cd s(0.0, kTwoPi * f);
    return Scalar(wc * wc / (s * (s + wc)));
  };
  const LoopMargins m = ComputeLoopMargins(loop, LogGrid(0.01, 1000.0, 50));
  const double x = (std::sqrt(5.0) - 1.0) / 2.0;
  REQUIRE(m.gain_crossovers.size() == 1);
  CHECK(m.gain_crossovers[0].f_hz == doctest::Approx(3.0 * std::sqrt(x)).epsilon(1e-10));
  CHECK(m.phase_margin->phase_margin_deg == doctest::Approx(90.0 - std::atan(std::sqrt(x)) * 180.0 / M_PI).epsilon(1e-10));
  CHECK(m.phase_crossovers.empty());
  CHECK_FALSE(m.upper_gain_margin);
  CHECK_FALSE(m.lower_gain_margin);
}

TEST_CASE("the modulus margin is the minimum of |1 + L|, as a dense scan finds it") {
  // Independent computation: |1 + L| at 400001 log-spaced frequencies over
  // 0.1-1 Hz (around the minimum), a step of 5.8e-6 in ln f: the scan's
  // minimum is above the true one by O(step^2) relative. Tolerance 1e-8.
  const double k = 2.0;
  const LoopMargins m = ComputeLoopMargins([&](double f) { return Scalar(ThirdOrder(k, f)); }, LogGrid(0.001, 100.0, 120));
  double scan = 1e300, scan_f = 0.0;
  for (double f : LogGrid(0.1, 1.0, 400001)) {
    const double v = std::abs(1.0 + ThirdOrder(k, f));
    if (v < scan) scan = v, scan_f = f;
  }
  CHECK(m.modulus_margin == doctest::Approx(scan).epsilon(1e-8));
  CHECK(m.modulus_margin <= scan);
  CHECK(m.modulus_margin_f_hz == doctest::Approx(scan_f).epsilon(1e-4));
  // The modulus margin bounds the gain margin: GM >= 1/(1 - MM).
  CHECK(m.upper_gain_margin->gain_margin >= 1.0 / (1.0 - m.modulus_margin));
}

TEST_CASE("two decoupled channels: the modulus margin is the smaller channel's, no classical margins") {
  // sigma_min(I + diag(L1, L2)) = min(|1 + L1|, |1 + L2|): the MIMO margin
  // equals the smaller of the two SISO ones. Tolerance 1e-8.
  const std::vector<double> f = LogGrid(0.001, 100.0, 150);
  const auto l1 = [](double fz) { return ThirdOrder(2.0, fz); };
  const auto l2 = [](double fz) { return ThirdOrder(4.0, fz); };
  const LoopMargins m1 = ComputeLoopMargins([&](double fz) { return Scalar(l1(fz)); }, f);
  const LoopMargins m2 = ComputeLoopMargins([&](double fz) { return Scalar(l2(fz)); }, f);
  const LoopMargins both = ComputeLoopMargins(
      [&](double fz) {
        Eigen::MatrixXcd l = Eigen::MatrixXcd::Zero(2, 2);
        l(0, 0) = l1(fz);
        l(1, 1) = l2(fz);
        return l;
      },
      f);
  CHECK(both.channels == 2);
  CHECK(both.modulus_margin == doctest::Approx(std::min(m1.modulus_margin, m2.modulus_margin)).epsilon(1e-8));
  CHECK(m2.modulus_margin < m1.modulus_margin);
  CHECK(both.gain_crossovers.empty());
  CHECK(both.phase_crossovers.empty());
  CHECK_FALSE(both.phase_margin);
}

TEST_CASE("a loop closed on 2 of 12 channels: the modulus margin as the full SVD of a rotated copy gives it") {
  // L = G K with K acting on channels 3 and 8 only: columns of L are zero
  // elsewhere, and sigma_min(I + L) comes from a 4 x 4 problem. P L P^H
  // (P a random unitary) has the same singular values of I + L and no zero
  // column, so it takes the 12 x 12 SVD.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(12, 12), x(12, 12);
  for (Eigen::Index i = 0; i < 12; ++i)
    for (Eigen::Index j = 0; j < 12; ++j) {
      x(i, j) = cd(normal(rng), normal(rng));
      if (j == 2 || j == 7) a(i, j) = cd(normal(rng), normal(rng));
    }
  const Eigen::MatrixXcd p = Eigen::HouseholderQR<Eigen::MatrixXcd>(x).householderQ();
  const auto l = [&](double f) -> Eigen::MatrixXcd {
    const cd s(0.0, kTwoPi * f);
    return a * (3.0 / (s * (s + 1.0)));
  };
  const std::vector<double> f = LogGrid(0.01, 100.0, 300);
  const LoopMargins reduced = ComputeLoopMargins(l, f);
  const LoopMargins full = ComputeLoopMargins([&](double fz) { return Eigen::MatrixXcd(p * l(fz) * p.adjoint()); }, f);
  CHECK(reduced.channels == 12);
  CHECK(reduced.modulus_margin < 1.0);
  CHECK(std::abs(reduced.modulus_margin - full.modulus_margin) <= 1e-12);
  CHECK(std::abs(reduced.modulus_margin_f_hz / full.modulus_margin_f_hz - 1.0) <= 1e-6);
  // No loop at all: I + 0, every singular value 1.
  const LoopMargins none = ComputeLoopMargins([](double) { return Eigen::MatrixXcd(Eigen::MatrixXcd::Zero(4, 4)); }, f);
  CHECK(none.modulus_margin == 1.0);
}

TEST_CASE("a crossover exactly on a grid frequency is counted once") {
  // L = 1/(j f/f0): |L| = 1 at f0 = 1 Hz, a grid point; PM = 90.
  const LoopMargins m = ComputeLoopMargins([](double f) { return Scalar(1.0 / cd(0.0, f)); }, {0.1, 1.0, 10.0});
  REQUIRE(m.gain_crossovers.size() == 1);
  CHECK(m.gain_crossovers[0].f_hz == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(m.gain_crossovers[0].phase_margin_deg == doctest::Approx(90.0).epsilon(1e-12));
}

}  // namespace
}  // namespace deb
