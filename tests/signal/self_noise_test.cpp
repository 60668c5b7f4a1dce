#include "deb/signal/self_noise.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "deb/signal/welch.h"
#include "tests/signal/signal_test_support.h"

namespace deb {
namespace {

constexpr double kFs = 200.0;
constexpr Eigen::Index kSamples = 1 << 20;

// Ground u seen by sensors with gains g_i plus independent white noise of
// standard deviation n_i.
CsdEstimate SideBySide(const std::vector<double>& gains, const std::vector<double>& noise_sigma) {
  const Eigen::VectorXd u = test::Ar1(kSamples, 0.7, 1.0, 21);  // coloured ground motion
  Eigen::MatrixXd m(kSamples, static_cast<Eigen::Index>(gains.size()));
  for (std::size_t i = 0; i < gains.size(); ++i)
    m.col(static_cast<Eigen::Index>(i)) =
        gains[i] * u + (noise_sigma[i] > 0.0 ? test::WhiteNoise(kSamples, noise_sigma[i], 30 + i)
                                             : Eigen::VectorXd::Zero(kSamples));
  WelchOptions o;
  o.segment_length = 1024;
  return WelchCsd(TimeSeries(kFs, m, {}, "um/s"), o);
}

// The noise is white, so the estimate's scatter across bins is its own
// standard error; the mean of B Hann bins has the variance of B / 1.944
// independent ones. Checks the mean over bins 1..511 against the truth
// within 4 such sigma and returns the relative deviation.
double CheckRecovered(const Eigen::VectorXd& estimate, double true_level, double allowed_bias = 0.0) {
  const Eigen::VectorXd bins = estimate.segment(1, 511);
  const double mean = bins.mean();
  const double scatter = std::sqrt((bins.array() - mean).square().sum() / (bins.size() - 1));
  const double sigma_mean = scatter * std::sqrt(test::kHannBinCorrelationFactor / bins.size());
  MESSAGE("noise estimate / truth = " << mean / true_level << ", 4 sigma = " << 4.0 * sigma_mean / true_level);
  CHECK(std::abs(mean - true_level) < 4.0 * sigma_mean + allowed_bias * true_level);
  return mean / true_level - 1.0;
}

TEST_CASE("three-sensor (Sleeman) estimates recover three different noise levels under three different gains") {
  const std::vector<double> gains = {1.0, 0.8, 1.25}, sigma = {0.3, 0.2, 0.45};
  const CsdEstimate csd = SideBySide(gains, sigma);
  const SelfNoiseEstimate r = ThreeSensorSelfNoise(csd, 0, 1, 2);
  REQUIRE(r.noise.psd.cols() == 3);
  CHECK(r.noise.channel_names == std::vector<std::string>{"ch1", "ch2", "ch3"});
  CHECK(r.noise.unit == "um/s");
  CHECK(r.method.find("Sleeman") != std::string::npos);
  for (int i = 0; i < 3; ++i) {
    const double truth = 2.0 * sigma[static_cast<std::size_t>(i)] * sigma[static_cast<std::size_t>(i)] / kFs;
    CheckRecovered(r.noise.psd.col(i), truth);
  }
}

TEST_CASE("two-sensor (Holcomb) estimates recover the common noise level of identical sensors") {
  const CsdEstimate csd = SideBySide({1.0, 1.0}, {0.3, 0.3});
  const SelfNoiseEstimate r = TwoSensorSelfNoise(csd, 0, 1);
  const double truth = 2.0 * 0.3 * 0.3 / kFs;
  // N = S (1 - gamma) with gamma estimated from K averages: E[gamma^2] is
  // biased up by (1 - g^2)^2 / K, which biases N down by about S (1 - g^2)^2
  // / (2 K g): allow that (0.2 % here).
  CheckRecovered(r.noise.psd.col(0), truth, 0.002);
  CheckRecovered(r.noise.psd.col(1), truth, 0.002);
}

TEST_CASE("a 20 % gain mismatch biases the two-sensor estimate by more than 10 % but not the three-sensor one") {
  const double sigma = 0.3, truth = 2.0 * sigma * sigma / kFs;
  const CsdEstimate csd = SideBySide({1.0, 1.2, 0.9}, {sigma, sigma, sigma});
  const SelfNoiseEstimate two = TwoSensorSelfNoise(csd, 0, 1);
  CHECK(std::abs(two.noise.psd.col(1).segment(1, 511).mean() / truth - 1.0) > 0.1);
  const SelfNoiseEstimate three = ThreeSensorSelfNoise(csd, 0, 1, 2);
  for (int i = 0; i < 3; ++i) CheckRecovered(three.noise.psd.col(i), truth);
}

TEST_CASE("self-noise estimates below zero are set to zero and counted; the result is a budget source") {
  // No noise at all: the estimate is zero up to rounding, below it in some bins.
  const CsdEstimate csd = SideBySide({1.0, 1.0, 1.0}, {0.0, 0.0, 0.0});
  const SelfNoiseEstimate r = ThreeSensorSelfNoise(csd, 0, 1, 2);
  CHECK(r.clamped_bins[0] > 0);
  CHECK(r.noise.psd.minCoeff() >= 0.0);
  const auto source = ToMeasuredSpectrum(r.noise);
  CHECK(source->channels() == 3);
}

TEST_CASE("self-noise needs distinct channels that exist") {
  const CsdEstimate csd = SideBySide({1.0, 1.0}, {0.3, 0.3});
  CHECK_THROWS_AS(TwoSensorSelfNoise(csd, 0, 0), InputError);
  CHECK_THROWS_AS(TwoSensorSelfNoise(csd, 0, 2), InputError);
  CHECK_THROWS_AS(ThreeSensorSelfNoise(csd, 0, 1, 1), InputError);
}

}  // namespace
}  // namespace deb
