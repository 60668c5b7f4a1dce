#include "deb/signal/welch.h"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "deb/core/error.h"
#include "tests/signal/signal_test_support.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

using test::kHannBinCorrelationFactor;
using test::kPi;

TimeSeries Series(double fs, std::initializer_list<Eigen::VectorXd> channels) {
  Eigen::MatrixXd m(channels.begin()->size(), static_cast<Eigen::Index>(channels.size()));
  Eigen::Index c = 0;
  for (const auto& x : channels) m.col(c++) = x;
  return TimeSeries(fs, m);
}

// Mean of v over bins [first, last).
double MeanOver(const Eigen::VectorXd& v, Eigen::Index first, Eigen::Index last) {
  return v.segment(first, last - first).mean();
}

TEST_CASE("white noise of variance s^2 has the one-sided level 2 s^2 / fs, within 4 sigma of the bin mean") {
  const double fs = 500.0, sigma = 3.0;
  const TimeSeries x = Series(fs, {test::WhiteNoise(1 << 20, sigma, 1)});
  WelchOptions o;
  o.segment_length = 1024;
  const PsdEstimate e = WelchPsd(x, o);
  REQUIRE(e.f_hz.size() == 513);
  CHECK(e.f_hz[1] == doctest::Approx(fs / 1024));
  CHECK(e.provenance.segments == 2047);
  const double level = 2.0 * sigma * sigma / fs;
  // Each bin is level chi2_nu / nu: relative std sqrt(2/nu); the mean of B
  // neighbouring Hann bins has the variance of B / 1.944 independent ones.
  const Eigen::Index bins = 511;
  const double sigma_mean = std::sqrt(2.0 / e.provenance.degrees_of_freedom * kHannBinCorrelationFactor / bins);
  const double mean = MeanOver(e.psd.col(0), 1, 512) / level;
  MESSAGE("white level ratio " << mean << ", sigma of the mean " << sigma_mean);
  CHECK(std::abs(mean - 1.0) < 4.0 * sigma_mean);
  // Nyquist is not doubled: half the level. At DC the segment mean is gone
  // before windowing, so E|X_0|^2 = s^2 (S2 - S1^2/L) = s^2 L/8 for Hann: a
  // sixth of the level (one bin: within 4 sqrt(2/nu)).
  CHECK(std::abs(e.psd(512, 0) / level - 0.5) < 4.0 * 0.5 * std::sqrt(2.0 / e.provenance.degrees_of_freedom));
  CHECK(std::abs(e.psd(0, 0) / level - 1.0 / 6.0) < 4.0 / 6.0 * std::sqrt(2.0 / e.provenance.degrees_of_freedom));
}

TEST_CASE("Parseval: the PSD summed over bins times fs/L is the window-weighted mean square of the segments (rel 1e-12)") {
  const double fs = 100.0;
  const Eigen::VectorXd data = test::WhiteNoise(10000, 1.5, 2) + Eigen::VectorXd::Constant(10000, 0.3);
  for (int length : {256, 255}) {  // even and odd: Nyquist bin or not
    WelchOptions o;
    o.segment_length = length;
    o.detrend = Detrend::kNone;
    o.window = WindowKind::kHamming;
    const PsdEstimate e = WelchPsd(Series(fs, {data}), o);
    const std::vector<double> w = MakeWindow(o.window, length);
    const WindowSums s = SumsOf(w);
    double direct = 0.0;
    const int step = e.provenance.segment_length - e.provenance.overlap_samples;
    for (int k = 0; k < e.provenance.segments; ++k) {
      for (int n = 0; n < length; ++n) {
        const double v = w[static_cast<std::size_t>(n)] * data(k * step + n);
        direct += v * v;
      }
    }
    direct /= s.sum_squares * e.provenance.segments;
    CHECK(e.psd.col(0).sum() * fs / length == doctest::Approx(direct).epsilon(1e-12));
  }
}

