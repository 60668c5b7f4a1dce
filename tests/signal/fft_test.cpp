#include "deb/signal/fft.h"

#include <doctest/doctest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "deb/core/error.h"
#include "tests/signal/signal_test_support.h"

namespace deb {
namespace {

TEST_CASE("the FFT of a cosine on bin k has N/2 in bin k and nothing elsewhere (abs 1e-9)") {
  for (int n : {16, 17, 1000, 4096}) {
    const RealFft fft(n);
    CHECK(fft.bins() == n / 2 + 1);
    RealFft::Buffer b = fft.MakeBuffer();
    const int k = 3;
    for (int i = 0; i < n; ++i) b.input()[i] = std::cos(2.0 * test::kPi * k * i / n);
    fft.Execute(b);
    for (int j = 0; j < fft.bins(); ++j) {
      const double expected = j == k ? n / 2.0 : 0.0;
      CHECK(std::abs(b.output()[j].real() - expected) < 1e-9);
      CHECK(std::abs(b.output()[j].imag()) < 1e-9);
    }
  }
}

TEST_CASE("the FFT of a unit impulse at sample 1 is exp(-j 2 pi k / N) (abs 1e-12)") {
  const int n = 64;
  const RealFft fft(n);
  RealFft::Buffer b = fft.MakeBuffer();
  for (int i = 0; i < n; ++i) b.input()[i] = i == 1 ? 1.0 : 0.0;
  fft.Execute(b);
  for (int k = 0; k < fft.bins(); ++k) {
    CHECK(std::abs(b.output()[k] - std::polar(1.0, -2.0 * test::kPi * k / n)) < 1e-12);
  }
}

TEST_CASE("plans made and executed on several threads give the transform of one thread, bit for bit") {
  const int n = 1024;
  const Eigen::VectorXd x = test::WhiteNoise(n, 1.0, 7);
  const RealFft reference(n);
  RealFft::Buffer rb = reference.MakeBuffer();
  for (int i = 0; i < n; ++i) rb.input()[i] = x(i);
  reference.Execute(rb);
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int repeat = 0; repeat < 20; ++repeat) {
        const RealFft fft(n);
        RealFft::Buffer b = fft.MakeBuffer();
        for (int i = 0; i < n; ++i) b.input()[i] = x(i);
        fft.Execute(b);
        for (int k = 0; k < fft.bins(); ++k) mismatches[static_cast<std::size_t>(t)] += b.output()[k] != rb.output()[k];
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int m : mismatches) CHECK(m == 0);
}

TEST_CASE("an FFT length below 1 is an input error") { CHECK_THROWS_AS(RealFft(0), InputError); }

}  // namespace
}  // namespace deb
