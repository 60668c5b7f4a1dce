// Welch PSD of 8 channels x 10^7 samples (generated in memory), on one
// thread and on all threads; the default segments (8 of 2^21 samples) on 1
// and 2 threads. Prints seconds; not run by CTest.
#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "deb/core/parallel.h"
#include "deb/signal/welch.h"

int main() {
  constexpr int kChannels = 8;
  constexpr Eigen::Index kSamples = 10'000'000;
  const double fs = 1000.0;
  Eigen::MatrixXd x(kSamples, kChannels);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (Eigen::Index c = 0; c < kChannels; ++c)
    for (Eigen::Index n = 0; n < kSamples; ++n) x(n, c) = normal(rng);
  const deb::TimeSeries series(fs, std::move(x));

  struct Case {
    const char* what;
    int segment;
    deb::Averaging averaging;
    int threads[2];  // 0: all
  };
  const Case cases[] = {{"Hann, 65536-sample segments, 50 % overlap, mean", 65536, deb::Averaging::kMean, {1, 0}},
                        {"Hann, 4096-sample segments, 50 % overlap, mean", 4096, deb::Averaging::kMean, {1, 0}},
                        {"Hann, 65536-sample segments, 50 % overlap, median", 65536, deb::Averaging::kMedian, {1, 0}},
                        {"Hann, default segments (>= 8), 50 % overlap, mean", 0, deb::Averaging::kMean, {1, 2}}};
  std::printf("Welch PSD, %d channels x %lld samples (%d threads available)\n", kChannels,
              static_cast<long long>(kSamples), deb::DefaultThreadCount());
  for (const Case& c : cases) {
    for (int threads : c.threads) {
      deb::WelchOptions o;
      o.segment_length = c.segment;
      o.averaging = c.averaging;
      o.threads = threads;
      const auto t0 = std::chrono::steady_clock::now();
      const deb::PsdEstimate e = deb::WelchPsd(series, o);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      // The mean level over the bins between 0 Hz and Nyquist (a single bin scatters by a few %).
      const double level = e.psd.col(0).segment(1, e.psd.rows() - 2).mean();
      const std::string on =
          threads == 0 ? "all threads" : threads == 1 ? "1 thread" : std::to_string(threads) + " threads";
      std::printf("  %-52s %-12s %7.3f s  (%d averages, mean level %.5g, expected %.4g)\n", c.what, on.c_str(), s,
                  e.provenance.segments, level, 2.0 / fs);
    }
  }
  return 0;
}