TEST_CASE("Parseval against the variance: the integrated white-noise PSD is s^2 within 4 sigma") {
  const double fs = 1000.0, sigma = 0.7;
  const PsdEstimate e = WelchPsd(Series(fs, {test::WhiteNoise(1 << 20, sigma, 3)}), WelchOptions{});
  const int length = e.provenance.segment_length;
  // Weighted mean square of one Hann segment of Gaussian white noise:
  // relative variance 2 S4 / S2^2 = 2 (35/128) / (3/8)^2 / L; half-overlapped
  // neighbours correlate by 3/35.
  const double rel_var_one = 2.0 * (35.0 / 128.0) / (9.0 / 64.0) / length;
  const double sigma_rel = std::sqrt(rel_var_one * (1.0 + 2.0 * 3.0 / 35.0) / e.provenance.segments);
  const double variance = e.psd.col(0).sum() * fs / length;
  MESSAGE("integrated variance / s^2 = " << variance / (sigma * sigma) << ", sigma " << sigma_rel);
  CHECK(std::abs(variance / (sigma * sigma) - 1.0) < 4.0 * sigma_rel);
}

TEST_CASE("a sine's power and frequency: A^2/2 over its peak (rel 1e-3), peak at the nearest bin, flat-top peak x ENBW = A^2/2 (rel 3e-3)") {
  const double fs = 1024.0, amplitude = 2.0, f0 = 100.3;
  Eigen::VectorXd x(1 << 16);
  for (Eigen::Index n = 0; n < x.size(); ++n) x(n) = amplitude * std::sin(2.0 * kPi * f0 * n / fs + 0.4);
  for (WindowKind window : {WindowKind::kHann, WindowKind::kBlackmanHarris, WindowKind::kFlatTop}) {
    WelchOptions o;
    o.segment_length = 1024;  // 1 Hz bins; f0 sits 0.3 bin off bin 100
    o.window = window;
    const PsdEstimate e = WelchPsd(Series(fs, {x}), o);
    Eigen::Index peak = 0;
    e.psd.col(0).maxCoeff(&peak);
    CHECK(peak == 100);
    const double power = e.psd.col(0).segment(peak - 8, 17).sum() * e.provenance.resolution_hz;
    CHECK(power == doctest::Approx(amplitude * amplitude / 2).epsilon(1e-3));
    // Power-weighted centroid of the peak: within 0.05 bin of f0.
    double num = 0.0, den = 0.0;
    for (Eigen::Index k = peak - 8; k <= peak + 8; ++k) {
      num += e.f_hz[static_cast<std::size_t>(k)] * e.psd(k, 0);
      den += e.psd(k, 0);
    }
    CHECK(std::abs(num / den - f0) < 0.05);
    if (window == WindowKind::kFlatTop) {
      CHECK(e.psd(peak, 0) * e.provenance.enbw_hz == doctest::Approx(amplitude * amplitude / 2).epsilon(3e-3));
    }
  }
}

TEST_CASE("AR(1) noise matches its analytic PSD in every group of 64 bins within 4 sigma plus 0.5 % window bias") {
  const double fs = 100.0, a = 0.9, sigma = 1.0;
  const TimeSeries x = Series(fs, {test::Ar1(1 << 20, a, sigma, 4)});
  WelchOptions o;
  o.segment_length = 2048;
  const PsdEstimate e = WelchPsd(x, o);
  const double sigma_bin = std::sqrt(2.0 / e.provenance.degrees_of_freedom);
  const int group = 64;
  double worst = 0.0;
  for (int first = 1; first + group <= 1024; first += group) {
    double ratio = 0.0;
    for (int k = first; k < first + group; ++k)
      ratio += e.psd(k, 0) / test::Ar1Psd(e.f_hz[static_cast<std::size_t>(k)], a, sigma, fs);
    ratio /= group;
    const double tolerance = 4.0 * sigma_bin * std::sqrt(kHannBinCorrelationFactor / group) + 0.005;
    worst = std::max(worst, std::abs(ratio - 1.0) / tolerance);
    CHECK(std::abs(ratio - 1.0) < tolerance);
  }
  MESSAGE("AR(1): worst group deviation " << worst << " of its tolerance");
}

