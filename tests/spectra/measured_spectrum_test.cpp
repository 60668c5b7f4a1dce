#include "deb/spectra/measured_spectrum.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

// Two channels: S = a f^-2 and S = b f^1.5, tabulated on an uneven log grid.
MeasuredSpectrum PowerLaws(Extrapolation extrapolation = Extrapolation::kError) {
  const std::vector<double> f_hz = {0.1, 0.3, 1.0, 2.5, 10.0, 40.0, 100.0};
  Eigen::MatrixXd psd(f_hz.size(), 2);
  for (std::size_t i = 0; i < f_hz.size(); ++i) {
    psd(i, 0) = 7.0 * std::pow(f_hz[i], -2.0);
    psd(i, 1) = 0.2 * std::pow(f_hz[i], 1.5);
  }
  MeasuredSpectrumOptions options;
  options.extrapolation = extrapolation;
  options.channel_names = {"floor", "sensor"};
  options.unit = "um/s";
  options.origin = "power_laws.csv";
  return MeasuredSpectrum(f_hz, psd, options);
}

TEST_CASE("log-log interpolation reproduces a power law at interval midpoints (rel 1e-12)") {
  const MeasuredSpectrum measured = PowerLaws();
  const std::vector<double>& f = measured.f_hz();
  for (std::size_t i = 0; i + 1 < f.size(); ++i) {
    for (double f_mid : {std::sqrt(f[i] * f[i + 1]), 0.5 * (f[i] + f[i + 1]), f[i] + 0.1 * (f[i + 1] - f[i])}) {
      const Eigen::VectorXd psd = measured.Psd(f_mid);
      CHECK(psd(0) == doctest::Approx(7.0 * std::pow(f_mid, -2.0)).epsilon(1e-12));
      CHECK(psd(1) == doctest::Approx(0.2 * std::pow(f_mid, 1.5)).epsilon(1e-12));
    }
  }
}

TEST_CASE("a tabulated frequency returns its tabulated values exactly, including the range ends") {
  const MeasuredSpectrum measured = PowerLaws();
  for (std::size_t i = 0; i < measured.f_hz().size(); ++i) {
    const Eigen::VectorXd psd = measured.Psd(measured.f_hz()[i]);
    CHECK(psd(0) == measured.psd_table()(i, 0));
    CHECK(psd(1) == measured.psd_table()(i, 1));
  }
}

TEST_CASE("an interval with a zero end is interpolated linearly in f") {
  Eigen::MatrixXd psd(3, 1);
  psd << 0.0, 4.0, 0.0;
  const MeasuredSpectrum measured({1.0, 2.0, 4.0}, psd);
  CHECK(measured.Psd(1.5)(0) == doctest::Approx(2.0).epsilon(1e-15));
  CHECK(measured.Psd(3.0)(0) == doctest::Approx(2.0).epsilon(1e-15));
  CHECK(measured.Psd(1.0)(0) == 0.0);
}

TEST_CASE("outside the data, extrapolation 'error' throws naming the frequency and the data range") {
  const MeasuredSpectrum measured = PowerLaws();
  const std::string message = InputErrorText([&] { measured.Psd(0.05); });
  CHECK(message.find("power_laws.csv") != std::string::npos);
  CHECK(message.find("0.05 Hz") != std::string::npos);
  CHECK(message.find("0.1-100 Hz") != std::string::npos);
  CHECK_THROWS_AS(measured.Csd(100.5), InputError);
}

TEST_CASE("outside the data, extrapolation 'zero' gives 0 and 'hold' the nearest end value") {
  const MeasuredSpectrum zero = PowerLaws(Extrapolation::kZero);
  CHECK(zero.Psd(0.05).isZero(0.0));
  CHECK(zero.Psd(1000.0).isZero(0.0));
  const MeasuredSpectrum hold = PowerLaws(Extrapolation::kHold);
  CHECK(hold.Psd(0.01) == hold.psd_table().row(0).transpose());
  CHECK(hold.Psd(1e4) == hold.psd_table().row(6).transpose());
}

