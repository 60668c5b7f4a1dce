#include "deb/spectra/channel_set.h"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/vc_curve.h"

namespace deb {
namespace {

using SpectrumPtr = std::shared_ptr<const Spectrum>;

// Three independent channels with different levels: 1, 4, 9 (white).
std::shared_ptr<const IndependentChannels> ThreeWhite() {
  return std::make_shared<IndependentChannels>(std::vector<SpectrumPtr>{
      std::make_shared<FlatSpectrum>(1.0), std::make_shared<FlatSpectrum>(4.0), std::make_shared<FlatSpectrum>(9.0)});
}

TEST_CASE("independent channels stack the parts' PSDs on a block diagonal") {
  const IndependentChannels set({std::make_shared<FlatSpectrum>(2.0),
                                 std::make_shared<VcSpectrum>(VcClass::kD, VcOptions::ThesisModified()),
                                 std::make_shared<FlatSpectrum>(5.0, 1.0, 20.0)});
  CHECK(set.channels() == 3);
  CHECK(set.IsDiagonal());
  const double f_hz = 10.0;
  const Eigen::MatrixXcd csd = set.Csd(f_hz);
  const Eigen::VectorXd psd = set.Psd(f_hz);
  CHECK(psd(0) == 2.0);
  CHECK(psd(1) == VcSpectrum(VcClass::kD, VcOptions::ThesisModified()).Psd(f_hz)(0));
  CHECK(psd(2) == 5.0);
  CHECK(csd.real().diagonal() == psd);
  CHECK(csd.imag().isZero(0.0));
  CHECK((csd.real() - Eigen::MatrixXd(psd.asDiagonal())).isZero(0.0));
}

TEST_CASE("independent channels' breakpoints are the sorted union and the white level needs every part white") {
  const IndependentChannels mixed({std::make_shared<FlatSpectrum>(1.0, 3.0, 30.0),
                                   std::make_shared<FlatSpectrum>(1.0, 3.0, 50.0)});
  CHECK(mixed.BreakpointsHz() == std::vector<double>{3.0, 30.0, 50.0});
  CHECK_FALSE(mixed.WhiteLevel().has_value());
  const auto white = ThreeWhite()->WhiteLevel();
  REQUIRE(white.has_value());
  CHECK(*white == Eigen::Vector3d(1.0, 4.0, 9.0).asDiagonal().toDenseMatrix());
  CHECK_THROWS_AS(IndependentChannels({}), InputError);
}

TEST_CASE("correlated channels follow S_ij = rho_ij sqrt(S_ii S_jj) (rel 1e-15)") {
  Eigen::Matrix3d rho;
  rho << 1.0, 0.5, -0.2, 0.5, 1.0, 0.3, -0.2, 0.3, 1.0;
  const CorrelatedChannels correlated(ThreeWhite(), rho);
  const Eigen::MatrixXcd csd = correlated.Csd(7.0);
  const double s[] = {1.0, 4.0, 9.0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      CHECK(csd(i, j).real() == doctest::Approx(rho(i, j) * std::sqrt(s[i] * s[j])).epsilon(1e-15));
      CHECK(csd(i, j).imag() == 0.0);
    }
  }
  CHECK(correlated.Psd(7.0) == Eigen::Vector3d(1.0, 4.0, 9.0));
  CHECK_FALSE(correlated.IsDiagonal());
  // White base: the white level is rho o sqrt(d d^T), the same matrix.
  REQUIRE(correlated.WhiteLevel().has_value());
  CHECK(correlated.WhiteLevel()->isApprox(csd.real(), 1e-15));
}

TEST_CASE("fully coherent channels (rho = 1 everywhere) give a rank-1 CSD (abs 1e-12 x trace)") {
  const CorrelatedChannels coherent(ThreeWhite(), Eigen::Matrix3d::Ones());
  const Eigen::MatrixXd csd = coherent.Csd(1.0).real();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(csd);
  const double trace = csd.trace();
  CHECK(eigen.eigenvalues()(2) == doctest::Approx(trace).epsilon(1e-12));
  CHECK(std::abs(eigen.eigenvalues()(0)) <= 1e-12 * trace);
  CHECK(std::abs(eigen.eigenvalues()(1)) <= 1e-12 * trace);
}

TEST_CASE("a correlated CSD is Hermitian and positive semi-definite for any valid coherence (abs 1e-12)") {
  // rho from a Gram matrix of unit vectors is a valid coherence matrix.
  Eigen::MatrixXd vectors(4, 3);
  vectors << 1, 2, 0.5, -1, 0.3, 2, 0.7, -0.4, 1, 0.2, 0.1, -3;
  for (int i = 0; i < 4; ++i) vectors.row(i).normalize();
  Eigen::MatrixXd rho = vectors * vectors.transpose();
  rho = 0.5 * (rho + rho.transpose());
  rho.diagonal().setOnes();
  const auto base = std::make_shared<IndependentChannels>(std::vector<SpectrumPtr>{
      std::make_shared<VcSpectrum>(VcClass::kC, VcOptions::ThesisModified()),
      std::make_shared<FlatSpectrum>(3.0), std::make_shared<FlatSpectrum>(0.5, 1.0, 10.0),
      std::make_shared<FlatSpectrum>(2.0)});
  const CorrelatedChannels correlated(base, rho);
  for (double f_hz : {0.6, 1.0, 5.0, 30.0, 200.0}) {
    const Eigen::MatrixXcd csd = correlated.Csd(f_hz);
    CHECK((csd - csd.adjoint()).norm() <= 1e-12 * csd.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eigen(csd);
    CHECK(eigen.eigenvalues().minCoeff() >= -1e-12 * csd.norm());
  }
  CHECK(correlated.BreakpointsHz() == base->BreakpointsHz());
}

TEST_CASE("a coherence matrix that is not positive semi-definite is rejected naming the eigenvalue") {
  Eigen::Matrix3d rho;  // pairwise fine, jointly impossible: 1~2, 1~3 but 2 anti 3
  rho << 1.0, 0.9, 0.9, 0.9, 1.0, -0.9, 0.9, -0.9, 1.0;
  const std::string message = InputErrorText([&] { CorrelatedChannels(ThreeWhite(), rho); });
  const std::string key = "not positive semi-definite: eigenvalue ";
  const std::size_t at = message.find(key);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(message.substr(at + key.size())) == doctest::Approx(-0.8).epsilon(1e-12));
  CHECK(message.find("channels 1, 2, 3") != std::string::npos);
}

TEST_CASE("a coherence matrix with a bad entry is rejected naming the entry and value") {
  Eigen::Matrix3d rho = Eigen::Matrix3d::Identity();
  rho(1, 1) = 0.9;
  CHECK(InputErrorText([&] { CorrelatedChannels(ThreeWhite(), rho); }).find("coherence(row 2, column 2) = 0.9") !=
        std::string::npos);
  rho = Eigen::Matrix3d::Identity();
  rho(0, 2) = 0.4;
  CHECK(InputErrorText([&] { CorrelatedChannels(ThreeWhite(), rho); }).find("symmetric") != std::string::npos);
  rho(2, 0) = 0.4;
  CHECK_NOTHROW(CorrelatedChannels(ThreeWhite(), rho));
  rho(0, 1) = rho(1, 0) = 1.2;
  CHECK(InputErrorText([&] { CorrelatedChannels(ThreeWhite(), rho); }).find("1.2; coherences must lie in [-1, 1]") !=
        std::string::npos);
  rho(0, 1) = rho(1, 0) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(CorrelatedChannels(ThreeWhite(), rho), InputError);
  CHECK(InputErrorText([&] { CorrelatedChannels(ThreeWhite(), Eigen::Matrix2d::Identity()); })
            .find("must be 3 x 3") != std::string::npos);
}

TEST_CASE("coherence applies to independent channels only") {
  Eigen::Matrix3d rho = Eigen::Matrix3d::Ones();
  const auto correlated = std::make_shared<CorrelatedChannels>(ThreeWhite(), rho);
  CHECK(InputErrorText([&] { CorrelatedChannels(correlated, rho); }).find("already has cross terms") !=
        std::string::npos);
}

TEST_CASE("identity coherence leaves the channels independent and the CSD equal to the base's") {
  const CorrelatedChannels same(ThreeWhite(), Eigen::Matrix3d::Identity());
  CHECK(same.IsDiagonal());
  CHECK(same.Csd(2.0) == ThreeWhite()->Csd(2.0));
}

}  // namespace
}  // namespace deb
