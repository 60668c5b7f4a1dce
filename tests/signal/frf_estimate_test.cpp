#include "deb/signal/frf_estimate.h"

#include <doctest/doctest.h>

#include <complex>

#include "deb/core/error.h"
#include "deb/signal/time_series.h"
#include "deb/signal/welch.h"
#include "signal_test_support.h"

namespace deb {
namespace {

using test::kPi;

// Force x (white) and two responses: y = FIR (0.5, 0.3, -0.2) of x, and z =
// 2 x delayed by 3 samples, each with independent output noise.
CsdEstimate Shaker(double output_noise) {
  const Eigen::Index n = 1 << 16;
  const Eigen::VectorXd x = test::WhiteNoise(n, 1.0, 11), ny = test::WhiteNoise(n, output_noise, 12),
                        nz = test::WhiteNoise(n, output_noise, 13);
  Eigen::MatrixXd s(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    s(k, 0) = x(k);
    s(k, 1) = 0.5 * x(k) + (k >= 1 ? 0.3 * x(k - 1) : 0.0) - (k >= 2 ? 0.2 * x(k - 2) : 0.0) + ny(k);
    s(k, 2) = (k >= 3 ? 2.0 * x(k - 3) : 0.0) + nz(k);
  }
  WelchOptions o;
  o.segment_length = 1024;
  return WelchCsd(TimeSeries(1000.0, s, {"F", "y", "z"}), o);
}

std::complex<double> Fir(double f_hz) {
  const std::complex<double> z = std::polar(1.0, -2.0 * kPi * f_hz / 1000.0);
  return 0.5 + 0.3 * z - 0.2 * z * z;
}

TEST_CASE("H1 of a known filter and a pure delay is recovered to 0.5 % with coherence near 1") {
  const FrfEstimate e = EstimateFrf(Shaker(0.01), "F", {"y", "z"});
  REQUIRE(e.h.cols() == 2);
  CHECK(e.outputs == std::vector<std::string>{"y", "z"});
  double worst_y = 0.0, worst_z = 0.0, lowest_coherence = 1.0;
  for (std::size_t k = 1; k + 1 < e.f_hz.size(); ++k) {
    const double f = e.f_hz[k];
    const auto i = static_cast<Eigen::Index>(k);
    worst_y = std::max(worst_y, std::abs(e.h(i, 0) - Fir(f)));  // |H| <= 1
    // 2 e^{-j 2 pi f 3/fs}: a delay's phase falls linearly, -3 samples.
    worst_z = std::max(worst_z, std::abs(e.h(i, 1) - std::polar(2.0, -2.0 * kPi * f * 3.0 / 1000.0)) / 2.0);
    if (std::abs(Fir(f)) > 0.1) lowest_coherence = std::min(lowest_coherence, e.coherence(i, 0));
  }
  MESSAGE("largest error: FIR " << worst_y << ", delay " << worst_z << " (relative); lowest coherence "
                                << lowest_coherence);
  CHECK(worst_y < 5e-3);
  CHECK(worst_z < 5e-3);
  CHECK(lowest_coherence > 0.99);
  CHECK(e.empty_bins == 0);
}

TEST_CASE("output noise lowers the coherence but leaves H1 unbiased") {
  // Output noise of variance 1 against a delay path of gain 2 (signal power 4):
  // gamma^2 = 4 / (4 + 1) = 0.8 in every bin; H1 scatters about 2 by
  // sqrt((1 - gamma^2) / (2 n_d gamma^2)) ~ 3 % with n_d ~ 120 averages.
  const FrfEstimate e = EstimateFrf(Shaker(1.0), "F", {"z"});
  double mean_coherence = 0.0, mean_gain = 0.0;
  const std::size_t bins = e.f_hz.size() - 2;
  for (std::size_t k = 1; k + 1 < e.f_hz.size(); ++k) {
    mean_coherence += e.coherence(static_cast<Eigen::Index>(k), 0) / bins;
    mean_gain += std::abs(e.h(static_cast<Eigen::Index>(k), 0)) / bins;
  }
  MESSAGE("mean coherence " << mean_coherence << ", mean |H1| " << mean_gain);
  CHECK(mean_coherence == doctest::Approx(0.8).epsilon(0.02));
  CHECK(mean_gain == doctest::Approx(2.0).epsilon(0.01));
}

TEST_CASE("unknown channels and an output that is the input are errors naming them") {
  const CsdEstimate csd = Shaker(0.01);
  CHECK_THROWS_WITH_AS(EstimateFrf(csd, "G", {"y"}), "input 'G' is not a channel of the recording (F, y, z)", InputError);
  CHECK_THROWS_WITH_AS(EstimateFrf(csd, "F", {"w"}), "output 'w' is not a channel of the recording (F, y, z)",
                       InputError);
  CHECK_THROWS_WITH_AS(EstimateFrf(csd, "F", {"F"}), "output 'F' is the input channel", InputError);
  CHECK_THROWS_AS(EstimateFrf(csd, "F", {}), InputError);
}

TEST_CASE("noise on the input biases H1 low by the input's signal-to-noise ratio, and H2 not") {
  // Measured input = true force + noise of variance 0.25 (SNR 4): |H1| = 2 / (1 + 0.25) = 1.6,
  // while H2 = S_yy / S_yx stays at 2 (the output carries no noise).
  const Eigen::Index n = 1 << 16;
  const Eigen::VectorXd x = test::WhiteNoise(n, 1.0, 21), nx = test::WhiteNoise(n, 0.5, 22);
  Eigen::MatrixXd s(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    s(k, 0) = x(k) + nx(k);
    s(k, 1) = 2.0 * x(k);
  }
  WelchOptions o;
  o.segment_length = 1024;
  const CsdEstimate csd = WelchCsd(TimeSeries(1000.0, s, {"F", "y"}), o);
  double h1 = 0.0, h2 = 0.0;
  const FrfEstimate e1 = EstimateFrf(csd, "F", {"y"}, FrfEstimator::kH1);
  const FrfEstimate e2 = EstimateFrf(csd, "F", {"y"}, FrfEstimator::kH2);
  const std::size_t bins = csd.f_hz.size() - 2;
  for (std::size_t k = 1; k + 1 < csd.f_hz.size(); ++k) {
    h1 += std::abs(e1.h(static_cast<Eigen::Index>(k), 0)) / bins;
    h2 += std::abs(e2.h(static_cast<Eigen::Index>(k), 0)) / bins;
  }
  MESSAGE("mean |H1| " << h1 << " (expected 1.6), mean |H2| " << h2 << " (expected 2)");
  CHECK(h1 == doctest::Approx(1.6).epsilon(0.01));
  CHECK(h2 == doctest::Approx(2.0).epsilon(0.01));
  CHECK(ParseFrfEstimator("h2") == FrfEstimator::kH2);
  CHECK_THROWS_WITH_AS(ParseFrfEstimator("h3"), "unknown frequency response estimator 'h3'; allowed: h1, h2",
                       InputError);
}

}  // namespace
}  // namespace deb