TEST_CASE("coherence of a shared signal plus independent noises follows S_s^2 / ((S_s + N1)(S_s + N2)) within 4 sigma plus its 1/K bias") {
  const double fs = 200.0, a = 0.8;
  const Eigen::Index n = 1 << 20;
  const Eigen::VectorXd s = test::Ar1(n, a, 1.0, 5);
  const double s1 = 1.5, s2 = 3.0;  // noise standard deviations
  const TimeSeries x = Series(fs, {s + test::WhiteNoise(n, s1, 6), s + test::WhiteNoise(n, s2, 7)});
  WelchOptions o;
  o.segment_length = 1024;
  const CsdEstimate e = WelchCsd(x, o);
  const Eigen::VectorXd gamma2 = e.Coherence(0, 1);
  const double k_eff = e.provenance.degrees_of_freedom / 2.0;
  const int group = 32;
  for (int first = 1; first + group <= 512; first += group) {
    double measured = 0.0, expected = 0.0, variance = 0.0;
    for (int k = first; k < first + group; ++k) {
      const double ss = test::Ar1Psd(e.f_hz[static_cast<std::size_t>(k)], a, 1.0, fs);
      const double n1 = 2.0 * s1 * s1 / fs, n2 = 2.0 * s2 * s2 / fs;
      const double g = ss * ss / ((ss + n1) * (ss + n2));
      measured += gamma2(k);
      expected += g + (1.0 - g) * (1.0 - g) / k_eff;      // bias of the estimate
      variance += 2.0 * g * (1.0 - g) * (1.0 - g) / k_eff;  // Bendat & Piersol eq. 9.73
    }
    measured /= group;
    expected /= group;
    const double sigma = std::sqrt(variance / group * kHannBinCorrelationFactor / group);
    CHECK(std::abs(measured - expected) < 4.0 * sigma + 1e-4);
  }
  // Hermitian, real auto-spectra, coherence of a channel with itself is 1.
  CHECK((e.Cross(1, 0) - e.Cross(0, 1).conjugate()).norm() == 0.0);
  CHECK(e.Cross(0, 0).imag().norm() == 0.0);
  CHECK(e.Coherence(0, 0).segment(1, 500).minCoeff() == doctest::Approx(1.0));
}

TEST_CASE("the CSD phase of a channel delayed by tau is -2 pi f tau (conj on the first channel), within 5 sigma per bin") {
  const double fs = 1000.0;
  const int delay = 3;  // samples: tau = 3 ms
  const Eigen::Index n = 1 << 18;
  const Eigen::VectorXd x = test::WhiteNoise(n + delay, 1.0, 8);
  const TimeSeries series = Series(fs, {x.tail(n), x.head(n)});  // channel 1 lags channel 0 by `delay`
  WelchOptions o;
  o.segment_length = 512;
  // No detrend: the two segments' means differ, and removing them leaks
  // into bin 1 through the Hann main lobe.
  o.detrend = Detrend::kNone;
  const CsdEstimate e = WelchCsd(series, o);
  const Eigen::VectorXcd s01 = e.Cross(0, 1);
  // The delayed copy shares sum_n w_n w_{n+d} / S2 of each segment's
  // windowed power: that is its true coherence (squared).
  const std::vector<double> w = MakeWindow(o.window, 512);
  double shared = 0.0;
  for (int i = 0; i + delay < 512; ++i) shared += w[static_cast<std::size_t>(i)] * w[static_cast<std::size_t>(i + delay)];
  const double rho = shared / SumsOf(w).sum_squares;
  const double gamma2 = rho * rho;
  const double k_eff = e.provenance.degrees_of_freedom / 2.0;
  // Phase std of a CSD estimate: sqrt((1 - g^2) / (2 K g^2)) (Bendat & Piersol eq. 9.52).
  const double sigma = std::sqrt((1.0 - gamma2) / (2.0 * k_eff * gamma2));
  double worst = 0.0;
  int checked = 0;
  for (Eigen::Index k = 1; k < 256; ++k) {
    const double expected = -2.0 * kPi * e.f_hz[static_cast<std::size_t>(k)] * delay / fs;
    const double error = std::arg(s01(k) * std::polar(1.0, -expected));
    worst = std::max(worst, std::abs(error) / sigma);
    CHECK(std::abs(error) < 5.0 * sigma);
    ++checked;
  }
  MESSAGE("CSD phase: worst bin " << worst << " sigma (sigma " << sigma << " rad)");
  CHECK(checked == 255);
}

