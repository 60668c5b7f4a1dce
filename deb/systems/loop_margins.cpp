#include "deb/systems/loop_margins.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/parallel.h"

namespace deb {

namespace {

// Bisection and golden-section searches run in log f down to this width.
constexpr double kLogTolerance = 1e-13;

std::complex<double> Scalar(const LoopGainAt& loop_gain, double f_hz) {
  const Eigen::MatrixXcd l = loop_gain(f_hz);
  DEB_DEMAND(l.rows() == 1 && l.cols() == 1 && std::isfinite(l(0, 0).real()) && std::isfinite(l(0, 0).imag()));
  return l(0, 0);
}

// A root of g in [f_lo, f_hi], where g(f_lo) and g(f_hi) differ in sign,
// by bisection in log f.
double Bisect(const std::function<double(double)>& g, double f_lo, double f_hi) {
  double lo = std::log(f_lo), hi = std::log(f_hi);
  const bool rising = g(f_lo) < 0.0;
  while (hi - lo > kLogTolerance * std::max(1.0, std::abs(lo))) {
    const double mid = 0.5 * (lo + hi);
    const double v = g(std::exp(mid));
    if ((v < 0.0) == rising)
      lo = mid;
    else
      hi = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

// The minimum of g over [f_lo, f_hi] (g unimodal there) by golden section in log f.
double GoldenMinimum(const std::function<double(double)>& g, double f_lo, double f_hi, double* at_hz) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = std::log(f_lo), b = std::log(f_hi);
  double c = b - r * (b - a), d = a + r * (b - a);
  double gc = g(std::exp(c)), gd = g(std::exp(d));
  while (b - a > kLogTolerance * std::max(1.0, std::abs(a))) {
    if (gc < gd) {
      b = d, d = c, gd = gc;
      c = b - r * (b - a), gc = g(std::exp(c));
    } else {
      a = c, c = d, gc = gd;
      d = a + r * (b - a), gd = g(std::exp(d));
    }
  }
  *at_hz = std::exp(0.5 * (a + b));
  return g(*at_hz);
}

// sigma_min(I + L). Where only r columns J of L are nonzero (a controller
// acting on r of the loop's channels: L = U E_J^T, U = L(:, J)) and 2r < n,
// I + L is the identity on the complement of W = span(U, E_J) and maps W
// (as does its adjoint) into itself, so its singular values are ones and
// those of Q^H (I + L) Q for an orthonormal basis Q of a space holding W
// (the 2r columns of the Householder QR of [U, E_J]): an SVD of 2r x 2r
// instead of n x n, the same value.
double SmallestSingularValueOfIPlus(const Eigen::MatrixXcd& l) {
  const Eigen::Index n = l.rows();
  DEB_DEMAND(l.allFinite());
  if (n == 1) return std::abs(1.0 + l(0, 0));
  std::vector<Eigen::Index> used;
  for (Eigen::Index j = 0; j < n; ++j)
    if (!l.col(j).isZero(0.0)) used.push_back(j);
  const Eigen::Index r = static_cast<Eigen::Index>(used.size());
  if (2 * r >= n) {
    const Eigen::MatrixXcd m = Eigen::MatrixXcd::Identity(n, n) + l;
    return Eigen::JacobiSVD<Eigen::MatrixXcd>(m).singularValues().minCoeff();
  }
  if (r == 0) return 1.0;
  Eigen::MatrixXcd basis = Eigen::MatrixXcd::Zero(n, 2 * r);
  for (Eigen::Index i = 0; i < r; ++i) {
    basis.col(i) = l.col(used[static_cast<std::size_t>(i)]);
    basis(used[static_cast<std::size_t>(i)], r + i) = 1.0;
  }
  const Eigen::MatrixXcd q =
      Eigen::HouseholderQR<Eigen::MatrixXcd>(basis).householderQ() * Eigen::MatrixXcd::Identity(n, 2 * r);
  const Eigen::MatrixXcd reduced = Eigen::MatrixXcd::Identity(2 * r, 2 * r) + q.adjoint() * l * q;
  return std::min(1.0, Eigen::JacobiSVD<Eigen::MatrixXcd>(reduced).singularValues().minCoeff());
}

}  // namespace

double ToDecibel(double factor) { return 20.0 * std::log10(factor); }

LoopMargins ComputeLoopMargins(const LoopGainAt& loop_gain, const std::vector<double>& f_hz,
                               std::vector<Eigen::MatrixXcd> on_grid) {
  DEB_DEMAND(f_hz.size() >= 2 && f_hz.front() > 0.0);
  for (std::size_t k = 1; k < f_hz.size(); ++k) DEB_DEMAND(f_hz[k] > f_hz[k - 1]);
  const std::size_t n = f_hz.size();
  // L and the smallest singular value of I + L at every frequency, in
  // chunks on all threads (an SVD per frequency: most of the work for a
  // loop of many channels). A failing chunk throws what a serial loop would.
  DEB_DEMAND(on_grid.empty() || on_grid.size() == n);
  std::vector<Eigen::MatrixXcd> l = std::move(on_grid);
  const bool given = !l.empty();
  l.resize(n);
  std::vector<double> sigma(n);
  ParallelForBlocks(n, 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (!given) l[k] = loop_gain(f_hz[k]);
      DEB_DEMAND(l[k].rows() > 0 && l[k].rows() == l[k].cols() && l[k].allFinite());
      sigma[k] = SmallestSingularValueOfIPlus(l[k]);
    }
  });
  for (std::size_t k = 1; k < n; ++k) DEB_DEMAND(l[k].rows() == l[0].rows());
  LoopMargins m;
  m.channels = static_cast<int>(l[0].rows());

