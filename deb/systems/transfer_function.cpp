#include "deb/systems/transfer_function.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "deb/core/error.h"

namespace deb {
namespace {

void RequireFinite(const std::vector<double>& p, const char* name) {
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!std::isfinite(p[k])) {
      std::ostringstream os;
      os << "transfer function: " << name << " coefficient " << k + 1 << " = " << p[k]
         << " is not finite";
      throw InputError(os.str());
    }
}

std::vector<double> TrimLeadingZeros(std::vector<double> p) {
  std::size_t first = 0;
  while (first < p.size() && p[first] == 0.0) ++first;
  p.erase(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(first));
  return p;
}

std::complex<double> Horner(const std::vector<double>& p, std::complex<double> s) {
  std::complex<double> v = 0.0;
  for (double c : p) v = v * s + c;
  return v;
}

}  // namespace

TransferFunction::TransferFunction(std::vector<double> num, std::vector<double> den) {
  RequireFinite(num, "numerator");
  RequireFinite(den, "denominator");
  num_ = TrimLeadingZeros(std::move(num));
  den_ = TrimLeadingZeros(std::move(den));
  if (den_.empty())
    throw InputError("transfer function: the denominator is empty or all zero");
  if (num_.empty()) num_ = {0.0};
  if (num_.size() > den_.size()) {
    std::ostringstream os;
    os << "transfer function: improper, numerator degree " << num_.size() - 1
       << " > denominator degree " << den_.size() - 1
       << " (deb needs deg num <= deg den; add poles above the band of interest)";
    throw InputError(os.str());
  }
}

TransferFunction TransferFunction::Gain(double k) { return TransferFunction({k}, {1.0}); }

std::complex<double> TransferFunction::Evaluate(std::complex<double> s) const {
  return Horner(num_, s) / Horner(den_, s);
}

StateSpace ToStateSpace(const TransferFunction& tf) {
  const int n = tf.order();
  const double lead = tf.den().front();
  // Monic denominator s^n + a1 s^(n-1) + ... + an; numerator padded to n+1
  // coefficients b0 s^n + ... + bn, both divided by the leading coefficient.
  Eigen::VectorXd a(n + 1), b = Eigen::VectorXd::Zero(n + 1);
  for (int k = 0; k <= n; ++k) a(k) = tf.den()[k] / lead;
  const int offset = n + 1 - static_cast<int>(tf.num().size());
  for (std::size_t k = 0; k < tf.num().size(); ++k) b(offset + k) = tf.num()[k] / lead;
  Eigen::MatrixXd d(1, 1);
  d(0, 0) = b(0);
  if (n == 0) return StateSpace::Gain(d);
  // Controllable canonical form: x1' = -a1 x1 - ... - an xn + u, x(k+1)' = xk,
  // y = sum (bk - ak b0) xk + b0 u (the strictly proper remainder plus b0).
  Eigen::MatrixXd am = Eigen::MatrixXd::Zero(n, n), bm = Eigen::MatrixXd::Zero(n, 1);
  Eigen::MatrixXd cm(1, n);
  for (int k = 0; k < n; ++k) {
    am(0, k) = -a(k + 1);
    cm(0, k) = b(k + 1) - a(k + 1) * b(0);
  }
  for (int k = 1; k < n; ++k) am(k, k - 1) = 1.0;
  bm(0, 0) = 1.0;
  return StateSpace(std::move(am), std::move(bm), std::move(cm), std::move(d)).Balanced();
}

StateSpace ToStateSpace(const std::vector<std::vector<TransferFunction>>& tf) {
  if (tf.empty() || tf.front().empty())
    throw InputError("transfer matrix: needs at least one row and one column");
  const std::size_t rows = tf.size(), cols = tf.front().size();
  int n = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    if (tf[i].size() != cols) {
      std::ostringstream os;
      os << "transfer matrix: row " << i + 1 << " has " << tf[i].size()
         << " entries but row 1 has " << cols;
      throw InputError(os.str());
    }
    for (const auto& entry : tf[i]) n += entry.order();
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n), b = Eigen::MatrixXd::Zero(n, cols);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(rows, n), d(rows, cols);
  int at = 0;
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) {
      const StateSpace s = ToStateSpace(tf[i][j]);
      const int k = s.states();
      a.block(at, at, k, k) = s.A();
      b.block(at, j, k, 1) = s.B();
      c.block(i, at, 1, k) = s.C();
      d(i, j) = s.D()(0, 0);
      at += k;
    }
  return StateSpace(std::move(a), std::move(b), std::move(c), std::move(d));
}

}  // namespace deb
