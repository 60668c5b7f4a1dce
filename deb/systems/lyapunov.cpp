#include "deb/systems/lyapunov.h"

#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <string>

#include "deb/core/error.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// "+0.3 rad/s", "-0.1+2j rad/s", or "-0.1±2j rad/s" for a conjugate pair.
std::string FormatPole(Complex p, bool pair = false) {
  std::ostringstream os;
  os << std::showpos << p.real();
  if (p.imag() != 0.0) {
    if (pair) os << std::noshowpos << "\u00b1" << std::abs(p.imag()) << "j";
    else os << p.imag() << "j";
  }
  os << " rad/s";
  return os.str();
}

void RequireFinite(const Eigen::MatrixXd& m, const char* where, const char* name) {
  if (!m.allFinite()) {
    std::ostringstream os;
    os << where << ": " << name << " has an entry that is not finite";
    throw InputError(os.str());
  }
}

}  // namespace

Eigen::MatrixXd SolveLyapunov(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q) {
  const Eigen::Index n = a.rows();
  if (a.cols() != n || q.rows() != n || q.cols() != n) {
    std::ostringstream os;
    os << "SolveLyapunov: A is " << a.rows() << "x" << a.cols() << " and Q is " << q.rows()
       << "x" << q.cols() << "; both must be square of the same size";
    throw InputError(os.str());
  }
  RequireFinite(a, "SolveLyapunov", "A");
  RequireFinite(q, "SolveLyapunov", "Q");
  if (n == 0) return Eigen::MatrixXd(0, 0);

  // Balancing (exact powers of two) helps models in mixed units: with
  // A = T A_b T^-1, P = T P_b T where A_b P_b + P_b A_b^T + T^-1 Q T^-1 = 0.
  const Eigen::VectorXd scale = BalancingScale(a), inv = scale.cwiseInverse();
  const Eigen::MatrixXd ab = inv.asDiagonal() * a * scale.asDiagonal();
  const Eigen::MatrixXd qb = inv.asDiagonal() * q * inv.asDiagonal();

  // A_b = U T U^H; with Y = U^H P_b U the equation becomes T Y + Y T^H = -U^H Q_b U.
  // Real input: Eigen goes through the real Schur form, cheaper than complex QR.
  const Eigen::ComplexSchur<Eigen::MatrixXd> schur(ab);
  DEB_DEMAND(schur.info() == Eigen::Success);
  const Eigen::MatrixXcd& t = schur.matrixT();
  const Eigen::MatrixXcd& u = schur.matrixU();

  const double tol = 1e3 * kEps * std::max(ab.norm(), std::numeric_limits<double>::min());
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i; j < n; ++j)
      if (std::abs(t(i, i) + std::conj(t(j, j))) <= tol) {
        std::ostringstream os;
        os << "SolveLyapunov: singular equation, poles " << FormatPole(t(i, i)) << " and "
           << FormatPole(std::conj(t(j, j)))
           << " sum to zero (no unique solution; is a pole on the imaginary axis?)";
        throw InputError(os.str());
      }

  Eigen::MatrixXcd y = -(u.adjoint() * qb.cast<Complex>() * u);
  // Column j of T Y + Y T^H = R, with T^H lower triangular:
  //   (T + conj(t_jj) I) y_j = r_j - sum_{k>j} conj(t_jk) y_k,  j = n-1 ... 0,
  // each a back substitution, column-oriented.
  for (Eigen::Index j = n - 1; j >= 0; --j) {
    const Eigen::Index rest = n - j - 1;
    if (rest > 0) y.col(j).noalias() -= y.rightCols(rest) * t.row(j).tail(rest).adjoint();
    const Complex shift = std::conj(t(j, j));
    for (Eigen::Index i = n - 1; i >= 0; --i) {
      y(i, j) /= t(i, i) + shift;
      if (i > 0) y.col(j).head(i) -= y(i, j) * t.col(i).head(i);
    }
  }
  Eigen::MatrixXd pb = (u * y * u.adjoint()).real();
  if (q == q.transpose()) pb = 0.5 * (pb + pb.transpose()).eval();

  // Bartels-Stewart is backward stable: the residual is a few eps relative to
  // |A||P| + |Q| however ill-conditioned the equation; a larger one is a bug.
  const double residual = (ab * pb + pb * ab.transpose() + qb).norm();
  DEB_DEMAND(residual <= 1e-10 * std::sqrt(static_cast<double>(n)) *
                             (2.0 * ab.norm() * pb.norm() + qb.norm()));
  return scale.asDiagonal() * pb * scale.asDiagonal();
}