  // Modulus margin: the grid's smallest value, refined between its neighbours.
  const std::size_t k_min = static_cast<std::size_t>(std::min_element(sigma.begin(), sigma.end()) - sigma.begin());
  m.modulus_margin = sigma[k_min];
  m.modulus_margin_f_hz = f_hz[k_min];
  {
    const double lo = f_hz[k_min == 0 ? 0 : k_min - 1], hi = f_hz[std::min(n - 1, k_min + 1)];
    double at = 0.0;
    const double refined = GoldenMinimum(
        [&](double f) { return SmallestSingularValueOfIPlus(loop_gain(f)); }, lo, hi, &at);
    if (refined < m.modulus_margin) m.modulus_margin = refined, m.modulus_margin_f_hz = at;
  }
  if (m.channels != 1) return m;

  const auto log_gain = [&](double f) { return std::log(std::abs(Scalar(loop_gain, f))); };
  const auto imag = [&](double f) { return Scalar(loop_gain, f).imag(); };
  const auto phase_margin_deg = [](std::complex<double> v) { return std::arg(-v) * 180.0 / kPi; };
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const std::complex<double> a = l[k](0, 0), b = l[k + 1](0, 0);
    // Gain crossover: log|L| changes sign (a grid point exactly on |L| = 1 counts once).
    const double ga = std::log(std::abs(a)), gb = std::log(std::abs(b));
    if (ga == 0.0) m.gain_crossovers.push_back({f_hz[k], phase_margin_deg(a)});
    else if (gb != 0.0 && (ga < 0.0) != (gb < 0.0)) {
      const double f = Bisect(log_gain, f_hz[k], f_hz[k + 1]);
      m.gain_crossovers.push_back({f, phase_margin_deg(Scalar(loop_gain, f))});
    }
    // Phase crossover: Im L changes sign on the negative real axis.
    if (a.imag() == 0.0 && a.real() < 0.0) m.phase_crossovers.push_back({f_hz[k], -1.0 / a.real()});
    else if (b.imag() != 0.0 && (a.imag() < 0.0) != (b.imag() < 0.0)) {
      const double f = Bisect(imag, f_hz[k], f_hz[k + 1]);
      const std::complex<double> v = Scalar(loop_gain, f);
      if (v.real() < 0.0) m.phase_crossovers.push_back({f, 1.0 / std::abs(v)});
    }
  }
  const std::complex<double> last = l[n - 1](0, 0);
  if (std::log(std::abs(last)) == 0.0) m.gain_crossovers.push_back({f_hz[n - 1], phase_margin_deg(last)});
  if (last.imag() == 0.0 && last.real() < 0.0) m.phase_crossovers.push_back({f_hz[n - 1], -1.0 / last.real()});

  for (const GainCrossover& c : m.gain_crossovers)
    if (!m.phase_margin || c.phase_margin_deg < m.phase_margin->phase_margin_deg) m.phase_margin = c;
  for (const PhaseCrossover& c : m.phase_crossovers) {
    if (c.gain_margin > 1.0 && (!m.upper_gain_margin || c.gain_margin < m.upper_gain_margin->gain_margin))
      m.upper_gain_margin = c;
    if (c.gain_margin < 1.0 && (!m.lower_gain_margin || c.gain_margin > m.lower_gain_margin->gain_margin))
      m.lower_gain_margin = c;
  }
  return m;
}

}  // namespace deb
