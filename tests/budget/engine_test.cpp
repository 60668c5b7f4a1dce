#include "deb/budget/engine.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/spectra/channel_set.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/transfer_function.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
using Eigen::MatrixXd;
constexpr double kPi = 3.141592653589793238462643383279502884;
constexpr double kTwoPi = 2.0 * kPi;

std::vector<std::string> Numbered(const std::string& stem, int count) {
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) names.push_back(stem + std::to_string(i));
  return names;
}

Source MakeSource(std::shared_ptr<const Spectrum> spectrum, const std::string& unit,
                  const std::string& name = "noise") {
  Source s;
  s.name = name;
  s.unit = unit;
  s.channel_names = Numbered("ch", spectrum->channels());
  s.spectrum = std::move(spectrum);
  return s;
}

Source WhiteSource(double s0, const std::string& unit, const std::string& name = "noise") {
  return MakeSource(std::make_shared<FlatSpectrum>(s0), unit, name);
}

// Inputs u0, u1, ... all in in_unit; outputs y0, y1, ... all in out_unit.
Path MakePath(const StateSpace& sys, const std::string& in_unit, const std::string& out_unit,
              const std::string& name = "plant") {
  Path p;
  p.name = name;
  p.system = sys;
  p.input_names = Numbered("u", sys.inputs());
  p.output_names = Numbered("y", sys.outputs());
  p.input_units.assign(sys.inputs(), in_unit);
  p.output_units.assign(sys.outputs(), out_unit);
  return p;
}

// One source, one path, one contributor; one output per path row, all in out_unit.
Budget OnePathBudget(const Source& source, const Path& path, const std::string& out_unit,
                     ExactVariance exact = ExactVariance::kAuto) {
  Budget b;
  b.name = "test budget";
  b.sources = {source};
  b.paths = {path};
  b.contributors = {{"c", source.name, path.name, exact, {}, {}, false}};
  for (int i = 0; i < path.system.outputs(); ++i) {
    Output o;
    o.name = "out" + std::to_string(i);
    o.signal = path.output_names[i];
    o.unit = out_unit;
    b.outputs.push_back(o);
  }
  return b;
}

void UseAutoRange(Budget* b, double min_hz, double max_hz) {
  b->grid.kind = GridKind::kAuto;
  b->grid.range_given = true;
  b->grid.auto_options.min_hz = min_hz;
  b->grid.auto_options.max_hz = max_hz;
}

StateSpace Tf(std::vector<double> num, std::vector<double> den) {
  return ToStateSpace(TransferFunction(std::move(num), std::move(den)));
}

// The InputError thrown by fn (fails the test if none is thrown).
template <typename F>
InputError ErrorOf(F&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError thrown");
  return InputError("");
}

using test::Contains;

double RelDiff(double a, double b) { return std::abs(a - b) / std::abs(b); }

// Integral over [w1, w2] rad/s of |H(j w)|^2 for H(s) = 1/((s - p1)(s - p2)),
// Re p < 0. H(s)H(-s) = F(s) + F(-s) with F(s) = sum_k c_k/(s - p_k),
// c_k = Res_{p_k} H(s)H(-s); hence |H(jw)|^2 = 2 Re F(jw), and
// int dw/(jw - p) = -j log(jw - p), continuous on the principal branch since
// jw - p stays in the right half plane.
double SecondOrderGain2Integral(Complex p1, Complex p2, double w1, double w2) {
  const Complex j(0.0, 1.0);
  const Complex p[2] = {p1, p2};
  Complex sum = 0.0;
  for (int k = 0; k < 2; ++k) {
    const Complex other = p[1 - k];
    const Complex c = 1.0 / ((p[k] - other) * (-p[k] - p1) * (-p[k] - p2));
    sum += -j * c * (std::log(j * w2 - p[k]) - std::log(j * w1 - p[k]));
  }
  return 2.0 * sum.real();
}

}  // namespace

