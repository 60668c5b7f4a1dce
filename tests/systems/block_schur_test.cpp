#include "deb/systems/block_schur.h"

#include <doctest/doctest.h>

#include <random>

#include "test_util.h"

namespace deb {
namespace {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;

// A = S T S^-1 to 1e-13 relative, S S^-1 = I to 1e-12, T exactly zero
// outside its diagonal blocks and upper triangular inside them.
void CheckForm(const MatrixXd& a, const BlockSchurForm& f) {
  const int n = static_cast<int>(a.rows());
  REQUIRE(f.block_start.front() == 0);
  REQUIRE(f.block_start.back() == n);
  CHECK((f.s * f.t * f.s_inv - a.cast<std::complex<double>>()).norm() <= 1e-13 * a.norm());
  CHECK((f.s * f.s_inv - MatrixXcd::Identity(n, n)).norm() <= 1e-12);
  MatrixXcd outside = f.t;
  for (int b = 0; b < f.blocks(); ++b) {
    const int s0 = f.block_start[b], k = f.block_size(b);
    CHECK(f.t.block(s0, s0, k, k).triangularView<Eigen::StrictlyLower>().toDenseMatrix().isZero(0.0));
    outside.block(s0, s0, k, k).setZero();
  }
  CHECK(outside.isZero(0.0));
}

TEST_CASE("distinct well-separated eigenvalues give 1x1 blocks and a modest condition") {
  std::mt19937 rng(40);
  const MatrixXd a = testing::DenseFromModes(testing::TwelveStateSpec(), rng);
  const BlockSchurForm f = BlockDiagonalSchur(a);
  CheckForm(a, f);
  CHECK(f.blocks() == 12);
  CHECK(f.largest_block() == 1);
  CHECK(f.condition() < 1e4);
}

TEST_CASE("a Jordan block stays one block next to split-off simple eigenvalues") {
  // Double pole at -3 (one Jordan block) plus four simple poles, mixed.
  std::mt19937 rng(41);
  MatrixXd blocks = MatrixXd::Zero(6, 6);
  blocks(0, 0) = blocks(1, 1) = -3.0;
  blocks(0, 1) = 1.0;
  blocks.bottomRightCorner(4, 4) = testing::DenseFromModes({{-1.0, -10.0}, {{5.0, 0.1}}}, rng);
  const MatrixXd s = MatrixXd::Identity(6, 6) + 0.3 * testing::RandomMatrix(6, 6, rng);
  const MatrixXd a = s * blocks * s.inverse();
  const BlockSchurForm f = BlockDiagonalSchur(a);
  CheckForm(a, f);
  CHECK(f.blocks() == 5);
  CHECK(f.largest_block() == 2);
}

TEST_CASE("a six-fold Jordan chain cannot be split") {
  MatrixXd a = -MatrixXd::Identity(6, 6);
  for (int i = 1; i < 6; ++i) a(i, i - 1) = 1.0;
  const BlockSchurForm f = BlockDiagonalSchur(a);
  CheckForm(a, f);
  CHECK(f.blocks() == 1);
}

TEST_CASE("a random dense 30x30 matrix is split completely") {
  std::mt19937 rng(42);
  const MatrixXd a = testing::RandomMatrix(30, 30, rng);
  const BlockSchurForm f = BlockDiagonalSchur(a);
  CheckForm(a, f);
  CHECK(f.largest_block() == 1);
}

TEST_CASE("an empty matrix has no blocks") {
  const BlockSchurForm f = BlockDiagonalSchur(MatrixXd(0, 0));
  CHECK(f.blocks() == 0);
  CHECK(f.largest_block() == 0);
}

}  // namespace
}  // namespace deb