TEST_CASE("median averaging with its bias correction recovers the white level within 4 sigma, and ignores a burst") {
  const double fs = 100.0, sigma = 1.0;
  Eigen::VectorXd x = test::WhiteNoise(1 << 18, sigma, 9);
  x.segment(5000, 300).array() += 50.0 * test::WhiteNoise(300, 1.0, 10).array();  // a knock on the floor
  WelchOptions o;
  o.segment_length = 512;
  o.averaging = Averaging::kMedian;
  const PsdEstimate median = WelchPsd(Series(fs, {x}), o);
  const double level = 2.0 * sigma * sigma / fs;
  const double sigma_mean = std::sqrt(2.0 / median.provenance.degrees_of_freedom * kHannBinCorrelationFactor / 254);
  const double ratio = MeanOver(median.psd.col(0), 1, 255) / level;
  MESSAGE("median level ratio " << ratio << ", sigma " << sigma_mean);
  CHECK(std::abs(ratio - 1.0) < 4.0 * sigma_mean);
  o.averaging = Averaging::kMean;
  CHECK(MeanOver(WelchPsd(Series(fs, {x}), o).psd.col(0), 1, 255) / level > 1.5);  // the mean is not robust
  for (int k : {2, 3, 4, 5}) {  // even counts take the odd count below (bias of the middle pair)
    o.averaging = Averaging::kMedian;
    o.segment_length = 1 << 16;
    o.overlap = 0.0;
    const Eigen::VectorXd y = test::WhiteNoise(k * (1 << 16), sigma, 11 + k);
    CHECK(WelchPsd(Series(fs, {y}), o).provenance.segments == k);
  }
}

TEST_CASE("degrees of freedom: 2K without overlap, 2K / (1 + 2 (1 - 1/K) / 36) for Hann at 50 % (rel 1e-12)") {
  const std::vector<double> rect = MakeWindow(WindowKind::kRectangular, 100);
  CHECK(WelchDegreesOfFreedom(rect, 100, 7, Averaging::kMean) == doctest::Approx(14.0).epsilon(1e-12));
  const std::vector<double> hann = MakeWindow(WindowKind::kHann, 1000);
  const int k = 50;  // periodic Hann at half overlap: rho = 1/6 exactly
  CHECK(WelchDegreesOfFreedom(hann, 500, k, Averaging::kMean) ==
        doctest::Approx(2.0 * k / (1.0 + 2.0 * (1.0 - 1.0 / k) / 36.0)).epsilon(1e-12));
  const double ln2 = std::log(2.0);
  CHECK(WelchDegreesOfFreedom(rect, 100, 7, Averaging::kMedian) == doctest::Approx(14.0 * ln2 * ln2).epsilon(1e-12));
}

TEST_CASE("95 % chi-square bounds contain the true white level in 95 % of independent bins (within 4 binomial sigma)") {
  const double fs = 64.0, sigma = 1.0;
  WelchOptions o;
  o.segment_length = 4096;
  o.overlap = 0.0;
  o.window = WindowKind::kRectangular;  // independent bins, nu = 2K exactly
  const PsdEstimate e = WelchPsd(Series(fs, {test::WhiteNoise(4096 * 8, sigma, 12)}), o);
  CHECK(e.provenance.degrees_of_freedom == doctest::Approx(16.0));
  const double level = 2.0 * sigma * sigma / fs;
  int inside = 0, bins = 0;
  for (Eigen::Index k = 1; k < 2048; ++k, ++bins) {
    const double p = e.psd(k, 0);
    inside += p * e.provenance.lower_factor <= level && level <= p * e.provenance.upper_factor;
  }
  const double fraction = static_cast<double>(inside) / bins;
  MESSAGE("coverage " << fraction);
  CHECK(std::abs(fraction - 0.95) < 4.0 * std::sqrt(0.95 * 0.05 / bins));
}

