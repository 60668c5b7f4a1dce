// Random lightly damped models for the benchmarks: a block-diagonal A of
// mode pairs (natural frequencies log-uniform 0.5-500 Hz, damping log-uniform
// from zeta_min to zeta_min * zeta_ratio), plus a real pole at 3 Hz when the
// state count is odd, and random normal matrices to mix and drive it.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace deb::bench {

class RandomModes {
 public:
  explicit RandomModes(std::mt19937& rng) : rng_(rng) {}

  Eigen::MatrixXd ModalBlocks(int n, double zeta_min, double zeta_ratio) {
    Eigen::MatrixXd blocks = Eigen::MatrixXd::Zero(n, n);
    int at = 0;
    if (n % 2) blocks(at, at) = -2.0 * M_PI * 3.0, ++at;
    for (; at < n; at += 2) {
      const double w = 2.0 * M_PI * 0.5 * std::pow(1000.0, unit_(rng_));
      const double z = zeta_min * std::pow(zeta_ratio, unit_(rng_));
      blocks(at, at) = blocks(at + 1, at + 1) = -z * w;
      blocks(at, at + 1) = w * std::sqrt(1.0 - z * z);
      blocks(at + 1, at) = -blocks(at, at + 1);
    }
    return blocks;
  }

  // r x c standard normal entries, column by column.
  Eigen::MatrixXd Matrix(int r, int c) {
    Eigen::MatrixXd x(r, c);
    for (int j = 0; j < c; ++j)
      for (int i = 0; i < r; ++i) x(i, j) = normal_(rng_);
    return x;
  }

 private:
  std::mt19937& rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
};

}  // namespace deb::bench
