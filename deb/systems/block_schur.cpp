#include "deb/systems/block_schur.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "deb/core/error.h"
#include "deb/systems/state_space.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
using Eigen::MatrixXcd;

double Norm1(const MatrixXcd& x) {
  return x.size() == 0 ? 0.0 : x.cwiseAbs().colwise().sum().maxCoeff();
}

// Exchanges the diagonal entries k and k+1 of the triangular t by a rotation G
// on those two indices (t <- G^H t G, s <- s G, s_inv <- G^H s_inv). G's first
// column is the eigenvector of [t11 t12; 0 t22] for t22, (t12, t22 - t11).
void SwapAdjacent(BlockSchurForm& f, int k) {
  MatrixXcd& t = f.t;
  const Eigen::Index n = t.rows();
  const Complex t11 = t(k, k), t22 = t(k + 1, k + 1);
  const Complex v1 = t(k, k + 1), v2 = t22 - t11;
  const double norm = std::hypot(std::abs(v1), std::abs(v2));
  if (norm == 0.0) return;  // equal and uncoupled: nothing to exchange
  const Complex a = v1 / norm, b = v2 / norm;
  // G = [a, -conj(b); b, conj(a)], G^H = [conj(a), conj(b); -b, a].
  for (Eigen::Index j = k; j < n; ++j) {
    const Complex r1 = t(k, j), r2 = t(k + 1, j);
    t(k, j) = std::conj(a) * r1 + std::conj(b) * r2;
    t(k + 1, j) = -b * r1 + a * r2;
  }
  for (Eigen::Index i = 0; i <= k + 1; ++i) {
    const Complex c1 = t(i, k), c2 = t(i, k + 1);
    t(i, k) = a * c1 + b * c2;
    t(i, k + 1) = -std::conj(b) * c1 + std::conj(a) * c2;
  }
  t(k + 1, k) = 0.0;
  t(k, k) = t22;
  t(k + 1, k + 1) = t11;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Complex c1 = f.s(i, k), c2 = f.s(i, k + 1);
    f.s(i, k) = a * c1 + b * c2;
    f.s(i, k + 1) = -std::conj(b) * c1 + std::conj(a) * c2;
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const Complex r1 = f.s_inv(k, j), r2 = f.s_inv(k + 1, j);
    f.s_inv(k, j) = std::conj(a) * r1 + std::conj(b) * r2;
    f.s_inv(k + 1, j) = -b * r1 + a * r2;
  }
}

// X with T11 X - X T22 = -T12 for the rows/columns [a, b) and [b, n) of the
// triangular t, column by column:
//   (T11 - t22_jj I) x_j = -t12_j + sum_{i<j} x_i t22_ij.
// Returns false as soon as an entry exceeds max_coupling (or the equation is
// singular: equal eigenvalues on both sides).
bool SolveSplit(const MatrixXcd& t, int a, int b, double max_coupling, MatrixXcd& x) {
  const int n = static_cast<int>(t.rows()), k = b - a, l = n - b;
  x.resize(k, l);
  for (int j = 0; j < l; ++j) {
    const Complex shift = t(b + j, b + j);
    for (int r = k - 1; r >= 0; --r) {
      Complex v = -t(a + r, b + j);
      for (int i = 0; i < j; ++i) v += x(r, i) * t(b + i, b + j);
      for (int q = r + 1; q < k; ++q) v -= t(a + r, a + q) * x(q, j);
      const Complex den = t(a + r, a + r) - shift;
      if (den == 0.0) return false;
      x(r, j) = v / den;
      if (!(std::abs(x(r, j)) <= max_coupling)) return false;
    }
  }
  return true;
}

}  // namespace

int BlockSchurForm::largest_block() const {
  int largest = 0;
  for (int i = 0; i < blocks(); ++i) largest = std::max(largest, block_size(i));
  return largest;
}

double BlockSchurForm::condition() const { return Norm1(s) * Norm1(s_inv); }

BlockSchurForm BlockDiagonalSchur(const Eigen::MatrixXd& a, double max_coupling) {
  DEB_DEMAND(a.rows() == a.cols());
  const int n = static_cast<int>(a.rows());
  BlockSchurForm f;
  f.block_start.push_back(0);
  if (n == 0) return f;
  // Real input: Eigen goes through the real Schur form, cheaper than complex QR.
  const Eigen::ComplexSchur<Eigen::MatrixXd> schur(a);
  if (schur.info() != Eigen::Success) ThrowNotConverged(a);
  f.t = schur.matrixT().triangularView<Eigen::Upper>();
  f.s = schur.matrixU();
  f.s_inv = schur.matrixU().adjoint();

  MatrixXcd x;
  int begin = 0;
  while (begin < n) {
    int end = begin + 1;
    while (end < n) {
      if (SolveSplit(f.t, begin, end, max_coupling, x)) {
        const int k = end - begin, l = n - end;
        f.t.block(begin, end, k, l).setZero();
        f.s.middleCols(end, l) += f.s.middleCols(begin, k) * x;
        f.s_inv.middleRows(begin, k) -= x * f.s_inv.middleRows(end, l);
        break;
      }
      // Bring the eigenvalue of the rest nearest to the block next to it.
      int nearest = end;
      double best = std::numeric_limits<double>::infinity();
      for (int j = end; j < n; ++j)
        for (int i = begin; i < end; ++i) {
          const double dist = std::abs(f.t(j, j) - f.t(i, i));
          if (dist < best) best = dist, nearest = j;
        }
      for (int k = nearest - 1; k >= end; --k) SwapAdjacent(f, k);
      ++end;
    }
    f.block_start.push_back(end);
    begin = end;
  }
  return f;
}

}  // namespace deb