TEST_CASE("measured channels are independent: the CSD is diagonal with the PSDs on it") {
  const MeasuredSpectrum measured = PowerLaws();
  const Eigen::MatrixXcd csd = measured.Csd(3.0);
  const Eigen::VectorXd psd = measured.Psd(3.0);
  CHECK(measured.IsDiagonal());
  CHECK(csd(0, 1) == std::complex<double>(0.0, 0.0));
  CHECK(csd(1, 0) == std::complex<double>(0.0, 0.0));
  CHECK(csd(0, 0).real() == psd(0));
  CHECK(csd(1, 1).real() == psd(1));
  CHECK(measured.BreakpointsHz() == measured.f_hz());  // every data point goes on the grid
  CHECK_FALSE(measured.WhiteLevel().has_value());
  CHECK(measured.Describe().find("2 channels (floor, sensor)") != std::string::npos);
}

TEST_CASE("a measured spectrum rejects bad frequencies, bad PSD values and mismatched sizes, quoting them") {
  Eigen::MatrixXd two(2, 1);
  two << 1.0, 1.0;
  CHECK(InputErrorText([&] { MeasuredSpectrum({2.0, 2.0}, two); }).find("2 Hz is not greater than") !=
        std::string::npos);
  CHECK(InputErrorText([&] { MeasuredSpectrum({0.0, 2.0}, two); }).find("= 0 Hz") != std::string::npos);
  CHECK(InputErrorText([&] { MeasuredSpectrum({1.0, 2.0, 3.0}, two); }).find("expected 3 rows") != std::string::npos);
  Eigen::MatrixXd negative(2, 1);
  negative << 1.0, -0.5;
  CHECK(InputErrorText([&] { MeasuredSpectrum({1.0, 2.0}, negative); }).find("-0.5") != std::string::npos);
  Eigen::MatrixXd one(1, 1);
  one << 1.0;
  CHECK(InputErrorText([&] { MeasuredSpectrum({1.0}, one); }).find("at least 2") != std::string::npos);
  MeasuredSpectrumOptions names;
  names.channel_names = {"a", "b"};
  CHECK_THROWS_AS(MeasuredSpectrum({1.0, 2.0}, two, names), InputError);
}

TEST_CASE("extrapolation names round-trip and an unknown name lists the allowed ones") {
  for (auto e : {Extrapolation::kError, Extrapolation::kZero, Extrapolation::kHold}) {
    CHECK(ParseExtrapolation(ToString(e)) == e);
  }
  CHECK(InputErrorText([] { ParseExtrapolation("clamp"); }).find("'clamp'; allowed: error, zero, hold") !=
        std::string::npos);
}


TEST_CASE("the bins of an estimate hold their value across their width, and the grid sees every edge") {
  Eigen::MatrixXd psd(3, 1);
  psd << 1.0, 8.0, 2.0;
  MeasuredSpectrumOptions o;
  o.interpolation = SpectrumInterpolation::kBins;
  const MeasuredSpectrum bins({1.0, 2.0, 3.0}, psd, o);
  CHECK(bins.bin_edges_hz() == std::vector<double>{0.5, 1.5, 2.5, 3.5});
  CHECK(bins.lo_hz() == 0.5);
  CHECK(bins.hi_hz() == 3.5);
  CHECK(bins.BreakpointsHz() == bins.bin_edges_hz());
  CHECK(bins.Psd(0.6)(0) == 1.0);
  CHECK(bins.Psd(1.49)(0) == 1.0);
  CHECK(bins.Psd(1.5)(0) == 8.0);  // an edge belongs to the bin above it
  CHECK(bins.Psd(3.5)(0) == 2.0);
  CHECK(bins.Psd(2.0)(0) == 8.0);
  CHECK(bins.Describe().find("constant over each bin (0.5-3.5 Hz)") != std::string::npos);
  CHECK_THROWS_AS(bins.Psd(3.6), InputError);
  // A first point close to 0 Hz: the lowest edge stays above 0.
  const MeasuredSpectrum low({0.1, 5.0}, Eigen::MatrixXd::Ones(2, 1), o);
  CHECK(low.lo_hz() == 0.05);
  CHECK(ToString(SpectrumInterpolation::kBins) == "bins");
  CHECK(ParseSpectrumInterpolation("log-log") == SpectrumInterpolation::kLogLog);
  CHECK_THROWS_WITH_AS(ParseSpectrumInterpolation("linear"), "unknown spectrum interpolation 'linear'; allowed: log-log, bins",
                       InputError);
}

}  // namespace
}  // namespace deb
