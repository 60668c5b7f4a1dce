// Modal-form evaluation and the closed-form modal covariance against two
// independent computations: the 2n-state realisation (ModalStateSpace) through
// FrequencyResponse and the Lyapunov solver, and the closed form of one mode.
#include "deb/systems/modal_response.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/lyapunov.h"
#include "test_util.h"

namespace deb {
namespace {

using testing::Contains;
using testing::MessageOf;

constexpr double kTwoPi = 6.283185307179586476925286766559;

// n modes log-spaced over 5-500 Hz with every third mode doubled 0.3 % above
// it, zeta from 1e-3 to 3e-2, m inputs and p outputs of random shapes.
ModalModel Clustered(int n, int m, int p, ModalQuantity q, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ModalModel model;
  for (int k = 0; k < n; ++k) {
    const double f = k % 3 == 1 ? model.f_hz.back() * 1.003 : 5.0 * std::pow(100.0, k / (n - 1.0));
    model.f_hz.push_back(f);
    model.zeta.push_back(1e-3 * std::pow(30.0, (k % 5) / 4.0));
  }
  model.phi_in.resize(m, n);
  model.phi_out.resize(p, n);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < m; ++i) model.phi_in(i, k) = u(rng);
    for (int i = 0; i < p; ++i) model.phi_out(i, k) = u(rng);
  }
  for (int i = 0; i < m; ++i) model.input_names.push_back("F" + std::to_string(i + 1));
  for (int i = 0; i < p; ++i) model.output_names.push_back("y" + std::to_string(i + 1));
  model.quantity = q;
  return model;
}

TEST_CASE("modal form equals the 2n-state realisation at every frequency, all three quantities") {
  for (ModalQuantity q : {ModalQuantity::kDisplacement, ModalQuantity::kVelocity, ModalQuantity::kAcceleration}) {
    CAPTURE(ToString(q));
    const ModalModel model = Clustered(30, 4, 3, q);
    const std::vector<int> rows = {2, 0};
    const ModalResponse modal(model, rows);
    const FrequencyResponse dense(ModalStateSpace(model).SelectOutputs(rows));
    CHECK(modal.outputs() == 2);
    CHECK(modal.inputs() == 4);
    std::vector<double> f;
    for (int i = 0; i < 700; ++i) f.push_back(0.5 * std::pow(1e4, i / 699.0));
    for (double fk : model.f_hz) f.push_back(fk);  // on the peaks
    double worst = 0.0;
    std::vector<Eigen::MatrixXcd> from_foreach(f.size());
    modal.ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& h) { from_foreach[k] = h; }, 2);
    for (std::size_t i = 0; i < f.size(); ++i) {
      const Eigen::MatrixXcd a = modal.At(f[i]), b = dense.At(f[i]);
      worst = std::max(worst, (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff());
      // ForEach evaluates in blocks by the same arithmetic: equal to rounding.
      CHECK((from_foreach[i] - a).cwiseAbs().maxCoeff() <= 1e-13 * a.cwiseAbs().maxCoeff());
    }
    // Observed 2e-13 (the dense form carries the eigenvector rounding).
    CHECK(worst < 1e-10);
  }
}

TEST_CASE("the pair form and the row form give the same H, static residual included") {
  // Two orders of the same sums: equal to rounding (observed 1e-15 of the
  // largest entry of H; 1e-13 allowed), in ForEach's blocks and in At().
  ModalModel model = Clustered(120, 5, 4, ModalQuantity::kDisplacement, 13);
  model.residual = Eigen::MatrixXd::Constant(4, 5, 1e-6);
  model.residual(2, 3) = -3e-6;
  const std::vector<int> rows = {3, 1, 1};
  const ModalResponse pairs(model, rows), by_rows(model, rows, ModalResponse::Form::kRows);
  std::vector<double> f;
  for (int i = 0; i < 1500; ++i) f.push_back(0.5 * std::pow(1e4, i / 1499.0));
  for (double fk : model.f_hz) f.push_back(fk);
  std::vector<Eigen::MatrixXcd> a(f.size()), b(f.size());
  pairs.ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& h) { a[k] = h; }, 2);
  by_rows.ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& h) { b[k] = h; }, 2);
  double worst = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    REQUIRE(a[k].rows() == 3);
    REQUIRE(a[k].cols() == 5);
    const double scale = b[k].cwiseAbs().maxCoeff();
    worst = std::max(worst, (a[k] - b[k]).cwiseAbs().maxCoeff() / scale);
    worst = std::max(worst, (pairs.At(f[k]) - b[k]).cwiseAbs().maxCoeff() / scale);
  }
  CHECK(worst <= 1e-13);
  // At 0 Hz only the modes' static parts and the residual remain.
  const Eigen::MatrixXcd h0 = pairs.At(0.0);
  CHECK(std::abs(h0(0, 3) - by_rows.At(0.0)(0, 3)) <= 1e-13 * std::abs(h0(0, 3)));
}