Eigen::MatrixXd OutputCovariance(const StateSpace& sys, const Eigen::MatrixXd& w_two_sided) {
  const Eigen::MatrixXd& w = w_two_sided;
  const int m = sys.inputs(), p = sys.outputs();
  if (w.rows() != m || w.cols() != m) {
    std::ostringstream os;
    os << "OutputCovariance: noise intensity W is " << w.rows() << "x" << w.cols()
       << " but the path has " << m << " inputs (W must be " << m << "x" << m << ")";
    throw InputError(os.str());
  }
  RequireFinite(w, "OutputCovariance", "W");
  const double w_scale = w.cwiseAbs().maxCoeff();
  for (int i = 0; i < m; ++i) {
    if (w(i, i) < 0.0) {
      std::ostringstream os;
      os << "OutputCovariance: W(" << i + 1 << "," << i + 1 << ") = " << w(i, i)
         << " is negative; an intensity must be >= 0";
      throw InputError(os.str());
    }
    for (int j = 0; j < i; ++j)
      if (std::abs(w(i, j) - w(j, i)) > 1e-12 * w_scale) {
        std::ostringstream os;
        os << "OutputCovariance: W is not symmetric, W(" << i + 1 << "," << j + 1
           << ") = " << w(i, j) << " but W(" << j + 1 << "," << i + 1 << ") = " << w(j, i);
        throw InputError(os.str());
      }
  }
  // White noise passed straight to an output has infinite variance.
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < m; ++j)
      if (sys.D()(i, j) != 0.0 && w(j, j) > 0.0) {
        std::ostringstream os;
        os << "OutputCovariance: infinite variance: direct feedthrough D != 0 under white "
              "noise (D("
           << i + 1 << "," << j + 1 << ") = " << sys.D()(i, j) << " and input " << j + 1
           << " has intensity " << w(j, j) << ")";
        throw InputError(os.str());
      }
  if (sys.states() == 0) return Eigen::MatrixXd::Zero(p, p);

  // Similarity-invariant: C P C^T is the same for the balanced realisation,
  // whose Schur form is better conditioned.
  const StateSpace bal = sys.Balanced();
  const Eigen::VectorXcd poles = bal.Poles();
  const double stable_margin = 64.0 * kEps * bal.A().norm();
  std::ostringstream unstable;
  int count = 0;
  for (Eigen::Index k = 0; k < poles.size(); ++k) {
    if (poles(k).real() < -stable_margin || poles(k).imag() < 0.0) continue;
    unstable << (count++ ? ", " : "") << FormatPole(poles(k), true);
  }
  if (count > 0) {
    std::ostringstream os;
    os << "OutputCovariance: exact variance needs a stable path; pole" << (count > 1 ? "s" : "")
       << " at " << unstable.str()
       << (count > 1 ? " are" : " is") << " not in the open left half plane";
    throw InputError(os.str());
  }
  const Eigen::MatrixXd state = SolveLyapunov(bal.A(), bal.B() * w * bal.B().transpose());
  Eigen::MatrixXd y = bal.C() * state * bal.C().transpose();
  return 0.5 * (y + y.transpose());
}

}  // namespace deb
