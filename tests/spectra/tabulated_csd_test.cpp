#include "deb/spectra/tabulated_csd.h"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

using Complex = std::complex<double>;

// Rows of S_ab in column a + n b, from one matrix per frequency.
Eigen::MatrixXcd Pack(const std::vector<Eigen::MatrixXcd>& nodes) {
  const Eigen::Index n = nodes.front().rows();
  Eigen::MatrixXcd table(static_cast<Eigen::Index>(nodes.size()), n * n);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (Eigen::Index b = 0; b < n; ++b)
      for (Eigen::Index a = 0; a < n; ++a) table(static_cast<Eigen::Index>(i), a + n * b) = nodes[i](a, b);
  return table;
}

// G G^H for a random complex G with `rank` columns: Hermitian, PSD, rank-deficient if rank < n.
Eigen::MatrixXcd RandomCsd(std::mt19937_64& rng, int n, int rank, double level) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXcd g(n, rank);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < rank; ++j) g(i, j) = Complex(normal(rng), normal(rng));
  return level * g * g.adjoint();
}

double SmallestEigenvalue(const Eigen::MatrixXcd& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>(m, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}

struct Table {
  std::vector<double> f_hz;
  std::vector<Eigen::MatrixXcd> nodes;
};

// Three channels at five frequencies: full rank, rank 1 (fully coherent),
// a channel with zero PSD (and no cross terms), levels over 6 decades.
Table ThreeChannels() {
  std::mt19937_64 rng(11);
  Table t;
  t.f_hz = {0.5, 2.0, 7.0, 40.0, 300.0};
  t.nodes = {RandomCsd(rng, 3, 3, 1.0), RandomCsd(rng, 3, 1, 1e-2), RandomCsd(rng, 3, 2, 1e-4),
             RandomCsd(rng, 3, 3, 1e-5), RandomCsd(rng, 3, 3, 1e-6)};
  t.nodes[2].row(1).setZero();
  t.nodes[2].col(1).setZero();
  return t;
}

TEST_CASE("a tabulated CSD returns its table exactly at the nodes") {
  const Table t = ThreeChannels();
  const TabulatedCsd s(t.f_hz, 3, Pack(t.nodes));
  CHECK(s.channels() == 3);
  CHECK_FALSE(s.IsDiagonal());
  CHECK(s.channel_names() == std::vector<std::string>{"ch1", "ch2", "ch3"});
  for (std::size_t i = 0; i < t.f_hz.size(); ++i) {
    CAPTURE(t.f_hz[i]);
    const Eigen::MatrixXcd csd = s.Csd(t.f_hz[i]);
    for (int b = 0; b < 3; ++b) {
      CHECK(csd(b, b) == Complex(t.nodes[i](b, b).real(), 0.0));
      CHECK(s.Psd(t.f_hz[i])(b) == t.nodes[i](b, b).real());
      for (int a = 0; a < b; ++a) {
        CHECK(csd(a, b) == t.nodes[i](a, b));
        CHECK(csd(b, a) == std::conj(t.nodes[i](a, b)));
      }
    }
  }
}

TEST_CASE("between nodes every matrix is Hermitian and positive semi-definite (1e-12 of its norm), autos log-log") {
  const Table t = ThreeChannels();
  const TabulatedCsd s(t.f_hz, 3, Pack(t.nodes));
  Eigen::MatrixXd autos(5, 3);
  for (int i = 0; i < 5; ++i) autos.row(i) = t.nodes[static_cast<std::size_t>(i)].diagonal().real().transpose();
  const MeasuredSpectrum diagonal(t.f_hz, autos);
  for (int k = 0; k <= 600; ++k) {
    const double f = 0.5 * std::pow(600.0, k / 600.0);  // 0.5-300 Hz
    CAPTURE(f);
    const Eigen::MatrixXcd csd = s.Csd(f);
    const double scale = csd.norm();
    CHECK((csd - csd.adjoint()).norm() == 0.0);
    CHECK(SmallestEigenvalue(csd) >= -1e-12 * scale);
    CHECK((csd.diagonal().real() - diagonal.Psd(f)).norm() <= 1e-15 * scale);
    CHECK((s.Psd(f) - diagonal.Psd(f)).norm() == 0.0);
    // Coherency bounded by 1 for every pair.
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < b; ++a) CHECK(std::norm(csd(a, b)) <= csd(a, a).real() * csd(b, b).real() * (1 + 1e-12));
  }
}