TEST_CASE("linear detrend removes a ramp that would otherwise leak into the low bins") {
  const double fs = 100.0;
  Eigen::VectorXd x = test::WhiteNoise(1 << 16, 1.0, 13);
  for (Eigen::Index n = 0; n < x.size(); ++n) x(n) += 1e-2 * static_cast<double>(n);
  WelchOptions o;
  o.segment_length = 1024;
  o.detrend = Detrend::kLinear;
  const double level = 2.0 / fs;
  CHECK(WelchPsd(Series(fs, {x}), o).psd(1, 0) / level < 2.0);
  o.detrend = Detrend::kMean;
  CHECK(WelchPsd(Series(fs, {x}), o).psd(1, 0) / level > 100.0);
}

TEST_CASE("one thread and two threads give the same estimate (rel 1e-12), mean and median, PSD and CSD") {
  const Eigen::Index n = 1 << 17;
  const TimeSeries x = Series(100.0, {test::WhiteNoise(n, 1.0, 14), test::WhiteNoise(n, 2.0, 15)});
  for (Averaging averaging : {Averaging::kMean, Averaging::kMedian}) {
    WelchOptions o;
    o.segment_length = 256;
    o.averaging = averaging;
    o.threads = 1;
    const PsdEstimate p1 = WelchPsd(x, o);
    const CsdEstimate c1 = WelchCsd(x, o);
    o.threads = 2;
    const PsdEstimate p2 = WelchPsd(x, o);
    const CsdEstimate c2 = WelchCsd(x, o);
    CHECK((p1.psd - p2.psd).norm() <= 1e-12 * p1.psd.norm());
    CHECK((c1.csd - c2.csd).norm() <= 1e-12 * c1.csd.norm());
    // The CSD's diagonal is the PSD.
    CHECK((c1.AutoSpectra().psd - p1.psd).norm() <= 1e-12 * p1.psd.norm());
  }
}

TEST_CASE("PSD and CSD are bitwise the same on 1, 2 and 5 threads, default and short segments, mean and median") {
  const Eigen::Index n = 1 << 17;
  const TimeSeries x = Series(
      100.0, {test::WhiteNoise(n, 1.0, 21), test::Ar1(n, 0.9, 2.0, 22), test::WhiteNoise(n, 0.5, 23)});
  // 0: automatic, 15 segments of 16384 (a few per job); 256: 1023 segments,
  // hundreds per job.
  for (int segment : {0, 256}) {
    for (Averaging averaging : {Averaging::kMean, Averaging::kMedian}) {
      CAPTURE(segment);
      WelchOptions o;
      o.segment_length = segment;
      o.averaging = averaging;
      o.threads = 1;
      const PsdEstimate p1 = WelchPsd(x, o);
      const CsdEstimate c1 = WelchCsd(x, o);
      CHECK(p1.provenance.segments == (segment == 0 ? 15 : 1023));
      for (int threads : {2, 5}) {
        CAPTURE(threads);
        o.threads = threads;
        const PsdEstimate p = WelchPsd(x, o);
        const CsdEstimate c = WelchCsd(x, o);
        CHECK((p.psd.array() == p1.psd.array()).all());
        CHECK((c.csd.array() == c1.csd.array()).all());
      }
    }
  }
}

TEST_CASE("the automatic segment length is the largest power of two giving at least 8 segments") {
  WelchOptions o;
  CHECK(SegmentLengthFor(9 * 512, o) == 1024);  // 1024 at 50 %: (4608 - 512) / 512 = 8 segments
  CHECK(SegmentLengthFor(9 * 512 - 1, o) == 512);
  o.overlap = 0.0;
  CHECK(SegmentLengthFor(8 * 1024, o) == 1024);
}

