// The Spectrum contract, checked for every kind of source: shapes, Hermitian
// and positive semi-definite CSD, Psd = diag(Csd), honest IsDiagonal and
// WhiteLevel, valid breakpoints, and identical results from concurrent calls.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <thread>

#include "deb/spectra/channel_set.h"
#include "deb/spectra/converted_spectrum.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/spectra/scaled_spectrum.h"
#include "deb/spectra/tabulated_csd.h"
#include "deb/spectra/vc_curve.h"

namespace deb {
namespace {

using SpectrumPtr = std::shared_ptr<const Spectrum>;

std::vector<SpectrumPtr> EveryKind() {
  const auto vc = std::make_shared<VcSpectrum>(VcClass::kD, VcOptions::ThesisModified());
  Eigen::MatrixXd table(4, 2);
  table << 1e-2, 0.0, 3e-3, 1.0, 1e-4, 2.0, 1e-5, 0.5;
  MeasuredSpectrumOptions hold;
  hold.extrapolation = Extrapolation::kHold;
  const auto measured = std::make_shared<MeasuredSpectrum>(std::vector<double>{0.3, 2.0, 30.0, 500.0}, table, hold);
  const auto floor = std::make_shared<IndependentChannels>(std::vector<SpectrumPtr>{vc, vc, vc});
  Eigen::Matrix3d rho;
  rho << 1.0, 0.8, 0.6, 0.8, 1.0, 0.7, 0.6, 0.7, 1.0;
  const auto coherent_floor = std::make_shared<CorrelatedChannels>(floor, rho);
  // Two channels, coherency 0.9 e^{j phi} turning with frequency (a delay).
  const std::vector<double> csd_f{0.2, 3.0, 40.0, 800.0};
  Eigen::MatrixXcd csd_table(4, 4);
  for (int i = 0; i < 4; ++i) {
    const double saa = 1e-3 / csd_f[static_cast<std::size_t>(i)], sbb = 2e-3;
    const std::complex<double> sab = 0.9 * std::sqrt(saa * sbb) * std::polar(1.0, 0.01 * csd_f[static_cast<std::size_t>(i)]);
    csd_table.row(i) << saa, std::conj(sab), sab, sbb;
  }
  TabulatedCsdOptions csd_hold;
  csd_hold.extrapolation = Extrapolation::kHold;
  const auto tabulated = std::make_shared<TabulatedCsd>(csd_f, 2, csd_table, csd_hold);
  const auto noise = std::make_shared<IndependentChannels>(std::vector<SpectrumPtr>(
      7, std::make_shared<FlatSpectrum>(20.0)));
  return {std::make_shared<FlatSpectrum>(20.0),
          std::make_shared<FlatSpectrum>(1.0, 0.5, 100.0),
          vc,
          std::make_shared<VcSpectrum>(VcClass::kA),
          measured,
          tabulated,
          std::make_shared<ConvertedSpectrum>(std::make_shared<PetersonSpectrum>(PetersonModel::kLow, Extrapolation::kHold),
                                              1e6, -1, "um/s"),
          std::make_shared<ConvertedSpectrum>(coherent_floor, 1e-3, 0, "mm/s"),
          floor,
          coherent_floor,
          std::make_shared<ScaledSpectrum>(coherent_floor, 2.0),
          noise,
          std::make_shared<CorrelatedChannels>(noise, Eigen::MatrixXd::Constant(7, 7, 0.5) +
                                                          0.5 * Eigen::MatrixXd::Identity(7, 7)),
          std::make_shared<IndependentChannels>(std::vector<SpectrumPtr>{measured, coherent_floor})};
}

std::vector<double> Frequencies() {
  std::vector<double> f_hz;
  for (int i = 0; i <= 400; ++i) f_hz.push_back(0.1 * std::pow(10.0, 4.0 * i / 400));  // 0.1-1000 Hz
  return f_hz;
}

TEST_CASE("every spectrum kind honours the Spectrum contract (Hermitian and PSD to 1e-12 relative)") {
  for (const SpectrumPtr& s : EveryKind()) {
    CAPTURE(s->Describe());
    CHECK_FALSE(s->Describe().empty());
    const int n = s->channels();
    REQUIRE(n >= 1);
    const std::vector<double> breakpoints = s->BreakpointsHz();
    for (std::size_t i = 0; i < breakpoints.size(); ++i) {
      CHECK(std::isfinite(breakpoints[i]));
      CHECK(breakpoints[i] > 0.0);
      if (i > 0) CHECK(breakpoints[i] > breakpoints[i - 1]);
    }
    const auto white = s->WhiteLevel();
    for (double f_hz : Frequencies()) {
      const Eigen::MatrixXcd csd = s->Csd(f_hz);
      const Eigen::VectorXd psd = s->Psd(f_hz);
      REQUIRE(csd.rows() == n);
      REQUIRE(csd.cols() == n);
      REQUIRE(psd.size() == n);
      const double scale = std::max(csd.norm(), 1e-300);
      CHECK((csd - csd.adjoint()).norm() <= 1e-12 * scale);
      CHECK((csd.diagonal().real() - psd).norm() <= 1e-15 * scale);
      CHECK(psd.minCoeff() >= 0.0);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eigen(csd);
      CHECK(eigen.eigenvalues().minCoeff() >= -1e-12 * scale);
      if (s->IsDiagonal()) {
        CHECK((csd - Eigen::MatrixXcd(csd.diagonal().asDiagonal())).norm() == 0.0);
      }
      if (white) CHECK((csd - white->cast<std::complex<double>>()).norm() <= 1e-15 * scale);
    }
  }
}

TEST_CASE("concurrent Csd and Psd calls return exactly what serial calls return") {
  const std::vector<double> f_hz = Frequencies();
  for (const SpectrumPtr& s : EveryKind()) {
    CAPTURE(s->Describe());
    std::vector<Eigen::MatrixXcd> serial;
    for (double f : f_hz) serial.push_back(s->Csd(f));
    const int kThreads = 4;
    std::vector<std::vector<Eigen::MatrixXcd>> parallel(kThreads);
    std::vector<std::thread> workers;
    for (int t = 0; t < kThreads; ++t) {
      workers.emplace_back([&, t] {
        // Each thread walks the grid in a different order.
        for (std::size_t k = 0; k < f_hz.size(); ++k) {
          const std::size_t i = (k * (2 * t + 1)) % f_hz.size();
          s->Psd(f_hz[i]);
          parallel[t].push_back(s->Csd(f_hz[i]));
        }
      });
    }
    for (auto& worker : workers) worker.join();
    for (int t = 0; t < kThreads; ++t) {
      for (std::size_t k = 0; k < f_hz.size(); ++k) {
        const std::size_t i = (k * (2 * t + 1)) % f_hz.size();
        CHECK(parallel[t][k] == serial[i]);
      }
    }
  }
}

}  // namespace
}  // namespace deb