TEST_CASE("a first-order low-pass under flat noise has variance S0/(4 tau) and the atan CPS") {
  const double tau = 0.01, s0 = 2.5;
  Budget b = OnePathBudget(WhiteSource(s0, "V"), MakePath(Tf({1.0}, {tau, 1.0}), "V", "V"), "V");
  UseAutoRange(&b, 1e-4, 1e6);
  const BudgetResult r = Evaluate(b);
  const ContributorResult& c = r.outputs[0].contributors[0];

  // Lyapunov: 1e-10 relative.
  REQUIRE(c.exact_variance.has_value());
  CHECK(*c.exact_variance == doctest::Approx(s0 / (4 * tau)).epsilon(1e-10));

  // CPS at every grid point against S0/(2 pi tau) [atan(2 pi tau f)]_{f_min}^{f}: 1e-4 relative.
  const std::vector<double>& f = r.grid.f_hz();
  const auto closed = [&](double hi) {
    return s0 / (kTwoPi * tau) * (std::atan(kTwoPi * tau * hi) - std::atan(kTwoPi * tau * f.front()));
  };
  double worst = 0.0;
  for (std::size_t k = 1; k < f.size(); ++k) worst = std::max(worst, RelDiff(c.cps[k], closed(f[k])));
  MESSAGE("low-pass CPS: worst relative deviation " << worst << " over " << f.size() << " points");
  CHECK(worst < 1e-4);
  CHECK(r.warnings.empty());
}

TEST_CASE("a contributor's result names its source and path, so writers need not re-align with the budget") {
  Budget b = OnePathBudget(WhiteSource(1.0, "V"), MakePath(Tf({1.0}, {0.01, 1.0}), "V", "V"), "V");
  b.sources[0].name = "amplifier";
  b.paths[0].name = "filter";
  b.contributors[0].source = "amplifier";
  b.contributors[0].path = "filter";
  UseAutoRange(&b, 1e-2, 1e3);
  const BudgetResult r = Evaluate(b);
  const ContributorResult& c = r.outputs[0].contributors[0];
  CHECK(c.name == "c");
  CHECK(c.source == "amplifier");
  CHECK(c.path == "filter");
}

TEST_CASE("a mass-spring-damper under flat force noise has sigma^2 = W/(2ck) and sigma_v^2 = W/(2cm)") {
  // W = S0/2 (two-sided); Lyapunov 1e-10 relative, grid CPS over 1e-4..1e5 Hz 1e-4 relative.
  const double m = 2.0, c = 3.0, k = 5000.0, s0 = 0.7, w = s0 / 2;
  // States (x, v): x' = v, m v' = -k x - c v + F.
  const StateSpace msd(MatrixXd{{0.0, 1.0}, {-k / m, -c / m}}, MatrixXd{{0.0}, {1.0 / m}},
                       MatrixXd{{1.0, 0.0}, {0.0, 1.0}}, MatrixXd::Zero(2, 1));
  Path p = MakePath(msd, "N", "m");
  p.output_units = {"m", "m/s"};
  Budget b = OnePathBudget(WhiteSource(s0, "N"), p, "m");
  b.outputs[1].unit = "m/s";
  UseAutoRange(&b, 1e-4, 1e5);
  const BudgetResult r = Evaluate(b);
  const ContributorResult& x = r.outputs[0].contributors[0];
  const ContributorResult& v = r.outputs[1].contributors[0];
  REQUIRE(x.exact_variance.has_value());
  REQUIRE(v.exact_variance.has_value());
  CHECK(*x.exact_variance == doctest::Approx(w / (2 * c * k)).epsilon(1e-10));
  CHECK(*x.exact_variance == doctest::Approx(s0 / (4 * c * k)).epsilon(1e-10));
  CHECK(*v.exact_variance == doctest::Approx(w / (2 * c * m)).epsilon(1e-10));
  // Displacement falls as f^-4 beyond 1e5 Hz (negligible tail); velocity as
  // f^-2, tail S(f_max) f_max ~ 1e-7 relative here.
  CHECK(RelDiff(x.variance, *x.exact_variance) < 1e-4);
  CHECK(RelDiff(v.variance, *v.exact_variance) < 1e-4);
  CHECK(r.warnings.empty());
}