TEST_CASE("the pair form of many channels and few modes takes smaller blocks, with the same H") {
  // 150 x 120 pairs: blocks of 58 frequencies (16 MB per worker), not 128.
  const ModalModel model = Clustered(4, 120, 150, ModalQuantity::kVelocity, 17);
  std::vector<int> rows(150);
  for (int r = 0; r < 150; ++r) rows[static_cast<std::size_t>(r)] = r;
  const ModalResponse pairs(model, rows), by_rows(model, rows, ModalResponse::Form::kRows);
  std::vector<double> f;
  for (int i = 0; i < 200; ++i) f.push_back(0.5 * std::pow(1e4, i / 199.0));
  std::vector<Eigen::MatrixXcd> a(f.size()), b(f.size());
  pairs.ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& h) { a[k] = h; }, 2);
  by_rows.ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& h) { b[k] = h; }, 2);
  double worst = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k)
    worst = std::max(worst, (a[k] - b[k]).cwiseAbs().maxCoeff() / b[k].cwiseAbs().maxCoeff());
  CHECK(worst <= 1e-13);
}

TEST_CASE("ForEach gives bit-identical responses on 1, 2 and 3 threads") {
  // 200 modes and one output make blocks of 256 frequencies. With 2562
  // frequencies a block cut where a thread's range ends left a block of one
  // frequency, whose product Eigen evaluates as a matrix-vector product,
  // summed in another order: before the fix 3 (2 threads) and 4 (3 threads)
  // frequencies differed in their last digits from 1 thread (as the
  // metrology frame's CSVs did).
  // The pair form's blocks are of 128 frequencies: 2562 leaves a last block
  // of 2, checked in the same way.
  const ModalModel model = Clustered(200, 3, 1, ModalQuantity::kDisplacement, 11);
  for (const ModalResponse::Form form : {ModalResponse::Form::kAuto, ModalResponse::Form::kRows}) {
    CAPTURE(static_cast<int>(form));
    const ModalResponse modal(model, {0}, form);
    std::vector<double> f;
    for (int i = 0; i < 2562; ++i) f.push_back(0.5 * std::pow(1e4, i / 2561.0));
    const auto run = [&](int threads) {
      std::vector<Eigen::MatrixXcd> h(f.size());
      modal.ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& hk) { h[k] = hk; }, threads);
      return h;
    };
    const std::vector<Eigen::MatrixXcd> one = run(1);
    for (const int threads : {2, 3}) {
      CAPTURE(threads);
      const std::vector<Eigen::MatrixXcd> other = run(threads);
      std::size_t differing = 0;
      for (std::size_t k = 0; k < f.size(); ++k)
        if (!(other[k].array() == one[k].array()).all()) ++differing;
      CHECK(differing == 0);
    }
  }
}

TEST_CASE("modal covariance equals the Lyapunov solution of the realisation, and the shares add up") {
  for (ModalQuantity q : {ModalQuantity::kDisplacement, ModalQuantity::kVelocity}) {
    CAPTURE(ToString(q));
    const ModalModel model = Clustered(24, 3, 2, q);
    // Correlated inputs: W = L L^T.
    Eigen::MatrixXd l(3, 3);
    l << 1.0, 0.0, 0.0, 0.4, 0.8, 0.0, -0.3, 0.2, 0.5;
    const Eigen::MatrixXd w = l * l.transpose();
    const ModalCovariance modal = ModalOutputCovariance(model, {0, 1}, w);
    const Eigen::MatrixXd lyap = OutputCovariance(ModalStateSpace(model), w);
    for (int r = 0; r < 2; ++r) {
      CAPTURE(r);
      // The Lyapunov solver is accurate to 1e-12 here; observed 1e-13.
      CHECK(modal.variance(r) == doctest::Approx(lyap(r, r)).epsilon(1e-9));
      CHECK(modal.share.row(r).sum() == doctest::Approx(modal.variance(r)).epsilon(1e-12));
    }
  }
}

