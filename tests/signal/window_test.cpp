#include "deb/signal/window.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"
#include "tests/spectra/error_text.h"

namespace deb {
namespace {

// A periodic cosine-sum window a0 - a1 cos + a2 cos2 - ... has S1 = N a0 and
// S2 = N (a0^2 + sum_{m>=1} a_m^2 / 2), so ENBW = (a0^2 + sum a_m^2/2) / a0^2.
double ClosedFormEnbw(const std::vector<double>& a) {
  double s2 = a[0] * a[0];
  for (std::size_t m = 1; m < a.size(); ++m) s2 += 0.5 * a[m] * a[m];
  return s2 / (a[0] * a[0]);
}

TEST_CASE("window sums and equivalent noise bandwidths match the cosine-sum closed form (rel 1e-12)") {
  const int n = 1000;
  struct Case {
    WindowKind kind;
    std::vector<double> a;
    double published_enbw;  // Harris 1978 Table 1 / D'Antona & Ferrero, 3 decimals
  };
  const Case cases[] = {
      {WindowKind::kRectangular, {1.0}, 1.0},
      {WindowKind::kHann, {0.5, 0.5}, 1.5},
      {WindowKind::kHamming, {0.54, 0.46}, 1.363},
      {WindowKind::kBlackmanHarris, {0.35875, 0.48829, 0.14128, 0.01168}, 2.004},
      {WindowKind::kFlatTop, {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368}, 3.770},
  };
  for (const Case& c : cases) {
    const std::vector<double> w = MakeWindow(c.kind, n);
    REQUIRE(w.size() == static_cast<std::size_t>(n));
    const WindowSums s = SumsOf(w);
    CHECK(s.sum == doctest::Approx(n * c.a[0]).epsilon(1e-12));
    CHECK(EnbwBins(w) == doctest::Approx(ClosedFormEnbw(c.a)).epsilon(1e-12));
    CHECK(std::abs(EnbwBins(w) - c.published_enbw) < 1e-3);
  }
}

TEST_CASE("windows are periodic: the Hann window is 0 at n = 0 and 1 at n = N/2, and symmetric about N/2") {
  const std::vector<double> w = MakeWindow(WindowKind::kHann, 8);
  CHECK(w[0] == doctest::Approx(0.0));
  CHECK(w[4] == doctest::Approx(1.0));
  for (int n = 1; n < 8; ++n) CHECK(w[static_cast<std::size_t>(n)] == doctest::Approx(w[static_cast<std::size_t>(8 - n)]));
}

TEST_CASE("window names round-trip, accept boxcar and hanning, and an unknown name lists the allowed ones") {
  for (WindowKind k : {WindowKind::kRectangular, WindowKind::kHann, WindowKind::kHamming,
                       WindowKind::kBlackmanHarris, WindowKind::kFlatTop})
    CHECK(ParseWindowKind(ToString(k)) == k);
  CHECK(ParseWindowKind("boxcar") == WindowKind::kRectangular);
  CHECK(ParseWindowKind("hanning") == WindowKind::kHann);
  CHECK(InputErrorText([] { ParseWindowKind("kaiser"); })
            .find("'kaiser'; allowed: rectangular, hann, hamming, blackman_harris, flattop") != std::string::npos);
  CHECK_THROWS_AS(MakeWindow(WindowKind::kHann, 0), InputError);
}

}  // namespace
}  // namespace deb