TEST_CASE("a lightly damped resonance is integrated to 1e-4 on the automatic grid") {
  // Acceptance criterion: H = 1/(s^2 + 2 zeta w_n s + w_n^2), f_n = 10 Hz,
  // default automatic grid [0.1, 1000] Hz. Reference: the closed-form
  // integral of |H|^2 over exactly the grid's range (partial fractions, see
  // SecondOrderGain2Integral); CPS = S0/(2 pi) int |H(jw)|^2 dw. The
  // reference itself is checked against Lyapunov over [0, inf) first.
  const double f_n = 10.0, s0 = 1e-3, w_n = kTwoPi * f_n;
  for (double zeta : {1e-3, 1e-4}) {
    CAPTURE(zeta);
    const Budget b = OnePathBudget(WhiteSource(s0, "N"),
                                   MakePath(Tf({1.0}, {1.0, 2 * zeta * w_n, w_n * w_n}), "N", "m"), "m");
    const BudgetResult r = Evaluate(b);
    const ContributorResult& c = r.outputs[0].contributors[0];
    const Complex p1(-zeta * w_n, w_n * std::sqrt(1 - zeta * zeta)), p2 = std::conj(p1);

    // Closed form over [0, inf) equals W/(4 zeta w_n^3) = S0/(8 zeta w_n^3)
    // (W = S0/2; the m = 1 case of W/(2ck)) and the Lyapunov variance.
    const double whole = s0 / kTwoPi * SecondOrderGain2Integral(p1, p2, 0.0, 1e12);
    CHECK(whole == doctest::Approx(s0 / (8 * zeta * w_n * w_n * w_n)).epsilon(1e-9));
    REQUIRE(c.exact_variance.has_value());
    CHECK(*c.exact_variance == doctest::Approx(whole).epsilon(1e-9));

    const std::vector<double>& f = r.grid.f_hz();
    CHECK(f.front() == doctest::Approx(0.1).epsilon(1e-15));
    CHECK(f.back() == doctest::Approx(1000.0).epsilon(1e-15));
    const double ref = s0 / kTwoPi * SecondOrderGain2Integral(p1, p2, kTwoPi * f.front(), kTwoPi * f.back());
    const double dev = RelDiff(c.variance, ref);
    MESSAGE("zeta " << zeta << ": CPS " << c.variance << ", closed form " << ref << ", relative deviation "
                    << dev << " on " << f.size() << " points");
    CHECK(dev <= 1e-4);
    // The CPS just below and above the peak against the closed form as well.
    for (double fx : {0.5 * f_n, f_n * (1 - zeta), f_n * (1 + 3 * zeta), 2 * f_n}) {
      std::size_t k = 0;
      while (f[k + 1] <= fx) ++k;
      CAPTURE(f[k]);
      CHECK(RelDiff(c.cps[k],
                    s0 / kTwoPi * SecondOrderGain2Integral(p1, p2, kTwoPi * f.front(), kTwoPi * f[k])) <=
            1e-4);
    }
    CHECK(r.warnings.empty());
  }
}

TEST_CASE("Lyapunov and grid variances of a random 6-state 2x2 system agree to 1e-4") {
  // Diagonal white noise (S0 = 0.3, 1.7); poles 0.5..80 Hz, zeta 0.02..0.5;
  // the grid 1e-5..1e7 Hz covers the bandwidth (f^-2 tail ~ 1e-6 relative).
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto random = [&](int rows, int cols) {
    MatrixXd m(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) m(i, j) = normal(rng);
    return m;
  };
  MatrixXd blocks = MatrixXd::Zero(6, 6);
  const double modes[3][2] = {{0.5, 0.5}, {7.0, 0.02}, {80.0, 0.1}};  // (f_n Hz, zeta)
  for (int i = 0; i < 3; ++i) {
    const double w = kTwoPi * modes[i][0], z = modes[i][1];
    const double re = -z * w, im = w * std::sqrt(1 - z * z);
    blocks.block(2 * i, 2 * i, 2, 2) << re, im, -im, re;
  }
  const MatrixXd t = MatrixXd::Identity(6, 6) + 0.3 * random(6, 6);
  const StateSpace sys(t * blocks * t.inverse(), random(6, 2), random(2, 6), MatrixXd::Zero(2, 2));
  REQUIRE(sys.IsStable());

  auto parts = std::vector<std::shared_ptr<const Spectrum>>{std::make_shared<FlatSpectrum>(0.3),
                                                            std::make_shared<FlatSpectrum>(1.7)};
  Budget b = OnePathBudget(MakeSource(std::make_shared<IndependentChannels>(parts), "N"),
                           MakePath(sys, "N", "m"), "m", ExactVariance::kRequired);
  UseAutoRange(&b, 1e-5, 1e7);
  const BudgetResult r = Evaluate(b);
  CHECK(r.warnings.empty());
  const MatrixXd cov = OutputCovariance(sys, MatrixXd{{0.15, 0.0}, {0.0, 0.85}});
  for (int o = 0; o < 2; ++o) {
    const ContributorResult& c = r.outputs[o].contributors[0];
    REQUIRE(c.exact_variance.has_value());
    CHECK(*c.exact_variance == doctest::Approx(cov(o, o)).epsilon(1e-12));
    const double dev = RelDiff(c.variance, *c.exact_variance);
    MESSAGE("output " << o << ": grid vs Lyapunov relative deviation " << dev);
    CHECK(dev <= 1e-4);
  }
}