TEST_CASE("modal covariance matrix equals the Lyapunov covariance of the realisation, cross terms included") {
  for (ModalQuantity q : {ModalQuantity::kDisplacement, ModalQuantity::kVelocity}) {
    CAPTURE(ToString(q));
    const ModalModel model = Clustered(24, 3, 4, q, 11);
    Eigen::MatrixXd l(3, 3);
    l << 1.0, 0.0, 0.0, 0.4, 0.8, 0.0, -0.3, 0.2, 0.5;
    const Eigen::MatrixXd w = l * l.transpose();
    const std::vector<int> rows = {3, 0, 2, 0};  // out of order, one row twice
    const Eigen::MatrixXd modal = ModalOutputCovarianceMatrix(model, rows, w);
    const Eigen::MatrixXd lyap = OutputCovariance(ModalStateSpace(model).SelectOutputs(rows), w);
    const ModalCovariance own = ModalOutputCovariance(model, rows, w);
    REQUIRE(modal.rows() == 4);
    REQUIRE(modal.cols() == 4);
    CHECK(modal == modal.transpose());
    double worst = 0.0;
    for (Eigen::Index a = 0; a < 4; ++a) {
      CHECK(modal(a, a) == own.variance(a));  // the variances, to the bit
      for (Eigen::Index b = 0; b < 4; ++b) {
        // Relative to the pair's scale sqrt(C_aa C_bb): a cross term may be
        // small where the outputs are nearly uncorrelated.
        const double scale = std::sqrt(lyap(a, a) * lyap(b, b));
        worst = std::max(worst, std::abs(modal(a, b) - lyap(a, b)) / scale);
      }
    }
    CHECK(worst < 1e-9);
    // The repeated row: its cross term with itself is its variance.
    CHECK(modal(1, 3) == doctest::Approx(modal(1, 1)).epsilon(1e-13));
    // Correlated outputs, not a diagonal matrix: the test can tell.
    CHECK(std::abs(modal(0, 1)) > 1e-3 * std::sqrt(modal(0, 0) * modal(1, 1)));
  }
}

TEST_CASE("ten clustered modes at zeta 1e-3: the closed form matches the block-triangular Lyapunov solve") {
  // The cascade case of the exact-variance tests, here as ten modes of one
  // structure at 10 (1 + 0.03 k) Hz, one input, one output.
  ModalModel model;
  for (int k = 0; k < 10; ++k) {
    model.f_hz.push_back(10.0 * (1.0 + 0.03 * k));
    model.zeta.push_back(1e-3);
  }
  model.phi_in = Eigen::RowVectorXd::LinSpaced(10, 0.2, 1.1);
  model.phi_out = Eigen::RowVectorXd::LinSpaced(10, -1.0, 0.7);
  model.input_names = {"F"};
  model.output_names = {"z"};
  const Eigen::MatrixXd w = Eigen::MatrixXd::Constant(1, 1, 0.5);
  const double modal = ModalOutputCovariance(model, {0}, w).variance(0);
  const double lyap = OutputCovariance(ModalStateSpace(model), w)(0, 0);
  CHECK(modal == doctest::Approx(lyap).epsilon(1e-9));
}

TEST_CASE("one mode: the closed form W phi^2 / (4 zeta w^3), and W phi^2 / (4 zeta w) for the velocity") {
  ModalModel model;
  model.f_hz = {42.0};
  model.zeta = {0.02};
  model.phi_in = Eigen::MatrixXd::Constant(1, 1, 0.31);
  model.phi_out = Eigen::MatrixXd::Constant(1, 1, -0.7);
  model.input_names = {"F"};
  model.output_names = {"z"};
  const double w = kTwoPi * 42.0, phi2 = 0.31 * 0.31 * 0.7 * 0.7, intensity = 1.25;
  const Eigen::MatrixXd wm = Eigen::MatrixXd::Constant(1, 1, intensity);
  CHECK(ModalOutputCovariance(model, {0}, wm).variance(0) ==
        doctest::Approx(intensity * phi2 / (4 * 0.02 * w * w * w)).epsilon(1e-13));
  model.quantity = ModalQuantity::kVelocity;
  CHECK(ModalOutputCovariance(model, {0}, wm).variance(0) ==
        doctest::Approx(intensity * phi2 / (4 * 0.02 * w)).epsilon(1e-13));
}

