// Synthetic recordings with known spectra, from fixed seeds.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace deb::test {

constexpr double kPi = 3.14159265358979323846;

// n samples of zero-mean Gaussian white noise with standard deviation sigma.
inline Eigen::VectorXd WhiteNoise(Eigen::Index n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x(i) = normal(rng);
  return x;
}

// x_n = a x_{n-1} + e_n, e white with standard deviation sigma, started in
// its stationary distribution (variance sigma^2 / (1 - a^2)).
inline Eigen::VectorXd Ar1(Eigen::Index n, double a, double sigma, std::uint64_t seed) {
  const Eigen::VectorXd e = WhiteNoise(n, sigma, seed);
  Eigen::VectorXd x(n);
  x(0) = e(0) / std::sqrt(1.0 - a * a);
  for (Eigen::Index i = 1; i < n; ++i) x(i) = a * x(i - 1) + e(i);
  return x;
}

// One-sided PSD of that AR(1) process sampled at fs:
// S(f) = 2 sigma^2 / (fs |1 - a e^{-j 2 pi f / fs}|^2).
inline double Ar1Psd(double f_hz, double a, double sigma, double fs) {
  return 2.0 * sigma * sigma / (fs * (1.0 - 2.0 * a * std::cos(2.0 * kPi * f_hz / fs) + a * a));
}

// Periodogram-bin correlation of a periodic Hann window: neighbouring bins
// of |X|^2 correlate by (2/3)^2 and the next by (1/6)^2, so the mean of B
// bins has the variance of B / (1 + 2 (4/9 + 1/36)) independent ones.
constexpr double kHannBinCorrelationFactor = 1.0 + 2.0 * (4.0 / 9.0 + 1.0 / 36.0);

}  // namespace deb::test