TEST_CASE("a velocity source read as a displacement output is scaled by (1000/(2 pi f))^2") {
  // um/s -> um/s unit-gain path, output in nm: S_nm = S_um/s (1e3/(2 pi f))^2; 1e-12 relative.
  const double s0 = 4.0;
  const Budget b = OnePathBudget(WhiteSource(s0, "um/s"),
                                 MakePath(StateSpace::Gain(MatrixXd::Identity(1, 1)), "um/s", "um/s"), "nm");
  const BudgetResult r = Evaluate(b);
  const std::vector<double>& f = r.grid.f_hz();
  const std::vector<double>& psd = r.outputs[0].contributors[0].psd;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double g = 1e3 / (kTwoPi * f[k]);
    CHECK(psd[k] == doctest::Approx(s0 * g * g).epsilon(1e-12));
  }
  // A time integration is no rational path: no exact variance, and a note saying why.
  CHECK_FALSE(r.outputs[0].contributors[0].exact_variance.has_value());
  CHECK(Contains(r.outputs[0].contributors[0].exact_note, "derivative"));
}

TEST_CASE("a source in m/s entering a path in um/s is scaled by 1e12 in PSD") {
  // 1e-12 relative, and the exact variance carries the same factor.
  const double s0 = 3e-15, tau = 0.1;
  const Budget b =
      OnePathBudget(WhiteSource(s0, "m/s"), MakePath(Tf({1.0}, {tau, 1.0}), "um/s", "um/s"), "um/s");
  const BudgetResult r = Evaluate(b);
  const std::vector<double>& f = r.grid.f_hz();
  const ContributorResult& c = r.outputs[0].contributors[0];
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double x = kTwoPi * tau * f[k];
    CHECK(c.psd[k] == doctest::Approx(1e12 * s0 / (1 + x * x)).epsilon(1e-12));
  }
  REQUIRE(c.exact_variance.has_value());
  CHECK(*c.exact_variance == doctest::Approx(1e12 * s0 / (4 * tau)).epsilon(1e-10));
}

TEST_CASE("an output unit that is not the path's quantity is rejected at outputs[0].unit") {
  const Budget b = OnePathBudget(WhiteSource(1.0, "um/s"),
                                 MakePath(StateSpace::Gain(MatrixXd::Identity(1, 1)), "um/s", "um/s"), "N");
  const InputError e = ErrorOf([&] { b.Validate(); });
  CHECK(e.key_path() == "outputs[0].unit");
  CHECK(Contains(e.what(), "um/s"));
  CHECK(Contains(e.what(), "N"));
  CHECK(ErrorOf([&] { Evaluate(b); }).key_path() == "outputs[0].unit");
}

