#include "deb/systems/lyapunov.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <complex>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/modes.h"
#include "deb/systems/transfer_function.h"
#include "polynomial_reference.h"
#include "test_util.h"

namespace deb {
namespace {

using Eigen::MatrixXd;
using testing::Contains;
using testing::MessageOf;

MatrixXd Scalar(double v) { return MatrixXd::Constant(1, 1, v); }

TEST_CASE("a first-order low-pass has H2 norm squared 1/(2 tau)") {
  // Unit two-sided intensity gives sigma^2 = ||H||_2^2 = 1/(2 tau); a
  // one-sided white level S0 (W = S0/2) gives S0/(4 tau). Tolerance 1e-12.
  const double tau = 0.025, s0 = 3.0;
  const StateSpace lp = ToStateSpace(TransferFunction({1.0}, {tau, 1.0}));
  CHECK(OutputCovariance(lp, Scalar(1.0))(0, 0) == doctest::Approx(1.0 / (2 * tau)).epsilon(1e-12));
  CHECK(OutputCovariance(lp, Scalar(s0 / 2))(0, 0) ==
        doctest::Approx(s0 / (4 * tau)).epsilon(1e-12));
}

TEST_CASE("a mass-spring-damper under white force has variances W/(2ck) and W/(2cm)") {
  // m x'' + c x' + k x = F, F white with two-sided intensity W; state (x, v).
  // Displacement and velocity are uncorrelated. Tolerance 1e-10.
  const double m = 2.1, c = 0.35, k = 480.0, w = 0.7;
  MatrixXd a(2, 2), b(2, 1);
  a << 0.0, 1.0, -k / m, -c / m;
  b << 0.0, 1.0 / m;
  const StateSpace msd(a, b, MatrixXd::Identity(2, 2), MatrixXd::Zero(2, 1));
  const MatrixXd cov = OutputCovariance(msd, Scalar(w));
  CHECK(cov(0, 0) == doctest::Approx(w / (2 * c * k)).epsilon(1e-10));
  CHECK(cov(1, 1) == doctest::Approx(w / (2 * c * m)).epsilon(1e-10));
  CHECK(std::abs(cov(0, 1)) <= 1e-10 * std::sqrt(cov(0, 0) * cov(1, 1)));
  // The same through the transfer function 1/(m s^2 + c s + k).
  const StateSpace tf = ToStateSpace(TransferFunction({1.0}, {m, c, k}));
  CHECK(OutputCovariance(tf, Scalar(w))(0, 0) == doctest::Approx(w / (2 * c * k)).epsilon(1e-10));
}

TEST_CASE("SolveLyapunov leaves a residual below 1e-10 |Q| on a random stable 20x20") {
  std::mt19937 rng(20);
  const MatrixXd r = testing::RandomMatrix(20, 20, rng);
  const double spectral_abscissa = Eigen::EigenSolver<MatrixXd>(r).eigenvalues().real().maxCoeff();
  const MatrixXd a = r - (spectral_abscissa + 0.5) * MatrixXd::Identity(20, 20);
  const MatrixXd g = testing::RandomMatrix(20, 5, rng);
  const MatrixXd q = g * g.transpose();
  const MatrixXd p = SolveLyapunov(a, q);
  CHECK((a * p + p * a.transpose() + q).norm() <= 1e-10 * q.norm());
  CHECK((p - p.transpose()).norm() == 0.0);
  CHECK(Eigen::SelfAdjointEigenSolver<MatrixXd>(p).eigenvalues().minCoeff() > 0.0);
}

TEST_CASE("SolveLyapunov is as accurate for a model in mixed units") {
  // States rescaled by T = diag(1, 1e6, 1, 1e6, ...) (m next to um): A_s =
  // T^-1 A T, Q_s = T^-1 Q T^-1 must give P_s = T^-1 P T^-1 entry by entry,
  // to 1e-10 relative to each entry's own scale sqrt(P_s,ii P_s,jj).
  std::mt19937 rng(23);
  const MatrixXd a = testing::DenseFromModes({{-1.0, -5.0}, {{3.0, 0.02}, {8.0, 0.1}}}, rng);
  const MatrixXd g = testing::RandomMatrix(6, 2, rng);
  const MatrixXd q = g * g.transpose();
  Eigen::VectorXd t(6);
  t << 1.0, 1e6, 1.0, 1e6, 1.0, 1e6;
  const Eigen::VectorXd ti = t.cwiseInverse();
  const MatrixXd p = SolveLyapunov(a, q);
  const MatrixXd ps = SolveLyapunov(ti.asDiagonal() * a * t.asDiagonal(),
                                    ti.asDiagonal() * q * ti.asDiagonal());
  const MatrixXd expected = ti.asDiagonal() * p * ti.asDiagonal();
  double worst = 0.0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      worst = std::max(worst, std::abs(ps(i, j) - expected(i, j)) /
                                  std::sqrt(expected(i, i) * expected(j, j)));
  CHECK(worst <= 1e-10);
}

TEST_CASE("SolveLyapunov handles a non-symmetric Q") {
  // Residual 1e-12 relative for an arbitrary right-hand side.
  std::mt19937 rng(21);
  const MatrixXd a = testing::DenseFromModes({{-1.0, -5.0}, {{3.0, 0.2}, {8.0, 0.01}}}, rng);
  const MatrixXd q = testing::RandomMatrix(6, 6, rng);
  const MatrixXd p = SolveLyapunov(a, q);
  CHECK((a * p + p * a.transpose() + q).norm() <= 1e-12 * (a.norm() * p.norm() + q.norm()));
}

TEST_CASE("output variance equals the integral of the output PSD over frequency") {
  // Random stable 6-state system, 2 outputs, 3 correlated inputs; variance
  // as (1/pi) int_0^inf diag(H W H^H) dw by Simpson's rule in w = tan(theta).
  // Tolerance 1e-8 relative.
  std::mt19937 rng(22);
  const StateSpace sys =
      testing::RandomSystem({{-0.7, -4.0}, {{2.0, 0.3}, {9.0, 0.1}}}, 2, 3, rng, false);
  const MatrixXd g = testing::RandomMatrix(3, 3, rng);
  const MatrixXd w = g * g.transpose();
  const MatrixXd cov = OutputCovariance(sys, w);
  const FrequencyResponse h(sys);
  const int intervals = 200000;  // even
  const double dt = (M_PI / 2) / intervals;
  // End points: w = 0, and w -> inf where |H|^2 (1 + w^2) -> |C B|^2.
  const Eigen::MatrixXcd h0 = h.At(0.0);
  const MatrixXd cb = sys.C() * sys.B();
  Eigen::VectorXd sum = (h0 * w * h0.adjoint()).diagonal().real() +
                        (cb * w * cb.transpose()).diagonal();
  for (int i = 1; i < intervals; ++i) {
    const double theta = i * dt, omega = std::tan(theta);
    const Eigen::MatrixXcd hf = h.At(omega / (2 * M_PI));
    const Eigen::VectorXd psd = (hf * w * hf.adjoint()).diagonal().real();
    sum += (i % 2 ? 4.0 : 2.0) * psd * (1.0 + omega * omega);
  }
  const Eigen::VectorXd integral = sum * dt / 3.0 / M_PI;
  for (int i = 0; i < 2; ++i) CHECK(integral(i) == doctest::Approx(cov(i, i)).epsilon(1e-8));
}

TEST_CASE("an unstable path is rejected listing the unstable pole") {
  const StateSpace sys(Scalar(0.3), Scalar(1.0), Scalar(1.0), Scalar(0.0));
  const std::string msg = MessageOf([&] { OutputCovariance(sys, Scalar(1.0)); });
  CHECK(Contains(msg, "exact variance needs a stable path"));
  CHECK(Contains(msg, "pole at +0.3 rad/s"));
  // An integrator is not stable either.
  const StateSpace integrator = ToStateSpace(TransferFunction({1.0}, {1.0, 0.0}));
  CHECK(Contains(MessageOf([&] { OutputCovariance(integrator, Scalar(1.0)); }), "pole at"));
  // An undamped pair is listed once, as a pair.
  const StateSpace osc = ToStateSpace(TransferFunction({1.0}, {1.0, 0.0, 4.0}));
  CHECK(Contains(MessageOf([&] { OutputCovariance(osc, Scalar(1.0)); }), "\u00b12j rad/s"));
}

TEST_CASE("direct feedthrough under white noise is rejected as infinite variance") {
  const StateSpace sys = ToStateSpace(TransferFunction({2.0, 1.0}, {1.0, 5.0}));
  CHECK(Contains(MessageOf([&] { OutputCovariance(sys, Scalar(1.0)); }),
                 "infinite variance: direct feedthrough D != 0 under white noise"));
  // Feedthrough from an input without noise does no harm.
  const StateSpace two = StackOutputs(sys, sys).SelectInputs({0});
  const StateSpace mixed = Append(ToStateSpace(TransferFunction({1.0}, {1.0, 5.0})),
                                  StateSpace::Gain(Scalar(1.0)));
  MatrixXd w = MatrixXd::Zero(2, 2);
  w(0, 0) = 1.0;
  CHECK(OutputCovariance(mixed, w)(0, 0) == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(two.outputs() == 2);
}

TEST_CASE("a wrong-sized or asymmetric intensity is rejected") {
  const StateSpace sys = ToStateSpace(TransferFunction({1.0}, {1.0, 5.0}));
  CHECK(Contains(MessageOf([&] { OutputCovariance(sys, MatrixXd::Identity(2, 2)); }),
                 "W is 2x2 but the path has 1 inputs"));
  MatrixXd w(2, 2);
  w << 1.0, 0.5, 0.4, 1.0;
  const StateSpace two = Append(sys, sys);
  CHECK(Contains(MessageOf([&] { OutputCovariance(two, w); }), "not symmetric"));
  CHECK(Contains(MessageOf([&] { OutputCovariance(sys, Scalar(-1.0)); }), "negative"));
}

TEST_CASE("a Lyapunov equation with poles summing to zero is singular") {
  MatrixXd a(2, 2);
  a << 0.0, 1.0, -4.0, 0.0;  // poles +-2j
  const std::string message = MessageOf([&] { SolveLyapunov(a, MatrixXd::Identity(2, 2)); });
  CHECK(Contains(message, "singular equation"));
  // Located: the two poles that sum to zero.
  CHECK(Contains(message, "2j rad/s and "));
  CHECK(Contains(message, "2j rad/s sum to zero"));
  CHECK_THROWS_AS(SolveLyapunov(a, MatrixXd::Identity(3, 3)), InputError);
}

TEST_CASE("a path without states has zero covariance") {
  const MatrixXd cov = OutputCovariance(StateSpace::Gain(MatrixXd::Zero(2, 1)), Scalar(1.0));
  CHECK(cov == MatrixXd::Zero(2, 2));
}


// ---------------------------------------------------------------------------
// Closed-form reference, no matrices. Convention (as OutputCovariance): white
// input of two-sided intensity W = 1, S_y(w) = |H(jw)|^2, so
//   sigma^2 = (1/2pi) int_-inf^inf |H(jw)|^2 dw = (1/2pi j) oint H(s) H(-s) ds
// around the left half plane, = sum over the poles p_i of H (Re < 0, simple)
// of Res_{s=p_i} H(s) H(-s) = sum_i r_i H(-p_i), r_i = Res_{s=p_i} H. For
// H(s) = g / prod_j (s - p_j): r_i = g / prod_{j!=i} (p_i - p_j) and
// H(-p_i) = g / prod_j (-p_i - p_j). Evaluated in long double from the
// factored form. One section H = w^2/(s^2 + 2 zeta w s + w^2) is the
// mass-spring-damper 1/(m s^2 + c s + k) times w^2 with m = 1, c = 2 zeta w,
// k = w^2, whose displacement variance W/(2 c k) gives w^4/(4 zeta w^3) =
// w/(4 zeta).
using LD = long double;
using CLD = std::complex<LD>;

// The closed form, and how far its terms cancel (sum |term| / |sum|).
std::pair<LD, LD> ClosedFormWithCancellation(const std::vector<CLD>& poles, LD gain) {
  CLD sum = 0.0L;
  LD size = 0.0L;
  for (std::size_t i = 0; i < poles.size(); ++i) {
    CLD r = gain, h = gain;
    for (std::size_t j = 0; j < poles.size(); ++j) {
      if (j != i) r /= poles[i] - poles[j];
      h /= -poles[i] - poles[j];
    }
    sum += r * h;
    size += std::abs(r * h);
  }
  return {sum.real(), size / std::abs(sum.real())};
}

LD ClosedFormVariance(const std::vector<CLD>& poles, LD gain) { return ClosedFormWithCancellation(poles, gain).first; }

// Clustered lightly damped modes of the audit: w_k = 2 pi 10 (1 + 0.03 k).
double ModeW(int k) { return 2 * M_PI * 10 * (1 + 0.03 * k); }

std::vector<CLD> SectionPoles(int sections, double zeta) {
  std::vector<CLD> p;
  for (int k = 0; k < sections; ++k) {
    const LD w = ModeW(k), z = zeta;  // the doubles the sections are built from
    p.push_back(CLD(-z * w, w * std::sqrt(1.0L - z * z)));
    p.push_back(std::conj(p.back()));
  }
  return p;
}

LD SectionGain(int sections) {
  LD g = 1.0L;
  for (int k = 0; k < sections; ++k) g *= static_cast<LD>(ModeW(k)) * ModeW(k);
  return g;
}

TEST_CASE("the closed form gives w/(4 zeta) for one second-order section") {
  for (const double zeta : {0.3, 1e-2, 1e-3}) {
    const double w = ModeW(0);
    const LD reference = ClosedFormVariance(SectionPoles(1, zeta), SectionGain(1));
    CHECK(static_cast<double>(reference) == doctest::Approx(w / (4 * zeta)).epsilon(1e-15));
    const StateSpace sec = ToStateSpace(TransferFunction({w * w}, {1.0, 2 * zeta * w, w * w}));
    CHECK(OutputCovariance(sec, Scalar(1.0))(0, 0) ==
          doctest::Approx(w / (4 * zeta)).epsilon(1e-12));
  }
}

TEST_CASE("a cascade of 8 or 10 clustered lightly damped sections matches the closed form") {
  // Series of H_k = w_k^2/(s^2 + 2 zeta w_k s + w_k^2). Before the fix (one
  // dense complex Schur form of the whole cascade, state variances spanning
  // 1e-3 ... 1e13) deb was off by up to 4e-5 (8 sections) and 1.5e-1 (10
  // sections, zeta 1e-3). Tolerance 1e-6 relative (observed ~1e-13).
  for (const int n : {8, 10})
    for (const double zeta : {1e-2, 1e-3}) {
      CAPTURE(n);
      CAPTURE(zeta);
      StateSpace cascade = StateSpace::Gain(Scalar(1.0));
      for (int k = 0; k < n; ++k) {
        const double w = ModeW(k);
        cascade = Series(cascade,
                         ToStateSpace(TransferFunction({w * w}, {1.0, 2 * zeta * w, w * w})));
      }
      const double reference =
          static_cast<double>(ClosedFormVariance(SectionPoles(n, zeta), SectionGain(n)));
      CHECK(OutputCovariance(cascade, Scalar(1.0))(0, 0) ==
            doctest::Approx(reference).epsilon(1e-6));
    }
}

// The same modes as one expanded polynomial, multiplied out in double.
std::vector<double> ExpandedDenominator(int sections, double zeta) {
  std::vector<double> den{1.0};
  for (int k = 0; k < sections; ++k) {
    const double w = ModeW(k), sec[3] = {1.0, 2 * zeta * w, w * w};
    std::vector<double> next(den.size() + 2, 0.0);
    for (std::size_t i = 0; i < den.size(); ++i)
      for (int j = 0; j < 3; ++j) next[i + j] += den[i] * sec[j];
    den = next;
  }
  return den;
}

// The roots of the rounded coefficients: Newton's method in long double on
// the exact double coefficients, started from the intended poles.
std::vector<CLD> RootsNear(const std::vector<double>& p, std::vector<CLD> roots) {
  for (CLD& r : roots)
    for (int it = 0; it < 30; ++it) {
      CLD v = 0.0L, d = 0.0L;
      for (double c : p) {
        d = d * r + v;
        v = v * r + static_cast<LD>(c);
      }
      const CLD step = v / d;
      r -= step;
      if (std::abs(step) <= 1e-18L * std::abs(r)) break;
    }
  return roots;
}

TEST_CASE("clustered modes as one expanded polynomial of order 16 or 20 match the closed form") {
  // The coefficients of the expanded polynomial, rounded to double, do not
  // define the intended system exactly: their roots are up to ~1e-6 |Re p|
  // (order 16) and ~3e-4 |Re p| (order 20) away from the intended poles, and
  // the variance they define differs by ~1e-7 (16) and ~1e-6 (20) from the
  // intended one (one ulp in a coefficient moves it by up to 2e-5 at order
  // 20). So the reference is the closed form of the system the rounded
  // coefficients define: its own roots, found here in long double.
  // Before the fix (companion realisation) the exact variance was negative
  // or off by orders of magnitude. Tolerance 1e-6 relative.
  for (const int n : {8, 10})
    for (const double zeta : {1e-2, 1e-3}) {
      CAPTURE(n);
      CAPTURE(zeta);
      const std::vector<double> den = ExpandedDenominator(n, zeta);
      const double num = static_cast<double>(SectionGain(n));
      const std::vector<CLD> intended = SectionPoles(n, zeta);
      const std::vector<CLD> actual = RootsNear(den, intended);
      LD shift = 0.0L;
      for (std::size_t i = 0; i < intended.size(); ++i)
        shift = std::max(shift, std::abs(actual[i] - intended[i]) / std::abs(intended[i].real()));
      CHECK(shift < 1e-3L);  // the right roots, not neighbours
      const double reference = static_cast<double>(ClosedFormVariance(actual, num));
      const StateSpace tf = ToStateSpace(TransferFunction({num}, den));
      CHECK(tf.states() == 2 * n);
      CHECK(OutputCovariance(tf, Scalar(1.0))(0, 0) == doctest::Approx(reference).epsilon(1e-6));
      // The intended system is within the polynomial's own rounding.
      const double intended_variance =
          static_cast<double>(ClosedFormVariance(intended, SectionGain(n)));
      CHECK(reference == doctest::Approx(intended_variance).epsilon(1e-5));
    }
}

TEST_CASE("an unreliable exact variance is refused, never returned negative") {
  // The companion form of the order-16 polynomial, built by hand: its
  // Lyapunov equation is so ill-conditioned that the computed variance is
  // meaningless (it came out negative); OutputCovariance must say so.
  const std::vector<double> den = ExpandedDenominator(8, 1e-2);
  const int n = 16;
  MatrixXd a = MatrixXd::Zero(n, n), b = MatrixXd::Zero(n, 1), c = MatrixXd::Zero(1, n);
  for (int k = 0; k < n; ++k) a(0, k) = -den[k + 1];
  for (int k = 1; k < n; ++k) a(k, k - 1) = 1.0;
  b(0, 0) = 1.0;
  c(0, n - 1) = static_cast<double>(SectionGain(8));
  const StateSpace companion(a, b, c, MatrixXd::Zero(1, 1));
  const std::string msg = MessageOf([&] { OutputCovariance(companion, Scalar(1.0)); });
  CHECK(Contains(msg, "exact variance is not reliable for this realisation"));
}


// ---------------------------------------------------------------------------
// Stiff cascades: sections at 1e-3 Hz and 1e4 Hz, H = w1^2 w2^2 / (d1 d2).

std::vector<double> Multiply(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

// The states of sys in the order perm (sys.A()(perm, perm), ...): the same
// system as one state space whose block structure is not in the order a
// series connection makes.
StateSpace Permuted(const StateSpace& sys, const std::vector<int>& perm) {
  return StateSpace(sys.A()(perm, perm), sys.B()(perm, Eigen::all), sys.C()(Eigen::all, perm), sys.D());
}

TEST_CASE("a stiff cascade of sections at 1e-3 Hz and 1e4 Hz has its exact variance in all three forms") {
  // Series, one block state space (the series realisation with its states
  // interleaved) and one transfer function. Before the fix all three were
  // refused: the rescaling made the 1e4 Hz block non-normal by ~1e7, LAPACK's
  // dtrsyl reported perturbed pivots (INFO = 1), and that was taken for
  // poles that "sum to zero" (they summed to -125.7 or -62.8-62831.8j).
  // Tolerance 1e-6 relative (observed ~1e-12).
  for (const double zeta : {1e-3, 1e-2, 0.1, 0.5}) {
    CAPTURE(zeta);
    const double w1 = 2 * M_PI * 1e-3, w2 = 2 * M_PI * 1e4;
    const std::vector<double> d1{1.0, 2 * zeta * w1, w1 * w1}, d2{1.0, 2 * zeta * w2, w2 * w2};
    std::vector<CLD> poles;
    for (const double w : {w1, w2}) {
      poles.push_back(CLD(-zeta * w, w * std::sqrt(1.0L - static_cast<LD>(zeta) * zeta)));
      poles.push_back(std::conj(poles.back()));
    }
    const double reference = static_cast<double>(
        ClosedFormVariance(poles, static_cast<LD>(w1) * w1 * static_cast<LD>(w2) * w2));
    const StateSpace s1 = ToStateSpace(TransferFunction({w1 * w1}, d1));
    const StateSpace s2 = ToStateSpace(TransferFunction({w2 * w2}, d2));
    const StateSpace series = Series(s1, s2);
    const StateSpace reversed = Series(s2, s1);
    const StateSpace block = Permuted(series, {2, 0, 3, 1});
    const StateSpace one = ToStateSpace(TransferFunction({w1 * w1 * w2 * w2}, Multiply(d1, d2)));
    for (const StateSpace* sys : {&series, &reversed, &block, &one}) {
      const std::string message = MessageOf([&] {
        CHECK(OutputCovariance(*sys, Scalar(1.0))(0, 0) == doctest::Approx(reference).epsilon(1e-6));
      });
      CHECK(message == "(no InputError)");
    }
  }
}

// ---------------------------------------------------------------------------
// Property: random stable systems, exact variance against the pole-residue
// closed form (long double), or a refusal whose reason is a measured one.

// Poles 1e-3 ... 1e5 Hz (log-uniform), zeta 1e-4 ... 1 (log-uniform), 1 to
// 24 states: pairs and real poles, as sections of unit DC gain.
struct RandomCascade {
  std::vector<std::vector<double>> sections;  // monic denominators of order 1 or 2
  std::vector<CLD> poles;
  LD gain = 1.0L;  // the product of the sections' numerators (their DC gains are 1)
};

RandomCascade MakeRandomCascade(std::mt19937& rng) {
  std::uniform_int_distribution<int> order(1, 24);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomCascade c;
  for (int n = order(rng), states = 0; states < n;) {
    const double w = 2 * M_PI * std::pow(10.0, -3.0 + 8.0 * u(rng));
    if (n - states >= 2 && u(rng) < 0.7) {
      const double zeta = std::min(std::pow(10.0, -4.0 + 4.0 * u(rng)), 0.999);
      c.sections.push_back({1.0, 2 * zeta * w, w * w});
      const LD re = -static_cast<LD>(zeta) * w, im = w * std::sqrt(1.0L - static_cast<LD>(zeta) * zeta);
      c.poles.push_back(CLD(re, im));
      c.poles.push_back(CLD(re, -im));
      c.gain *= static_cast<LD>(w) * w;
      states += 2;
    } else {
      c.sections.push_back({1.0, w});
      c.poles.push_back(CLD(-w, 0.0L));
      c.gain *= w;
      states += 1;
    }
  }
  return c;
}


// A block-diagonal modal realisation of `poles` (pairs as [re im; -im re],
// exact) with random B (states x 1) and C (1 x states), and its variance
// by the partial-fraction sum
//   sigma^2 = sum_a sum_b R_a conj(R_b) (-1 / (a + conj b)),
// R_a the residue of H at pole a (for a pair block, R = c^T P b with the
// spectral projector P = [1 -j; j 1] / 2 of re + j im).
std::pair<StateSpace, LD> RandomModal(const RandomCascade& c, std::mt19937& rng) {
  const int n = static_cast<int>(c.poles.size());
  MatrixXd a = MatrixXd::Zero(n, n);
  const MatrixXd b = testing::RandomMatrix(n, 1, rng), cm = testing::RandomMatrix(1, n, rng);
  std::vector<CLD> pole, residue;
  for (int k = 0; k < n; ++k) {
    const CLD p = c.poles[k];
    if (p.imag() == 0.0L) {
      a(k, k) = static_cast<double>(p.real());
      pole.push_back(CLD(a(k, k), 0.0L));
      residue.push_back(static_cast<LD>(cm(0, k)) * b(k, 0));
      continue;
    }
    const double re = static_cast<double>(p.real()), im = static_cast<double>(p.imag());
    a(k, k) = a(k + 1, k + 1) = re;
    a(k, k + 1) = im;
    a(k + 1, k) = -im;
    const CLD j(0.0L, 1.0L);
    const LD c1 = cm(0, k), c2 = cm(0, k + 1), b1 = b(k, 0), b2 = b(k + 1, 0);
    const CLD r = 0.5L * (c1 * b1 - j * c1 * b2 + j * c2 * b1 + c2 * b2);
    pole.push_back(CLD(re, im));
    residue.push_back(r);
    pole.push_back(CLD(re, -im));
    residue.push_back(std::conj(r));
    ++k;
  }
  CLD sum = 0.0L;
  for (std::size_t i = 0; i < pole.size(); ++i)
    for (std::size_t l = 0; l < pole.size(); ++l)
      sum += residue[i] * std::conj(residue[l]) * (-1.0L / (pole[i] + std::conj(pole[l])));
  return {StateSpace(a, b, cm, MatrixXd::Zero(1, 1)), sum.real()};
}

// As MakeRandomCascade, with a group of k = 2..6 lightly damped pairs
// (zeta 1e-4 ... 1e-1, log-uniform) at one frequency w: each at w exactly
// (repeated) or at w (1 + d), d 1e-9 ... 1e-3 (log-uniform; nearly
// repeated), half and half; the other sections as MakeRandomCascade's, the
// order 4 to 24, the sections in random order.
RandomCascade MakeRepeatedCascade(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = std::uniform_int_distribution<int>(4, 24)(rng);
  const int k = std::uniform_int_distribution<int>(2, std::min(6, n / 2))(rng);
  const double w = 2 * M_PI * std::pow(10.0, -3.0 + 8.0 * u(rng)), zeta = std::pow(10.0, -4.0 + 3.0 * u(rng));
  RandomCascade c;
  const auto add_pair = [&](double wi, double zi) {
    c.sections.push_back({1.0, 2 * zi * wi, wi * wi});
    const LD re = -static_cast<LD>(zi) * wi, im = wi * std::sqrt(1.0L - static_cast<LD>(zi) * zi);
    c.poles.push_back(CLD(re, im));
    c.poles.push_back(CLD(re, -im));
    c.gain *= static_cast<LD>(wi) * wi;
  };
  for (int i = 0; i < k; ++i) add_pair(u(rng) < 0.5 ? w : w * (1.0 + std::pow(10.0, -9.0 + 6.0 * u(rng))), zeta);
  for (int states = 2 * k; states < n;) {
    const double wi = 2 * M_PI * std::pow(10.0, -3.0 + 8.0 * u(rng));
    if (n - states >= 2 && u(rng) < 0.7) {
      add_pair(wi, std::min(std::pow(10.0, -4.0 + 4.0 * u(rng)), 0.999));
      states += 2;
    } else {
      c.sections.push_back({1.0, wi});
      c.poles.push_back(CLD(-wi, 0.0L));
      c.gain *= wi;
      states += 1;
    }
  }
  std::vector<int> order(c.sections.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<std::vector<double>> shuffled;
  for (const int i : order) shuffled.push_back(c.sections[i]);
  c.sections = shuffled;
  return c;
}

TEST_CASE("property: random stable systems get their exact variance to 1e-6, or a refusal with a measured reason") {
  // 300 random systems, each in four forms: a series of sections, the same
  // realisation with its states in random order (one block state space), one
  // transfer function of the expanded polynomial, and a modal state space
  // with random B and C. References are independent of deb's solver: the
  // pole-residue closed form in long double (for the transfer function, on
  // the roots of its rounded coefficients, found by Newton's method from the
  // intended poles), and the partial-fraction sum for the modal form.
  // Every result is a variance within 1e-6 of the reference or an
  // InputError saying what was measured (an estimated error, a residual, a
  // computed variance that is negative),
  // never "sum to zero" (no two poles of a stable system do), never an
  // abort. Cases whose reference itself cancels beyond 1e10 are not
  // compared (counted). The transfer function's DC gain is checked too
  // (1e-7: before the fix, cascades spanning 0.01 to 1e5 rad/s gave H(0) = 0
  // instead of 1 in the modal form).
  std::mt19937 rng(2026);
  int systems = 0, compared = 0, refused = 0, uncomparable = 0;
  double worst = 0.0, worst_dc = 0.0;
  std::string worst_what;
  const auto judge = [&](const std::string& form, const StateSpace& sys, LD reference, LD cancellation) {
    CAPTURE(form);
    if (!(cancellation < 1e10L)) {
      ++uncomparable;
      return;
    }
    try {
      const double v = OutputCovariance(sys, Scalar(1.0))(0, 0);
      const double error = std::abs(static_cast<double>((v - reference) / reference));
      CHECK(error <= 1e-6);
      if (error > worst) worst = error, worst_what = form;
      ++compared;
    } catch (const InputError& e) {
      const std::string why = e.what();
      CAPTURE(why);
      CHECK(!Contains(why, "sum to zero"));
      CHECK((Contains(why, "estimated error") || Contains(why, "residual") || Contains(why, "is negative")));
      ++refused;
    }
  };
  for (int trial = 0; trial < 300; ++trial) {
    CAPTURE(trial);
    const RandomCascade c = MakeRandomCascade(rng);
    ++systems;
    const auto [reference, cancellation] = ClosedFormWithCancellation(c.poles, c.gain);
    StateSpace series = StateSpace::Gain(Scalar(1.0));
    std::vector<double> den{1.0};
    for (const std::vector<double>& d : c.sections) {
      const double dc = d.back();
      series = Series(series, ToStateSpace(TransferFunction({dc}, d)));
      den = Multiply(den, d);
    }
    judge("series", series, reference, cancellation);
    std::vector<int> perm(series.states());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    judge("block state space", Permuted(series, perm), reference, cancellation);
    // One transfer function: its rounded coefficients define their own poles.
    const double num = static_cast<double>(c.gain);
    const std::vector<CLD> actual = RootsNear(den, c.poles);
    LD shift = 0.0L;
    for (std::size_t i = 0; i < actual.size(); ++i)
      shift = std::max(shift, std::abs(actual[i] - c.poles[i]) / std::abs(c.poles[i].real()));
    const StateSpace tf = ToStateSpace(TransferFunction({num}, den));
    const double dc = std::abs(FrequencyResponse(tf).At(0.0)(0, 0).real() - num / den.back()) / (num / den.back());
    CHECK(dc <= 1e-7);
    worst_dc = std::max(worst_dc, dc);
    if (shift < 1e-6L) {
      const auto [tf_reference, tf_cancellation] = ClosedFormWithCancellation(actual, num);
      judge("transfer function", tf, tf_reference, tf_cancellation);
    } else {
      ++uncomparable;  // the rounded coefficients moved a pole: no reference
    }
    const auto [modal, modal_reference] = RandomModal(c, rng);
    judge("modal state space", modal, modal_reference, 1.0L);
  }
  MESSAGE(systems << " systems, " << compared << " variances compared, worst relative error " << worst << " ("
                  << worst_what << "), " << refused << " refused, " << uncomparable
                  << " without a reference; worst DC gain error of the transfer functions " << worst_dc);
  CHECK(refused <= compared / 100);  // a refusal is the exception

  // 300 more, each with a group of repeated or nearly repeated lightly
  // damped pairs (MakeRepeatedCascade). The pole-residue closed form does
  // not exist for a repeated pole, so the references are Astrom's
  // recursion in binary128 (polynomial_reference.h): for the series and the
  // block state space on the product of the sections (multiplied in
  // binary128), for the transfer function on its coefficients as rounded
  // to double, which also say, exactly, how many of its roots rounding has
  // put in the right half plane. The transfer function's roots are the
  // truth: with as many unstable poles as the Routh table counts it is
  // refused as unstable, else its variance must be within 1e-6 and its H
  // too (WorstResponseError: 0, 200 frequencies log-spaced over two decades
  // either side of the group and 81 across its resonance, w (1 + m zeta / 8)),
  // or ToStateSpace refuses it with its estimated error. The modal form keeps
  // its partial-fraction sum (no pole differences in it).
  std::mt19937 rng_repeated(2027);
  int repeated_systems = 0, repeated_compared = 0, repeated_refused = 0, unstable_tf = 0;
  double worst_repeated = 0.0, worst_h = 0.0;
  std::string worst_repeated_what;
  for (int trial = 0; trial < 300; ++trial) {
    CAPTURE(trial);
    const RandomCascade c = MakeRepeatedCascade(rng_repeated);
    ++repeated_systems;
    const int before_compared = compared, before_refused = refused;
    const double before_worst = worst;
    worst = 0.0;
    std::vector<testing::Quad> product{1};
    testing::Quad gain = 1;
    StateSpace series = StateSpace::Gain(Scalar(1.0));
    std::vector<double> den{1.0};
    for (const std::vector<double>& d : c.sections) {
      series = Series(series, ToStateSpace(TransferFunction({d.back()}, d)));
      den = Multiply(den, d);
      std::vector<testing::Quad> next(product.size() + d.size() - 1, testing::Quad(0));
      for (std::size_t i = 0; i < product.size(); ++i)
        for (std::size_t j = 0; j < d.size(); ++j) next[i + j] += product[i] * d[j];
      product = next;
      gain *= d.back();
    }
    const testing::ReferenceVariance series_reference = testing::ReferenceH2({gain}, product);
    REQUIRE(series_reference.right_half_plane == 0);
    judge("series (repeated)", series, series_reference.variance, 1.0L);
    std::vector<int> perm(series.states());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng_repeated);
    judge("block state space (repeated)", Permuted(series, perm), series_reference.variance, 1.0L);
    const auto [modal, modal_reference] = RandomModal(c, rng_repeated);
    judge("modal state space (repeated)", modal, modal_reference, 1.0L);

    const double num = static_cast<double>(gain);
    const testing::ReferenceVariance reference = testing::ReferenceH2({num}, testing::ToQuad(den));
    std::optional<StateSpace> tf;
    const std::string refusal = MessageOf([&] { tf = ToStateSpace(TransferFunction({num}, den)); });
    if (!tf) {
      CAPTURE(refusal);
      CHECK(Contains(refusal, "cannot be located to the accuracy deb promises"));
      CHECK(Contains(refusal, "estimated error"));
      ++refused;
    } else if (reference.right_half_plane != 0) {
      // Undecided (-1: a zero in the Routh table) or unstable: deb must not
      // call it stable.
      const PoleStability stability = ClassifyPoles(FrequencyResponse(*tf).poles());
      if (reference.right_half_plane > 0)
        CHECK(static_cast<int>(stability.unstable.size()) == reference.right_half_plane);
      else
        CHECK(stability.unstable.size() + stability.marginal.size() > 0);
      CHECK(Contains(MessageOf([&] { OutputCovariance(*tf, Scalar(1.0)); }), "exact variance needs a stable path"));
      ++unstable_tf;
    } else {
      const PoleStability stability = ClassifyPoles(FrequencyResponse(*tf).poles());
      CHECK(stability.unstable.empty());
      CHECK(stability.marginal.empty());
      const double w_group = std::sqrt(c.sections.front().back());  // any: the grid spans all
      double w_lo = w_group, w_hi = w_group;
      for (const CLD& p : c.poles) {
        w_lo = std::min(w_lo, static_cast<double>(std::abs(p)));
        w_hi = std::max(w_hi, static_cast<double>(std::abs(p)));
      }
      std::vector<double> w = testing::LogSpace(w_lo / 100.0, w_hi * 100.0, 200);
      w.push_back(0.0);
      // The group: the pairs of the first k sections made by MakeRepeatedCascade
      // are the lightest damped among the repeated ones; sample every pair's
      // resonance.
      for (const CLD& p : c.poles)
        if (p.imag() > 0.0L && -p.real() < 0.2L * std::abs(p))
          for (int m = -40; m <= 40; ++m) {
            const LD zeta = -p.real() / std::abs(p);
            w.push_back(static_cast<double>(std::abs(p) * (1.0L + zeta * m / 8.0L)));
          }
      const double h_error = testing::WorstResponseError(*tf, {num}, den, w);
      CHECK(h_error <= 1e-6);
      worst_h = std::max(worst_h, h_error);
      judge("transfer function (repeated)", *tf, reference.variance, 1.0L);
    }
    repeated_compared += compared - before_compared;
    repeated_refused += refused - before_refused;
    if (worst > worst_repeated) worst_repeated = worst, worst_repeated_what = worst_what;
    worst = std::max(worst, before_worst);
  }
  MESSAGE(repeated_systems << " systems with repeated or nearly repeated pairs, " << repeated_compared
                           << " variances compared, worst relative error " << worst_repeated << " ("
                           << worst_repeated_what << "), " << repeated_refused << " refused, " << unstable_tf
                           << " transfer functions unstable as rounded (as many unstable poles as their Routh "
                              "table counts); worst relative error of a transfer function's H "
                           << worst_h);
  // Refusals are more frequent here (6 %: a cascade of nearly repeated
  // pairs makes the Lyapunov equation ill-conditioned) but still the exception.
  CHECK(repeated_refused <= repeated_compared / 10);
}

}  // namespace
}  // namespace deb
