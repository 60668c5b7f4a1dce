#include "deb/systems/real_block_diagonal.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "test_util.h"

namespace deb {
namespace {

using Eigen::MatrixXd;

// A = U Y D Y^-1 U^T with D the groups' diagonal blocks of T: relative
// residual in the Frobenius norm.
double Reconstruction(const MatrixXd& a, const RealBlockDiagonalForm& f) {
  MatrixXd d = MatrixXd::Zero(a.rows(), a.cols());
  for (int g = 0; g < f.groups(); ++g)
    d.block(f.start[g], f.start[g], f.group_size(g), f.group_size(g)) =
        f.t.block(f.start[g], f.start[g], f.group_size(g), f.group_size(g));
  const MatrixXd s = f.u * f.y;
  const MatrixXd back = s * d * f.y.triangularView<Eigen::UnitUpper>().solve(f.u.transpose());
  return (back - a).norm() / a.norm();
}

// The group holding the eigenvalue nearest to `pole`.
int GroupOf(const RealBlockDiagonalForm& f, std::complex<double> pole) {
  int best = 0;
  for (int i = 0; i < f.eigenvalues.size(); ++i)
    if (std::abs(f.eigenvalues(i) - pole) < std::abs(f.eigenvalues(best) - pole)) best = i;
  for (int g = 0; g < f.groups(); ++g)
    if (best < f.start[g + 1]) return g;
  return -1;
}

TEST_CASE("distinct poles: every real pole and pair is its own group, and A is recovered to 1e-13") {
  std::mt19937 rng(11);
  const testing::ModalSpec spec = testing::TwelveStateSpec();
  const MatrixXd a = testing::DenseFromModes(spec, rng);
  const RealBlockDiagonalForm f = RealBlockDiagonal(a);
  CHECK(f.largest_group() <= 2);
  CHECK(f.groups() == static_cast<int>(spec.real_poles_rad_s.size() + spec.pairs.size()));
  // Couplings up to kDefaultMaxCoupling each (the poles span 0 to 2e3 rad/s).
  CHECK(f.condition <= 1e6);
  CHECK(Reconstruction(a, f) <= 1e-13);
  // Y is unit upper triangular.
  CHECK((f.y.diagonal().array() == 1.0).all());
  CHECK(f.y.triangularView<Eigen::StrictlyLower>().toDenseMatrix().isZero(0.0));
}

TEST_CASE("a Jordan chain and a repeated pair stay in one group each, wherever the Schur form puts them") {
  // Poles: a triple real pole at -2 (a Jordan chain), the pair -0.1 +- 5j
  // twice (semisimple, as two equal modes of a symmetric structure), and
  // four distinct poles between them, all mixed by a random orthogonal Q.
  MatrixXd d = MatrixXd::Zero(11, 11);
  d(0, 0) = d(1, 1) = d(2, 2) = -2.0;
  d(0, 1) = d(1, 2) = 1.0;
  const auto pair = [&](int at, double re, double im) {
    d(at, at) = d(at + 1, at + 1) = re;
    d(at, at + 1) = im;
    d(at + 1, at) = -im;
  };
  pair(3, -0.1, 5.0);
  d(5, 5) = -7.0;
  pair(6, -0.3, 30.0);
  d(8, 8) = -0.5;
  pair(9, -0.1, 5.0);
  std::mt19937 rng(3);
  const MatrixXd q = testing::RandomMatrix(11, 11, rng).householderQr().householderQ();
  const MatrixXd a = q * d * q.transpose();
  const RealBlockDiagonalForm f = RealBlockDiagonal(a);
  CHECK(f.swaps_failed == 0);
  const int chain = GroupOf(f, -2.0), twice = GroupOf(f, {-0.1, 5.0});
  CHECK(f.group_size(chain) == 3);
  CHECK(f.group_size(twice) == 4);
  CHECK(f.groups() == 2 + 3);  // and -7, -0.3 +- 30j, -0.5 alone
  CHECK(Reconstruction(a, f) <= 1e-12);
}

TEST_CASE("poles within the cluster gap are never split, even where the coupling would allow it") {
  // Two real poles 1e-4 apart, far from the rest: one group of 2.
  MatrixXd d = MatrixXd::Zero(4, 4);
  d(0, 0) = -1.0;
  d(1, 1) = -1.0001;
  d(2, 2) = -50.0;
  d(3, 3) = -3.0;
  std::mt19937 rng(5);
  const MatrixXd q = testing::RandomMatrix(4, 4, rng).householderQr().householderQ();
  const RealBlockDiagonalForm f = RealBlockDiagonal(q * d * q.transpose());
  CHECK(f.groups() == 3);
  CHECK(f.group_size(GroupOf(f, -1.0)) == 2);
  // A wider gap splits them.
  CHECK(RealBlockDiagonal(q * d * q.transpose(), kDefaultMaxCoupling, 1e-5).groups() == 4);
}

TEST_CASE("a large matrix is decoupled batch by batch and still recovered to 1e-12") {
  // 300 states: three batches of about 128 decoupled from those above by one
  // level-3 solve each; pairs repeated in threes (clusters that must not be
  // split) placed so that some straddle the natural batch ends.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 300;
  MatrixXd d = MatrixXd::Zero(n, n);
  double w = 0.0, zeta = 0.0;
  for (int k = 0; k < n / 2; ++k) {
    if (k % 20 != 1 && k % 20 != 2) {
      w = 2.0 * M_PI * 0.5 * std::pow(1000.0, unit(rng));
      zeta = 1e-3 * std::pow(100.0, unit(rng));
    }
    d(2 * k, 2 * k + 1) = 1.0;  // x = [q, q']: the non-normal physical block
    d(2 * k + 1, 2 * k) = -w * w;
    d(2 * k + 1, 2 * k + 1) = -2.0 * zeta * w;
  }
  const MatrixXd q = testing::RandomMatrix(n, n, rng).householderQr().householderQ();
  const MatrixXd a = q * d * q.transpose();
  const RealBlockDiagonalForm f = RealBlockDiagonal(a);
  CHECK(f.largest_group() == 6);  // a pair three times
  CHECK(f.condition <= 1e2);
  CHECK(Reconstruction(a, f) <= 1e-12);
  MESSAGE("300 states: " << f.groups() << " groups, cond(Y) " << f.condition << ", A recovered to "
                         << Reconstruction(a, f));
}

TEST_CASE("an empty matrix has no groups; a non-finite one is an InputError") {
  const RealBlockDiagonalForm f = RealBlockDiagonal(MatrixXd(0, 0));
  CHECK(f.groups() == 0);
  CHECK(f.largest_group() == 0);
  MatrixXd a = MatrixXd::Identity(2, 2);
  a(0, 1) = NAN;
  CHECK_THROWS_AS(RealBlockDiagonal(a), InputError);
}

}  // namespace
}  // namespace deb