TEST_CASE("correlated channels propagate as |h1|^2 S1 + |h2|^2 S2 + 2 rho sqrt(S1 S2) Re(h1 conj h2)") {
  // h1 = 3/(s + 3), h2 = (s + 1)/(s^2 + s + 40); S1 = 0.5, S2 = 2; 1e-12
  // relative per grid point (no cancellation: sqrt(S1) 3 != sqrt(S2) at high f).
  const TransferFunction t1({3.0}, {1.0, 3.0}), t2({1.0, 1.0}, {1.0, 1.0, 40.0});
  const StateSpace sys = ToStateSpace(std::vector<std::vector<TransferFunction>>{{t1, t2}});
  const double s1 = 0.5, s2 = 2.0;
  const auto base = std::make_shared<IndependentChannels>(std::vector<std::shared_ptr<const Spectrum>>{
      std::make_shared<FlatSpectrum>(s1), std::make_shared<FlatSpectrum>(s2)});
  for (double rho : {-1.0, 0.0, 0.6, 1.0}) {
    CAPTURE(rho);
    const auto corr = std::make_shared<CorrelatedChannels>(base, MatrixXd{{1.0, rho}, {rho, 1.0}});
    CHECK(corr->IsDiagonal() == (rho == 0.0));
    Budget b = OnePathBudget(MakeSource(corr, "N"), MakePath(sys, "N", "m"), "m");
    UseAutoRange(&b, 1e-5, 1e6);  // flat below 0.5 Hz, f^-2 above 1 Hz: tails < 1e-5 relative
    const BudgetResult r = Evaluate(b);
    CHECK(r.warnings.empty());
    const std::vector<double>& f = r.grid.f_hz();
    const std::vector<double>& psd = r.outputs[0].contributors[0].psd;
    double worst = 0.0;
    for (std::size_t k = 0; k < f.size(); ++k) {
      const Complex s(0.0, kTwoPi * f[k]);
      const Complex h1 = t1.Evaluate(s), h2 = t2.Evaluate(s);
      const double expected = std::norm(h1) * s1 + std::norm(h2) * s2 +
                              2 * rho * std::sqrt(s1 * s2) * (h1 * std::conj(h2)).real();
      worst = std::max(worst, RelDiff(psd[k], expected));
    }
    MESSAGE("rho " << rho << ": worst relative deviation " << worst);
    CHECK(worst <= 1e-12);
    // White correlated source: the exact variance exists and matches the grid (1e-4).
    const ContributorResult& c = r.outputs[0].contributors[0];
    REQUIRE(c.exact_variance.has_value());
    CHECK(RelDiff(c.variance, *c.exact_variance) <= 1e-4);
  }
}

TEST_CASE("a band-limited correlated source into inputs of different units follows the hand formula") {
  // Source in um/s, flat up to 50 Hz (not white: S_u is evaluated per
  // frequency); input 0 in um/s, input 1 in um, so channel 2 is integrated:
  // g1 = h1, g2 = h2/(j w). 1e-12 relative per grid point; exactly 0 above 50 Hz.
  const TransferFunction t1({3.0}, {1.0, 3.0}), t2({1.0, 1.0}, {1.0, 1.0, 40.0});
  Path p = MakePath(ToStateSpace(std::vector<std::vector<TransferFunction>>{{t1, t2}}), "um/s", "um");
  p.input_units = {"um/s", "um"};
  const double s1 = 0.5, s2 = 2.0, f_hi = 50.0;
  const auto base = std::make_shared<IndependentChannels>(std::vector<std::shared_ptr<const Spectrum>>{
      std::make_shared<FlatSpectrum>(s1, 0.0, f_hi), std::make_shared<FlatSpectrum>(s2, 0.0, f_hi)});
  for (double rho : {-1.0, 0.0, 0.6, 1.0}) {
    CAPTURE(rho);
    const auto corr = std::make_shared<CorrelatedChannels>(base, MatrixXd{{1.0, rho}, {rho, 1.0}});
    const BudgetResult r = Evaluate(OnePathBudget(MakeSource(corr, "um/s"), p, "um"));
    const std::vector<double>& f = r.grid.f_hz();
    const std::vector<double>& psd = r.outputs[0].contributors[0].psd;
    double worst = 0.0;
    for (std::size_t k = 0; k < f.size(); ++k) {
      const Complex s(0.0, kTwoPi * f[k]);
      const Complex g1 = t1.Evaluate(s), g2 = t2.Evaluate(s) / s;
      const double expected = f[k] > f_hi ? 0.0
                                          : std::norm(g1) * s1 + std::norm(g2) * s2 +
                                                2 * rho * std::sqrt(s1 * s2) * (g1 * std::conj(g2)).real();
      if (expected == 0.0)
        CHECK(psd[k] == 0.0);
      else
        worst = std::max(worst, RelDiff(psd[k], expected));
    }
    MESSAGE("rho " << rho << ": worst relative deviation " << worst);
    CHECK(worst <= 1e-12);
    CHECK(Contains(r.outputs[0].contributors[0].exact_note, "not white"));
  }
}

