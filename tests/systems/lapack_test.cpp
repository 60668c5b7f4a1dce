#include "deb/systems/lapack.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <random>
#include <vector>

#include "deb/core/error.h"

namespace {

using deb::InputError;
using Eigen::MatrixXd;
using Complex = std::complex<double>;

MatrixXd Gaussian(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  MatrixXd x(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) x(i, j) = normal(rng);
  return x;
}

// Poles -1, -2 +- 3j, -0.5 +- 10j under a random (non-orthogonal) similarity.
MatrixXd KnownMatrix() {
  MatrixXd blocks = MatrixXd::Zero(5, 5);
  blocks(0, 0) = -1.0;
  blocks.block(1, 1, 2, 2) << -2.0, 3.0, -3.0, -2.0;
  blocks.block(3, 3, 2, 2) << -0.5, 10.0, -10.0, -0.5;
  const MatrixXd s = MatrixXd::Identity(5, 5) + 0.3 * Gaussian(5, 5, 3);
  return s * blocks * s.inverse();
}

std::vector<Complex> Sorted(const Eigen::VectorXcd& v) {
  std::vector<Complex> out(v.data(), v.data() + v.size());
  std::sort(out.begin(), out.end(), [](Complex a, Complex b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
  return out;
}

// Real eigenvalues with im == 0 exactly; pairs exactly conjugate, +j first.
void CheckExactPairs(const Eigen::VectorXcd& lambda) {
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (lambda(k).imag() == 0.0) continue;
    REQUIRE(lambda(k).imag() > 0.0);
    REQUIRE(k + 1 < lambda.size());
    CHECK(lambda(k + 1) == std::conj(lambda(k)));
    ++k;
  }
}

}  // namespace

TEST_CASE("RealSchur finds the known poles, real ones exactly real, pairs exactly conjugate") {
  const Eigen::VectorXcd lambda = deb::RealSchur(KnownMatrix()).eigenvalues;
  REQUIRE(lambda.size() == 5);
  CheckExactPairs(lambda);
  const std::vector<Complex> expected = {{-2.0, -3.0}, {-2.0, 3.0}, {-1.0, 0.0},
                                         {-0.5, -10.0}, {-0.5, 10.0}};
  const std::vector<Complex> got = Sorted(lambda);
  for (int k = 0; k < 5; ++k) CHECK(std::abs(got[k] - expected[k]) < 1e-12 * 10.0);
  CHECK(got[2].imag() == 0.0);
}

TEST_CASE("a pole at zero is +0, also from a diagonal entry -0") {
  MatrixXd a(2, 2);
  a << 0.0, 1.0, -0.0, -0.0;  // a rigid-body mode without damping
  const Eigen::VectorXcd lambda = deb::RealSchur(a).eigenvalues;
  for (Eigen::Index k = 0; k < 2; ++k) {
    CHECK_FALSE(std::signbit(lambda(k).real()));
    CHECK_FALSE(std::signbit(lambda(k).imag()));
  }
}

TEST_CASE("RealSchur reproduces A = U T U^T with U orthogonal and T quasi triangular") {
  const MatrixXd a = Gaussian(40, 40, 11);
  const deb::RealSchurForm f = deb::RealSchur(a);
  CHECK((f.u * f.t * f.u.transpose() - a).norm() <= 1e-12 * a.norm());
  CHECK((f.u.transpose() * f.u - MatrixXd::Identity(40, 40)).norm() <= 1e-12);
  CheckExactPairs(f.eigenvalues);
  for (int j = 0; j < 40; ++j)
    for (int i = j + 2; i < 40; ++i) REQUIRE(f.t(i, j) == 0.0);
  // Each 2x2 block is standardised and holds the pair listed at its rows.
  for (int k = 0; k < 40; ++k) {
    if (k + 1 < 40 && f.t(k + 1, k) != 0.0) {
      CHECK(f.t(k, k) == f.t(k + 1, k + 1));
      CHECK(f.eigenvalues(k).real() == f.t(k, k));
      CHECK(f.eigenvalues(k).imag() > 0.0);
      CHECK(f.eigenvalues(k + 1) == std::conj(f.eigenvalues(k)));
      if (k + 2 < 40) CHECK(f.t(k + 2, k + 1) == 0.0);
      ++k;
    } else {
      CHECK(f.eigenvalues(k) == Complex(f.t(k, k), 0.0));
    }
  }
}

TEST_CASE("SolveQuasiTriangularSylvester solves T1 X + X T2^T = C") {
  // Eigenvalues with Re < 0 in both (|lambda| of a Gaussian n x n ~ sqrt n):
  // T1 and -T2 share none.
  const deb::RealSchurForm f1 =
      deb::RealSchur(Gaussian(30, 30, 5) - 12.0 * MatrixXd::Identity(30, 30));
  const deb::RealSchurForm f2 =
      deb::RealSchur(Gaussian(20, 20, 6) - 12.0 * MatrixXd::Identity(20, 20));
  const MatrixXd c = Gaussian(30, 20, 7);
  const deb::SylvesterSolution s = deb::SolveQuasiTriangularSylvester(f1.t, f2.t, c);
  CHECK_FALSE(s.near_singular);
  CHECK((f1.t * s.x + s.x * f2.t.transpose() - c).norm() <= 1e-12 * c.norm());
}

TEST_CASE("SolveQuasiTriangularSylvester flags T1 and -T2 sharing an eigenvalue") {
  MatrixXd t1(2, 2), t2(1, 1), c(2, 1);
  t1 << 1.0, 5.0, 0.0, -3.0;
  t2 << -1.0;  // 1 + (-1) = 0
  c << 1.0, 2.0;
  CHECK(deb::SolveQuasiTriangularSylvester(t1, t2, c).near_singular);
}

TEST_CASE("the LAPACK functions refuse a matrix that is not square or not finite") {
  CHECK_THROWS_WITH_AS(deb::RealSchur(MatrixXd::Zero(2, 3)), doctest::Contains("not square"),
                       InputError);
  MatrixXd a = MatrixXd::Identity(3, 3);
  a(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(deb::RealSchur(a), doctest::Contains("not finite"), InputError);
  CHECK_THROWS_WITH_AS(deb::SolveQuasiTriangularSylvester(a, MatrixXd::Identity(1, 1),
                                                          MatrixXd::Ones(3, 1)),
                       doctest::Contains("not finite"), InputError);
  CHECK(deb::RealSchur(MatrixXd(0, 0)).t.size() == 0);
  // A right-hand side that is not finite gives a solution that is not finite.
  MatrixXd c = MatrixXd::Ones(3, 1);
  c(0, 0) = std::numeric_limits<double>::infinity();
  CHECK(deb::SolveQuasiTriangularSylvester(MatrixXd::Identity(3, 3), MatrixXd::Identity(1, 1), c)
            .x.hasNaN());
}

TEST_CASE("the BLAS kernels: named when the BLAS is OpenBLAS; a better choice only where it picked pre-AVX2 ones") {
  // Which kernels OpenBLAS picked depends on the machine; what holds on any:
  const std::string now = deb::BlasKernel();
  const std::vector<std::string> avx2_or_later = {"Haswell", "Zen", "SkylakeX", "Cooperlake", "SapphireRapids"};
  const bool fine = std::find(avx2_or_later.begin(), avx2_or_later.end(), now) != avx2_or_later.end();
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  const std::optional<std::string> better = deb::BetterBlasKernel();
  MESSAGE("OpenBLAS kernels: '" << now << "', OPENBLAS_CORETYPE " << std::string(set ? set : "unset") << ", better: "
                                << (better ? *better : "none"));
  if (now.empty() || fine || set != nullptr) CHECK(!better);
  if (better) CHECK((*better == "SkylakeX" || *better == "Haswell"));
  // Once OPENBLAS_CORETYPE is set (by the user, or by deb before it starts
  // itself again), the choice stands: no second restart.
  const std::string before = set ? set : "";
  ::setenv("OPENBLAS_CORETYPE", "Prescott", 1);
  CHECK(!deb::BetterBlasKernel());
  if (set)
    ::setenv("OPENBLAS_CORETYPE", before.c_str(), 1);
  else
    ::unsetenv("OPENBLAS_CORETYPE");
}

TEST_CASE("BlasProduct equals Eigen's product to rounding, on blocks with strides and on empty sizes") {
  // Against Eigen's product, 1e-14 of the norms' product (both sum the same
  // terms in other orders: observed about 1e-16).
  const MatrixXd a = Gaussian(70, 90, 21), b = Gaussian(90, 130, 22);
  MatrixXd out(70, 130);
  deb::BlasProduct(a, b, out);
  CHECK((out - a * b).norm() <= 1e-14 * a.norm() * b.norm());
  // Blocks of larger matrices: rows of a (stride 70), columns of b and out.
  MatrixXd wide = MatrixXd::Zero(70, 200);
  deb::BlasProduct(a.topRows(40), b.middleCols(30, 50), wide.block(10, 100, 40, 50));
  CHECK((wide.block(10, 100, 40, 50) - a.topRows(40) * b.middleCols(30, 50)).norm() <= 1e-14 * a.norm() * b.norm());
  CHECK(wide.leftCols(100).norm() == 0.0);
  CHECK(wide.topRows(10).norm() == 0.0);
  // An inner size of 0 gives zeros; no rows or columns, nothing.
  MatrixXd z = MatrixXd::Constant(3, 4, 7.0);
  deb::BlasProduct(MatrixXd(3, 0), MatrixXd(0, 4), z);
  CHECK(z.norm() == 0.0);
  MatrixXd none(0, 4);
  deb::BlasProduct(MatrixXd(0, 5), MatrixXd::Ones(5, 4), none);
  CHECK(none.size() == 0);
}

TEST_CASE("BlasUnitUpperSolve solves with Y's unit upper triangle only, as Eigen's triangular solve") {
  // Y's diagonal and lower part hold numbers that must not be read; its
  // strict upper part is scaled by 0.1, so that Y stays well conditioned
  // (a unit triangle of Gaussian entries grows its condition exponentially).
  const MatrixXd y = 0.1 * Gaussian(60, 60, 23);
  const MatrixXd rhs = Gaussian(60, 25, 24);
  const MatrixXd want = y.triangularView<Eigen::UnitUpper>().solve(rhs);
  MatrixXd wide = MatrixXd::Zero(60, 40);
  wide.middleCols(10, 25) = rhs;
  deb::BlasUnitUpperSolve(y, wide.middleCols(10, 25));
  // Relative to the solution: observed about 1e-15.
  CHECK((wide.middleCols(10, 25) - want).norm() <= 1e-12 * want.norm());
  CHECK(wide.leftCols(10).norm() == 0.0);
  CHECK(wide.rightCols(5).norm() == 0.0);
}

TEST_CASE("calls from several threads at once give what each call gives alone") {
  // OpenBLAS's single-threaded build shares its work buffers between
  // threads that call it at once (lapack.cpp, BlasTurn): without the turn,
  // four threads of dgees on this matrix got forms off by up to 34 in 1 to
  // 24 calls of 80. Here real Schur forms and products run together from
  // four threads and each must equal the lone call's to the bit: as the
  // library starts, and with one thread per call (the command line's
  // setting, under which OpenBLAS's threaded build runs the calls at once).
  const MatrixXd a = Gaussian(300, 300, 31), b = Gaussian(300, 300, 32);
  const auto together = [&](int* differing_forms, int* differing_products) {
    const deb::RealSchurForm alone = deb::RealSchur(a);
    MatrixXd product_alone(300, 300);
    deb::BlasProduct(a, b, product_alone);
    constexpr int kThreads = 4, kCalls = 12;
    std::atomic<int> forms{0}, products{0};
    std::vector<std::thread> threads;
    for (int k = 0; k < kThreads; ++k)
      threads.emplace_back([&, k] {
        for (int call = 0; call < kCalls; ++call) {
          if ((call + k) % 2 == 0) {
            const deb::RealSchurForm form = deb::RealSchur(a);
            if (form.t != alone.t || form.u != alone.u) ++forms;
          } else {
            MatrixXd product(300, 300);
            deb::BlasProduct(a, b, product);
            if (product != product_alone) ++products;
          }
        }
      });
    for (std::thread& t : threads) t.join();
    *differing_forms = forms.load();
    *differing_products = products.load();
  };
  int forms = -1, products = -1;
  together(&forms, &products);
  CHECK(forms == 0);
  CHECK(products == 0);
  deb::UseOneBlasThreadPerCall();
  together(&forms, &products);
  CHECK(forms == 0);
  CHECK(products == 0);
}
