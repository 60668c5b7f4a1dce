#include "deb/core/integrate.h"

#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "deb/core/frequency_grid.h"

namespace deb {

namespace {

// The Lobatto panels [1, 2] and [2, 5] (kPanelNodes points each, sharing
// 2 Hz), then the points `after` (> 5 Hz): panel starts {0, kPanelNodes - 1}.
std::vector<double> PanelsThen(const std::vector<double>& after) {
  const std::vector<double>& x = FrequencyGrid::LobattoNodes();
  std::vector<double> f;
  for (const auto& [a, b] : {std::pair<double, double>{1.0, 2.0}, {2.0, 5.0}})
    for (std::size_t j = f.empty() ? 0 : 1; j < x.size(); ++j) f.push_back(a + 0.5 * (b - a) * (x[j] + 1.0));
  f.insert(f.end(), after.begin(), after.end());
  return f;
}

}  // namespace

TEST_CASE("a power law is integrated exactly whatever the grid spacing") {
  // s = 3 f^-2 on [1, 100] has integral 3 (1 - 1/100) = 2.97.
  const std::vector<double> f = FrequencyGrid::Log(1.0, 100.0, 5).f_hz();
  std::vector<double> s;
  for (double x : f) s.push_back(3.0 * std::pow(x, -2.0));
  const auto c = CumulativeIntegral(f, s);
  CHECK(c.back() == doctest::Approx(2.97).epsilon(1e-12));
}

TEST_CASE("the 1/f power law integrates to a logarithm") {
  const std::vector<double> f = {1.0, 10.0};
  CHECK(CumulativeIntegral(f, {1.0, 0.1}).back() == doctest::Approx(std::log(10.0)).epsilon(1e-12));
}

TEST_CASE("an interval with a zero end falls back to the trapezoid") {
  CHECK(PowerLawIntervalIntegral(1.0, 3.0, 0.0, 2.0) == doctest::Approx(2.0).epsilon(1e-15));
}

TEST_CASE("a partial-interval integral agrees with the full cumulative integral") {
  const std::vector<double> f = FrequencyGrid::Log(0.1, 1000.0, 41).f_hz();
  std::vector<double> s;
  for (double x : f) s.push_back(1.0 / (1.0 + x * x));
  const auto c = CumulativeIntegral(f, s);
  CHECK(IntegralBetween(f, s, f.front(), f.back()) == doctest::Approx(c.back()).epsilon(1e-13));
  // Splitting at a point inside an interval changes nothing for a power law segment.
  const double mid = 3.3;
  CHECK(IntegralBetween(f, s, f.front(), mid) + IntegralBetween(f, s, mid, f.back()) ==
        doctest::Approx(c.back()).epsilon(1e-13));
}

TEST_CASE("the cumulative integral is the same, bit for bit, on one thread and on four") {
  const std::vector<double> f = FrequencyGrid::Log(0.01, 1000.0, 20001).f_hz();
  std::vector<double> s;
  for (double x : f) s.push_back(1.0 / (1.0 + std::pow(x - 3.0, 2)));
  CHECK(CumulativeIntegral(f, s, 1) == CumulativeIntegral(f, s, 4));
}

TEST_CASE("a flat spectrum's band integral is level times bandwidth") {
  const std::vector<double> f = {0.5, 2.0, 7.0};
  const std::vector<double> s = {4.0, 4.0, 4.0};
  CHECK(IntegralBetween(f, s, 1.0, 5.0) == doctest::Approx(16.0).epsilon(1e-14));
}

TEST_CASE("the linear quadrature weights: the Lobatto rule on panels, the trapezoid between them") {
  // Panels on [1, 2] and [2, 5], then plain intervals 5-6-8.
  const std::vector<double> f = PanelsThen({6.0, 8.0});
  const FrequencyGrid grid(f, {0, 5});
  const std::vector<double> q = LinearQuadratureWeights(grid);
  REQUIRE(q.size() == f.size());
  // On the panels alone, a degree-9 polynomial is integrated exactly, as
  // their CumulativeIntegral does.
  const FrequencyGrid panels(std::vector<double>(f.begin(), f.begin() + 11), {0, 5});
  const std::vector<double> qp = LinearQuadratureWeights(panels);
  std::vector<double> s(panels.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = 1.0 + std::pow(panels.f_hz()[i] - 1.0, 9);
  double integral = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) integral += qp[i] * s[i];
  CHECK(integral == doctest::Approx(4.0 + std::pow(4.0, 10) / 10.0).epsilon(1e-13));
  CHECK(integral == doctest::Approx(CumulativeIntegral(panels, s).back()).epsilon(1e-13));
  for (std::size_t i = 0; i < 10; ++i) CHECK(q[i] == qp[i]);
  // The intervals 5-6 and 6-8 by the trapezoid: 5 Hz gets the panel's last
  // Lobatto weight and 0.5, 6 Hz 0.5 + 1, 8 Hz 1.
  CHECK(q[10] == doctest::Approx(1.5 * FrequencyGrid::LobattoCumulativeWeights()[5][5] + 0.5).epsilon(1e-14));
  CHECK(q[11] == doctest::Approx(1.5).epsilon(1e-14));
  CHECK(q[12] == doctest::Approx(1.0).epsilon(1e-14));
  double total = 0.0;
  for (const double w : q) total += w;
  CHECK(total == doctest::Approx(8.0 - 1.0).epsilon(1e-14));  // a constant is integrated exactly
}

}  // namespace deb