TEST_CASE("modal covariance refuses what has no finite variance, and bad W") {
  ModalModel model = Clustered(4, 2, 1, ModalQuantity::kDisplacement);
  const Eigen::MatrixXd w = Eigen::MatrixXd::Identity(2, 2);
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(model, {0}, Eigen::MatrixXd::Identity(3, 3)); }),
                 "the model has 2 input(s)"));
  Eigen::MatrixXd asym = w;
  asym(0, 1) = 0.5;
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(model, {0}, asym); }), "not symmetric"));
  model.quantity = ModalQuantity::kAcceleration;
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(model, {0}, w); }), "infinite variance"));
  model.quantity = ModalQuantity::kDisplacement;
  model.f_hz[0] = 0.0;  // a rigid-body mode
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(model, {0}, w); }), "rigid-body mode"));
  // ... whose response is finite above 0 Hz and refused at 0 Hz.
  const ModalResponse r(model, {0});
  CHECK(std::isfinite(std::abs(r.At(0.1)(0, 0))));
  CHECK(Contains(MessageOf([&] { r.At(0.0); }), "coincides with a pole"));
  CHECK(Contains(MessageOf([&] { r.At(NAN); }), "not finite"));
}

TEST_CASE("modes that cancel at an output: a variance below its rounding is refused, not printed") {
  // Two identical modes with opposite output shapes: the output sees nothing
  // but rounding; with a 1e-7 difference, a variance 1e-14 of the terms,
  // below their rounding bound; with 1e-2 the variance is trusted.
  ModalModel model;
  model.f_hz = {30.0, 30.0};
  model.zeta = {0.01, 0.01};
  model.phi_in = Eigen::RowVector2d(1.0, 1.0);
  model.phi_out = Eigen::RowVector2d(1.0, -1.0);
  model.input_names = {"F"};
  model.output_names = {"z"};
  const Eigen::MatrixXd w = Eigen::MatrixXd::Identity(1, 1);
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(model, {0}, w); }), "not reliable"));
  model.phi_out(0, 1) = -1.0 + 1e-7;
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(model, {0}, w); }), "not reliable"));
  model.phi_out(0, 1) = -1.0 + 1e-2;
  const double w0 = kTwoPi * 30.0;
  CHECK(ModalOutputCovariance(model, {0}, w).variance(0) ==
        doctest::Approx(1e-4 / (4 * 0.01 * w0 * w0 * w0)).epsilon(1e-9));
}

}  // namespace
}  // namespace deb

namespace deb {
namespace {

TEST_CASE("residual: static keeps the static response of the dropped modes, exactly at 0 Hz") {
  ModalModel full;
  full.f_hz = {10.0, 200.0};
  full.zeta = {0.02, 0.01};
  full.phi_in = Eigen::RowVector2d(0.5, 0.8);
  full.phi_out = Eigen::RowVector2d(1.0, -0.6);
  full.input_names = {"F"};
  full.output_names = {"z"};
  const ModalModel plain = full.Truncated(50.0), corrected = full.Truncated(50.0, true);
  REQUIRE(corrected.modes() == 1);
  const double w2 = kTwoPi * 200.0, dropped = -0.6 * 0.8 / (w2 * w2);  // the dropped mode's static compliance
  REQUIRE(corrected.residual.size() == 1);
  CHECK(corrected.residual(0, 0) == doctest::Approx(dropped).epsilon(1e-15));
  const ModalResponse h_full(full, {0}), h_plain(plain, {0}), h_corrected(corrected, {0});
  for (double f : {1e-3, 1.0, 5.0}) {
    CAPTURE(f);
    const std::complex<double> a = h_full.At(f)(0, 0), b = h_corrected.At(f)(0, 0), c = h_plain.At(f)(0, 0);
    // The dropped mode's dynamic part: 2 zeta (f / 200 Hz) + (f / 200 Hz)^2 of its static one.
    const double r = f / 200.0;
    CHECK(std::abs(a - b) <= 1.1 * (2 * 0.01 * r + r * r) * std::abs(dropped));
    CHECK(std::abs(a - c) == doctest::Approx(std::abs(dropped)).epsilon(2 * (2 * 0.01 * r + r * r) + 1e-9));
  }
  // The realisation carries it as D, and the exact variance is refused.
  const FrequencyResponse dense(ModalStateSpace(corrected));
  CHECK(std::abs(dense.At(3.0)(0, 0) - h_corrected.At(3.0)(0, 0)) <= 1e-12 * std::abs(h_corrected.At(3.0)(0, 0)));
  CHECK(Contains(MessageOf([&] { ModalOutputCovariance(corrected, {0}, Eigen::MatrixXd::Identity(1, 1)); }),
                 "static residual"));
  full.quantity = ModalQuantity::kVelocity;
  CHECK(Contains(MessageOf([&] { full.Truncated(50.0, true); }), "needs output_quantity: displacement"));
}

}  // namespace
}  // namespace deb