TEST_CASE("the coherency is interpolated linearly in log f and the autos log-log: a closed form at mid-decade") {
  // Channel a: 1/f; b: 4/f^2; coherency 0.8 at 1 Hz, 0.2j at 10 Hz.
  const std::vector<double> f_hz = {1.0, 10.0};
  std::vector<Eigen::MatrixXcd> nodes(2, Eigen::MatrixXcd(2, 2));
  const Complex c0(0.8, 0.0), c1(0.0, 0.2);
  for (int i = 0; i < 2; ++i) {
    const double f = f_hz[static_cast<std::size_t>(i)];
    const double saa = 1.0 / f, sbb = 4.0 / (f * f);
    const Complex c = i == 0 ? c0 : c1;
    nodes[static_cast<std::size_t>(i)] << saa, std::sqrt(saa * sbb) * c, std::sqrt(saa * sbb) * std::conj(c), sbb;
  }
  const TabulatedCsd s(f_hz, 2, Pack(nodes));
  const double f = std::sqrt(10.0);  // t = 1/2
  const Eigen::MatrixXcd csd = s.Csd(f);
  CHECK(csd(0, 0).real() == doctest::Approx(1.0 / f).epsilon(1e-14));
  CHECK(csd(1, 1).real() == doctest::Approx(4.0 / (f * f)).epsilon(1e-14));
  const Complex expected = std::sqrt(4.0 / (f * f * f)) * 0.5 * (c0 + c1);
  CHECK(std::abs(csd(0, 1) - expected) <= 1e-14 * std::abs(expected));
}

TEST_CASE("outside the table: an error naming the range, zero, or the end matrix held") {
  const Table t = ThreeChannels();
  CHECK(InputErrorText([&] { TabulatedCsd(t.f_hz, 3, Pack(t.nodes)).Csd(400.0); })
            .find("frequency 400 Hz is outside the data range 0.5-300 Hz") != std::string::npos);
  TabulatedCsdOptions zero;
  zero.extrapolation = Extrapolation::kZero;
  CHECK(TabulatedCsd(t.f_hz, 3, Pack(t.nodes), zero).Csd(0.1).norm() == 0.0);
  TabulatedCsdOptions hold;
  hold.extrapolation = Extrapolation::kHold;
  const TabulatedCsd held(t.f_hz, 3, Pack(t.nodes), hold);
  CHECK(held.Csd(0.1) == held.Csd(0.5));
  CHECK(held.Csd(1000.0) == held.Csd(300.0));
  CHECK(held.BreakpointsHz() == t.f_hz);  // every data point
}