namespace deb {

TEST_CASE("the integral's derivative weights: Lobatto on panels, the power law's partial derivatives elsewhere") {
  // Panels on [1, 2] and [2, 5], then power-law intervals 5-6-8-9 and an
  // interval with a zero end, 9-10.
  const std::vector<double> f = PanelsThen({6.0, 8.0, 9.0, 10.0});
  const FrequencyGrid grid(f, {0, 5});
  std::vector<double> s(f.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = 3.0 / (1.0 + f[i]);
  // f: 0-10 the panels (6 nodes each, sharing 2 Hz), 11: 6 Hz, 12: 8, 13: 9, 14: 10.
  REQUIRE(f.size() == 15);
  s[13] = s[12] * 8.0 / 9.0;  // s f equal at 8 and 9 Hz: the series branch (e = 0)
  s.back() = 0.0;             // the trapezoid's interval
  const std::vector<double> q = IntegralGradientWeights(grid, s);
  const std::vector<double> lin = LinearQuadratureWeights(grid);
  for (std::size_t i = 0; i < 10; ++i) CHECK(q[i] == lin[i]);  // panels: linear in s
  // The integral is homogeneous of degree 1 in s (Euler): sum q_i s_i = I.
  double euler = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) euler += q[i] * s[i];
  CHECK(euler == doctest::Approx(CumulativeIntegral(grid, s).back()).epsilon(1e-14));
  // Each weight against a central difference of the integral (step 1e-4
  // relative, truncation ~1e-9 relative of the weight). Not at a zero: the
  // power law is not differentiable there (a PSD's derivative is zero
  // where the PSD is: dS = 2 Re(h S_u dh^H) with h S_u^(1/2) = 0).
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const double ds = 1e-4 * s[i];
    std::vector<double> up = s, down = s;
    up[i] += ds;
    down[i] -= ds;
    const double cd = (CumulativeIntegral(grid, up).back() - CumulativeIntegral(grid, down).back()) / (up[i] - down[i]);
    CHECK(q[i] == doctest::Approx(cd).epsilon(1e-7));
  }
  // The closed form on one interval, 6-8 Hz: dI/ds1 = L f1 g(e), g(e) = (e^e - 1 - e)/e^2.
  const double L = std::log(8.0 / 6.0), e = std::log(s[12] * 8.0 / (s[11] * 6.0));
  const double from_6_to_8 = L * 6.0 * (std::exp(e) - 1.0 - e) / (e * e);
  const double from_5_to_6 = q[11] - from_6_to_8;  // 6 Hz's weight is the sum of both intervals'
  const double L0 = std::log(6.0 / 5.0), e0 = std::log(s[11] * 6.0 / (s[10] * 5.0));
  CHECK(from_5_to_6 == doctest::Approx(L0 * 6.0 * (std::exp(-e0) - 1.0 + e0) / (e0 * e0)).epsilon(1e-12));
}

}  // namespace deb