TEST_CASE("bad input: too few samples for a segment, NaN in the data, invalid options") {
  const TimeSeries x = Series(100.0, {test::WhiteNoise(1000, 1.0, 16)});
  WelchOptions o;
  o.segment_length = 1024;
  const std::string message = InputErrorText([&] { WelchPsd(x, o); });
  CHECK(message.find("too few samples: 1000 samples are fewer than one segment of 1024") != std::string::npos);
  CHECK_THROWS_AS(WelchCsd(x, o), InputError);
  CHECK(InputErrorText([] { SegmentLengthFor(8, WelchOptions{}); }).find("too few samples: 8 samples are fewer than one segment of 16") != std::string::npos);
  CHECK(SegmentLengthFor(40, WelchOptions{}) == 16);  // fewer than 8 segments, but a spectrum
  WelchOptions two;
  two.segment_length = 2;
  CHECK(InputErrorText([&] { SegmentLengthFor(100, two); }).find("at least 16 samples") != std::string::npos);

  Eigen::MatrixXd bad = Eigen::MatrixXd::Zero(100, 2);
  bad(42, 1) = std::nan("");
  const std::string nan = InputErrorText([&] { TimeSeries(10.0, bad, {"x", "z"}); });
  CHECK(nan.find("channel 'z', sample 42 (t = 4.2 s) is nan; every sample must be finite") != std::string::npos);

  o.segment_length = 64;
  o.overlap = 1.0;
  std::string error;
  CHECK_FALSE(o.IsValid(&error));
  CHECK(error.find("overlap 1 is invalid") != std::string::npos);
  CHECK_THROWS_AS(WelchPsd(x, o), InputError);
  o.overlap = 0.5;
  o.confidence = 1.5;
  CHECK(InputErrorText([&] { WelchPsd(x, o); }).find("confidence 1.5") != std::string::npos);
  // Below 1, but (1 + c) / 2 rounds to 1: the upper quantile would be infinite.
  o.confidence = 0.9999999999999999;
  CHECK(InputErrorText([&] { WelchPsd(x, o); }).find("too close to 1") != std::string::npos);
  o.confidence = 0.999999;
  CHECK(o.IsValid(&error));
}

TEST_CASE("an estimate carries its provenance and converts to a budget source without its 0 Hz bin") {
  const TimeSeries x(250.0, test::WhiteNoise(1 << 14, 1.0, 17), {"z"}, "um/s");
  WelchOptions o;
  o.segment_length = 500;
  o.window = WindowKind::kBlackmanHarris;
  const PsdEstimate e = WelchPsd(x, o);
  const WelchProvenance& p = e.provenance;
  CHECK(p.window == WindowKind::kBlackmanHarris);
  CHECK(p.overlap_samples == 250);
  CHECK(p.segments == (16384 - 500) / 250 + 1);
  CHECK(p.resolution_hz == doctest::Approx(0.5));
  CHECK(p.enbw_hz == doctest::Approx(EnbwBins(MakeWindow(WindowKind::kBlackmanHarris, 500)) * 0.5));
  CHECK(p.lower_factor < 1.0);
  CHECK(p.upper_factor > 1.0);
  CHECK(p.Describe().front().find("blackman_harris, segment 500 samples, overlap 250 samples") != std::string::npos);
  const auto spectrum = ToMeasuredSpectrum(e);
  CHECK(spectrum->f_hz().front() == doctest::Approx(0.5));
  CHECK(spectrum->f_hz().size() == 250);
  CHECK(spectrum->unit() == "um/s");
  CHECK(spectrum->channel_names() == std::vector<std::string>{"z"});
  CHECK(spectrum->Psd(10.0)(0) == doctest::Approx(e.psd(20, 0)));
}

}  // namespace
}  // namespace deb