TEST_CASE("a static gain mixes fully coherent channels exactly") {
  // y = 2 u1 - 3 u2, S1 = 1, S2 = 4, rho = 1: 4 + 36 - 2*2*3*2 = 16; rho = -1: 64.
  const auto base = std::make_shared<IndependentChannels>(std::vector<std::shared_ptr<const Spectrum>>{
      std::make_shared<FlatSpectrum>(1.0), std::make_shared<FlatSpectrum>(4.0)});
  for (const auto& rho_expected : {std::pair{1.0, 16.0}, std::pair{-1.0, 64.0}, std::pair{0.0, 40.0}}) {
    const double rho = rho_expected.first, expected = rho_expected.second;
    CAPTURE(rho);
    const auto corr = std::make_shared<CorrelatedChannels>(base, MatrixXd{{1.0, rho}, {rho, 1.0}});
    const Budget b = OnePathBudget(MakeSource(corr, "N"),
                                   MakePath(StateSpace::Gain(MatrixXd{{2.0, -3.0}}), "N", "N"), "N");
    const BudgetResult r = Evaluate(b);
    for (double s : r.outputs[0].contributors[0].psd) CHECK(s == doctest::Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("contributors add up: total CPS, shares of variance and band variances") {
  // Two flat sources through unit gains; bands [1, 10] and [10, 100] Hz give
  // S0 * 9 and S0 * 90 (1e-12 relative).
  const double s_a = 2.0, s_b = 0.5;
  Budget b = OnePathBudget(WhiteSource(s_a, "um", "a"),
                           MakePath(StateSpace::Gain(MatrixXd::Identity(1, 1)), "um", "um", "pa"), "um");
  b.sources.push_back(WhiteSource(s_b, "um", "b"));
  b.paths.push_back(MakePath(Tf({1.0}, {0.01, 1.0}), "um", "um", "pb"));
  b.contributors.push_back({"d", "b", "pb", ExactVariance::kAuto, {}, {}, false});
  b.bands = {{1.0, 10.0}, {10.0, 100.0}};
  const BudgetResult r = Evaluate(b);
  const OutputResult& out = r.outputs[0];
  REQUIRE(out.contributors.size() == 2);
  const std::size_t n = r.grid.size();
  for (std::size_t k = 0; k < n; ++k) {
    CHECK(out.total_psd[k] ==
          doctest::Approx(out.contributors[0].psd[k] + out.contributors[1].psd[k]).epsilon(1e-14));
    CHECK(out.total_cps[k] ==
          doctest::Approx(out.contributors[0].cps[k] + out.contributors[1].cps[k]).epsilon(1e-12));
  }
  CHECK(out.contributors[0].variance / out.variance + out.contributors[1].variance / out.variance ==
        doctest::Approx(1.0).epsilon(1e-12));
  CHECK(out.rms() == doctest::Approx(std::sqrt(out.total_cps.back())).epsilon(1e-15));
  const std::vector<double> rev = ReverseCps(out.total_cps);
  CHECK(rev.front() == doctest::Approx(out.variance).epsilon(1e-15));
  CHECK(rev.back() == 0.0);

  REQUIRE(out.bands.size() == 2);
  CHECK(out.bands[0].contributor_variance[0] == doctest::Approx(s_a * 9).epsilon(1e-12));
  CHECK(out.bands[1].contributor_variance[0] == doctest::Approx(s_a * 90).epsilon(1e-12));
  for (const BandResult& br : out.bands)
    CHECK(br.variance ==
          doctest::Approx(br.contributor_variance[0] + br.contributor_variance[1]).epsilon(1e-12));
  // Without bands the engine reports decades covering the grid.
  b.bands.clear();
  const BudgetResult d = Evaluate(b);
  REQUIRE(d.outputs[0].bands.size() == 4);  // 0.1..1..10..100..1000 Hz
  double sum = 0.0;
  for (const BandResult& br : d.outputs[0].bands) sum += br.variance;
  CHECK(sum == doctest::Approx(d.outputs[0].variance).epsilon(1e-12));
}

TEST_CASE("a band edge within the grid's tolerance of its end is that end: the band's figure, no abort") {
  // Flat PSD 2 through a unit gain on the explicit grid [1, 10, 100] Hz: [1, 10] holds 18, [10, 100] 180.
  Budget b = OnePathBudget(WhiteSource(2.0, "N"), MakePath(StateSpace::Gain(MatrixXd::Identity(1, 1)), "N", "N"), "N");
  b.grid.kind = GridKind::kExplicit;
  b.grid.f_hz = {1.0, 10.0, 100.0};
  b.bands = {{0.9999999999995, 10.0}, {10.0, 100.00000000000005}};
  b.outputs[0].band_requirements = {{0.9999999999995, 10.0, 1.0}, {10.0, 100.00000000000005, 20.0}};
  const BudgetResult r = Evaluate(b);
  REQUIRE(r.outputs[0].bands.size() == 2);
  CHECK(r.outputs[0].bands[0].variance == doctest::Approx(18.0).epsilon(1e-12));
  CHECK(r.outputs[0].bands[1].variance == doctest::Approx(180.0).epsilon(1e-12));
  CHECK(r.outputs[0].band_requirements[0].variance == doctest::Approx(18.0).epsilon(1e-12));
  CHECK(r.outputs[0].band_requirements[1].variance == doctest::Approx(180.0).epsilon(1e-12));
  // Beyond the tolerance: a located error.
  b.outputs[0].band_requirements.clear();
  b.bands = {{0.99999999, 10.0}};
  CHECK(ErrorOf([&] { Evaluate(b); }).key_path() == "bands[0]");
}

TEST_CASE("the default decade bands are grid points of the automatic grid: as accurate as the same bands given") {
  // Two light resonances astride 10 Hz (zeta 0.01 at 9.7 and 10.4 Hz): a decade edge inside a panel
  // near them was off by up to 3e-4 of the band when it was interpolated.
  const double w1 = kTwoPi * 9.7, w2 = kTwoPi * 10.4;
  Budget b = OnePathBudget(WhiteSource(1.0, "N"), MakePath(Tf({w1 * w1}, {1.0, 0.02 * w1, w1 * w1}), "N", "m"), "m");
  b.sources.push_back(WhiteSource(1.0, "N", "second"));
  b.paths.push_back(MakePath(Tf({w2 * w2}, {1.0, 0.02 * w2, w2 * w2}), "N", "m", "p2"));
  b.contributors.push_back({"d", "second", "p2", ExactVariance::kAuto, {}, {}, false});
  const BudgetResult by_default = Evaluate(b);
  b.bands = {{0.1, 1.0}, {1.0, 10.0}, {10.0, 100.0}, {100.0, 1000.0}};
  const BudgetResult given = Evaluate(b);
  const OutputResult& d = by_default.outputs[0];
  const OutputResult& g = given.outputs[0];
  REQUIRE(d.bands.size() == 4);
  REQUIRE(g.bands.size() == 4);
  double sum = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(d.bands[i].band.lo_hz == g.bands[i].band.lo_hz);
    CHECK(d.bands[i].band.hi_hz == g.bands[i].band.hi_hz);
    CHECK(std::abs(d.bands[i].variance - g.bands[i].variance) <= 1e-12 * d.variance);
    sum += d.bands[i].variance;
  }
  CHECK(std::abs(sum / d.variance - 1.0) < 1e-12);
  // The grid holds each decade as a breakpoint: points at decade (1 -+ 1e-9), a power-law step between.
  const std::vector<double>& f = by_default.grid.f_hz();
  for (const double decade : {1.0, 10.0, 100.0}) {
    const auto above = std::lower_bound(f.begin(), f.end(), decade);
    REQUIRE(above != f.begin());
    CHECK(*above / decade - 1.0 == doctest::Approx(1e-9).epsilon(1e-3));
    CHECK(1.0 - *(above - 1) / decade == doctest::Approx(1e-9).epsilon(1e-3));
  }
}

TEST_CASE("misuse of the public API throws InputError, never aborts") {
  Budget b = OnePathBudget(WhiteSource(1.0, "N", "floor"), MakePath(Tf({1.0}, {1.0, 1.0}), "N", "m", "stage"), "m");
  InputError e = ErrorOf([&] { b.FindSource("flor"); });
  CHECK(e.key_path() == "sources");
  CHECK(Contains(e.what(), "no source named 'flor'"));
  CHECK(Contains(e.what(), "did you mean 'floor'"));
  e = ErrorOf([&] { b.FindPath("stag"); });
  CHECK(e.key_path() == "paths");
  CHECK(Contains(e.what(), "did you mean 'stage'"));
  CHECK(&b.FindSource("floor") == &b.sources[0]);
  EngineOptions options;
  for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    options.exact_tolerance = bad;
    std::string why;
    CHECK_FALSE(options.IsValid(&why));
    CHECK(Contains(why, "exact_tolerance"));
    CHECK(Contains(ErrorOf([&] { Evaluate(b, options); }).what(), "must be finite and > 0"));
  }
  // A band a hair outside an explicit grid (it aborted in IntegralBetween).
  b.grid.kind = GridKind::kExplicit;
  b.grid.f_hz = {1.0, 10.0, 100.0};
  b.bands = {{0.9999999999995, 10.0}};
  CHECK_NOTHROW(Evaluate(b));
  b.bands = {{0.999999, 10.0}};
  CHECK(ErrorOf([&] { Evaluate(b); }).key_path() == "bands[0]");
}

TEST_CASE("a source whose channel count differs from the path's inputs is rejected") {
  const Budget b =
      OnePathBudget(WhiteSource(1.0, "N"), MakePath(StateSpace::Gain(MatrixXd{{1.0, 1.0}}), "N", "N"), "N");
  const InputError e = ErrorOf([&] { Evaluate(b); });
  CHECK(e.key_path() == "contributors[0]");
  CHECK(Contains(e.what(), "1 channel(s)"));
  CHECK(Contains(e.what(), "2 input(s)"));
}

TEST_CASE("an unstable path is rejected, naming its pole") {
  const Budget b = OnePathBudget(WhiteSource(1.0, "N"), MakePath(Tf({1.0}, {1.0, -1.0}), "N", "m"), "m");
  const InputError e = ErrorOf([&] { Evaluate(b); });
  CHECK(e.key_path() == "contributors[0].path");
  CHECK(Contains(e.what(), "unstable"));
  CHECK(Contains(e.what(), "pole(s) at 1 + 0j rad/s"));
}

TEST_CASE("a required exact variance of a band-limited source is an error at contributors[0].exact") {
  const Budget b = OnePathBudget(MakeSource(std::make_shared<FlatSpectrum>(1.0, 1.0, 100.0), "N"),
                                 MakePath(Tf({1.0}, {1.0, 1.0}), "N", "m"), "m", ExactVariance::kRequired);
  const InputError e = ErrorOf([&] { Evaluate(b); });
  CHECK(e.key_path() == "contributors[0].exact");
  CHECK(Contains(e.what(), "not white"));
}

TEST_CASE("bands must be non-empty and inside an explicit grid") {
  Budget b = OnePathBudget(WhiteSource(1.0, "N"), MakePath(Tf({1.0}, {1.0, 1.0}), "N", "m"), "m");
  b.bands = {{10.0, 10.0}};
  InputError e = ErrorOf([&] { Evaluate(b); });
  CHECK(e.key_path() == "bands[0]");
  CHECK(Contains(e.what(), "empty"));
  b.bands = {{20.0, 5.0}};
  CHECK(ErrorOf([&] { Evaluate(b); }).key_path() == "bands[0]");

  b.grid.kind = GridKind::kExplicit;
  b.grid.f_hz = FrequencyGrid::Log(1.0, 100.0, 50).f_hz();
  b.bands = {{2.0, 50.0}, {50.0, 200.0}};
  e = ErrorOf([&] { Evaluate(b); });
  CHECK(e.key_path() == "bands[1]");
  CHECK(Contains(e.what(), "beyond the frequency grid"));
  b.bands = {{2.0, 50.0}};
  CHECK_NOTHROW(Evaluate(b));
}

}  // namespace deb