TEST_CASE("a table that is not Hermitian, not positive semi-definite or misshapen is rejected, naming entry and frequency") {
  Table t = ThreeChannels();
  TabulatedCsdOptions named;
  named.channel_names = {"x", "y", "z"};
  named.origin = "floor.csv";
  Eigen::MatrixXcd table = Pack(t.nodes);
  table(3, 2 + 3 * 0) += Complex(0.0, 1e-3);  // S(z, x) at 40 Hz no longer conj(S(x, z))
  const std::string hermitian = InputErrorText([&] { TabulatedCsd(t.f_hz, 3, table, named); });
  CHECK(hermitian.find("cross-spectral table 'floor.csv': S(x, z) = ") == 0);
  CHECK(hermitian.find(" at 40 Hz; the matrix must be Hermitian") != std::string::npos);

  // |coherency| 1.5 between two channels.
  std::vector<Eigen::MatrixXcd> bad(2, Eigen::MatrixXcd(2, 2));
  bad[0] << 1.0, 0.5, 0.5, 1.0;
  bad[1] << 1.0, Complex(0.0, 1.5), Complex(0.0, -1.5), 1.0;
  const std::string psd = InputErrorText([&] { TabulatedCsd({1.0, 2.0}, 2, Pack(bad)); });
  CHECK(psd.find("the matrix at 2 Hz is not positive semi-definite: its coherency matrix has eigenvalue -0.5 "
                 "(|coherency| = 1.5 > 1)") != std::string::npos);

  // Three channels pairwise coherent 0.9, 0.9, -0.9: each pair is fine, the whole is not.
  std::vector<Eigen::MatrixXcd> triple(2, Eigen::MatrixXcd::Identity(3, 3));
  triple[1] << 1.0, 0.9, 0.9, 0.9, 1.0, -0.9, 0.9, -0.9, 1.0;
  CHECK(InputErrorText([&] { TabulatedCsd({1.0, 2.0}, 3, Pack(triple)); }).find("not positive semi-definite") !=
        std::string::npos);

  // A cross term where a channel has no power.
  std::vector<Eigen::MatrixXcd> dead(2, Eigen::MatrixXcd::Identity(2, 2));
  dead[0](1, 1) = 0.0;
  dead[0](0, 1) = dead[0](1, 0) = 1e-20;
  CHECK(InputErrorText([&] { TabulatedCsd({1.0, 2.0}, 2, Pack(dead)); }).find("but a channel's PSD is 0 there") !=
        std::string::npos);

  std::vector<Eigen::MatrixXcd> complex_auto(2, Eigen::MatrixXcd::Identity(2, 2));
  complex_auto[1](1, 1) = Complex(1.0, 0.1);
  CHECK(InputErrorText([&] { TabulatedCsd({1.0, 2.0}, 2, Pack(complex_auto)); })
            .find("the auto-PSD of channel 2 at 2 Hz is 1 + 0.1j; an auto-PSD must be real") != std::string::npos);

  CHECK(InputErrorText([&] { TabulatedCsd({1.0, 2.0}, 3, Pack(bad)); }).find("expected 2 rows (one per frequency) and 9") !=
        std::string::npos);
  CHECK(InputErrorText([&] { TabulatedCsd({2.0, 1.0}, 2, Pack(bad)); }).find("must increase strictly") !=
        std::string::npos);
  std::vector<Eigen::MatrixXcd> negative(2, Eigen::MatrixXcd::Identity(2, 2));
  negative[0](0, 0) = -1.0;
  CHECK(InputErrorText([&] { TabulatedCsd({1.0, 2.0}, 2, Pack(negative)); }).find("must be finite and >= 0") !=
        std::string::npos);
}

TEST_CASE("Describe names the origin, channels, points, interpolation and extrapolation") {
  const Table t = ThreeChannels();
  TabulatedCsdOptions o;
  o.channel_names = {"x", "y", "z"};
  o.origin = "rec.csv";
  o.unit = "um/s";
  CHECK(TabulatedCsd(t.f_hz, 3, Pack(t.nodes), o).Describe() ==
        "cross-spectral 'rec.csv', 3 channels (x, y, z), 5 points 0.5-300 Hz, auto-PSDs log-log, coherency linear "
        "in log f, extrapolation error; CSD in (um/s)^2/Hz");
}


TEST_CASE("with bins, the matrix is the node's across its bin, and the bin edges are the breakpoints") {
  const Table t = ThreeChannels();
  TabulatedCsdOptions o;
  o.interpolation = SpectrumInterpolation::kBins;
  const TabulatedCsd s(t.f_hz, 3, Pack(t.nodes), o);
  CHECK(s.Csd(1.2) == s.Csd(0.5));    // bin of 0.5 Hz: 0.5 - 0.75 ... 1.25 Hz
  CHECK(s.Csd(1.3) == s.Csd(2.0));    // bin of 2 Hz: 1.25-4.5 Hz
  CHECK(s.Csd(400.0) == s.Csd(300.0));  // the last bin reaches 300 + 130 Hz
  CHECK(s.BreakpointsHz() == std::vector<double>{0.25, 1.25, 4.5, 23.5, 170.0, 430.0});
  CHECK(s.Csd(2.5)(0, 0).real() == s.Psd(2.5)(0));
  CHECK_THROWS_AS(s.Csd(431.0), InputError);
}

}  // namespace
}  // namespace deb
