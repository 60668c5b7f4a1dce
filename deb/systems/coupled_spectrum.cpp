#include "deb/systems/coupled_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/parallel.h"

namespace deb {
namespace {

using cd = std::complex<double>;
using Eigen::Index;
using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using Eigen::VectorXcd;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// The relative rounding error of one term of the closed form
// (CoupledOutputCovariance): C~, B~ W B~^H and G, each a product or sum.
constexpr double kRoundingPerTerm = 4.0 * kEps;
// The eigenvectors' own accuracy, eps times the largest eigenvalue
// condition, times this margin (CoupledOutputCovariance).
constexpr double kConditionMargin = 16.0;

// A ~ D + U V^T in the basis X that diagonalises each block; B and C with it.
struct Diagonal {
  VectorXcd d;
  MatrixXcd u, v, b, c;
  MatrixXd d_feed;
};

double EigenvectorCondition(const MatrixXcd& x) {
  const Eigen::JacobiSVD<MatrixXcd> svd(x);
  return svd.singularValues()(0) / svd.singularValues()(x.rows() - 1);
}

// Each block diagonalised, A ~ D + U V^T in the basis X that does so. A
// block that is not diagonalisable well (its eigenvalues do not converge,
// or its eigenvector matrix has a condition number over
// kMaxCoupledBlockCondition: a rigid-body mode's double integrator
// [0 1; 0 0], a Jordan-like cluster) keeps its diagonal (X = I) and the
// rest of it joins the coupling, at the rank of its SVD (a double
// integrator adds 1).
Diagonal Diagonalise(const CoupledRealisation& sys) {
  const Index n = sys.states();
  MatrixXd u = sys.u, v = sys.v;
  std::vector<MatrixXcd> xs;
  std::vector<VectorXcd> evs;
  Index at = 0;
  for (const MatrixXd& blk : sys.blocks) {
    const Index s = blk.rows();
    if (s == 1) {
      xs.push_back(MatrixXcd::Identity(1, 1));
      evs.push_back(VectorXcd::Constant(1, blk(0, 0)));
    } else if (const Eigen::EigenSolver<MatrixXd> es(blk, true);
               es.info() == Eigen::Success && EigenvectorCondition(es.eigenvectors()) <= kMaxCoupledBlockCondition) {
      xs.push_back(es.eigenvectors());
      evs.push_back(es.eigenvalues());
    } else {
      const MatrixXd rest = blk - MatrixXd(blk.diagonal().asDiagonal());
      const Eigen::JacobiSVD<MatrixXd> svd(rest, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Index rank = 0;
      while (rank < s && svd.singularValues()(rank) > 0.0) ++rank;
      const Eigen::VectorXd root = svd.singularValues().head(rank).cwiseSqrt();
      MatrixXd wider_u = MatrixXd::Zero(n, u.cols() + rank), wider_v = MatrixXd::Zero(n, v.cols() + rank);
      wider_u.leftCols(u.cols()) = u;
      wider_v.leftCols(v.cols()) = v;
      wider_u.block(at, u.cols(), s, rank) = svd.matrixU().leftCols(rank) * root.asDiagonal();
      wider_v.block(at, v.cols(), s, rank) = svd.matrixV().leftCols(rank) * root.asDiagonal();
      u = std::move(wider_u);
      v = std::move(wider_v);
      xs.push_back(MatrixXcd::Identity(s, s));
      evs.push_back(blk.diagonal().cast<cd>());
    }
    at += s;
  }
  Diagonal out;
  out.d.resize(n);
  out.u.resize(n, u.cols());
  out.v.resize(n, v.cols());
  out.b.resize(n, sys.inputs());
  out.c.resize(sys.outputs(), n);
  out.d_feed = sys.d;
  at = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const MatrixXcd& x = xs[i];
    const Index s = x.rows();
    const Eigen::PartialPivLU<MatrixXcd> lu(x);
    out.d.segment(at, s) = evs[i];
    if (u.cols() > 0) {  // no coupling (SolveCoupled): no columns to slice
      out.u.middleRows(at, s) = lu.solve(u.middleRows(at, s).cast<cd>());
      out.v.middleRows(at, s) = x.transpose() * v.middleRows(at, s).cast<cd>();
    }
    out.b.middleRows(at, s) = lu.solve(sys.b.middleRows(at, s).cast<cd>());
    out.c.middleCols(at, s) = sys.c.middleCols(at, s).cast<cd>() * x;
    at += s;
  }
  return out;
}

// 1 / z without the library's care for infinities (__divdc3): a pole on a
// block's own pole gives inf or nan here, which the callers test for.
inline cd Reciprocal(cd z) {
  const double n = z.real() * z.real() + z.imag() * z.imag();
  return {z.real() / n, -z.imag() / n};
}

// The secular matrices at points z: M(z) = I - V^T (z - D)^-1 U and
// M'(z) = V^T (z - D)^-2 U, with sum_k 1 / (z - d_k).
class Secular {
 public:
  explicit Secular(const Diagonal& dg) : dg_(dg), r_(dg.u.cols()) {
    const Index n = dg.d.size();
    ft_.resize(r_ * r_, n);  // row a + r b: V(k, a) U(k, b)
    for (Index b = 0; b < r_; ++b)
      for (Index a = 0; a < r_; ++a) ft_.row(a + r_ * b) = (dg.v.col(a).array() * dg.u.col(b).array()).transpose();
  }

  // Columns: (z_j - d_k)^-1 for k down the rows.
  MatrixXcd Resolvents(const cd* z, Index count) const {
    const Index n = dg_.d.size();
    MatrixXcd cz(n, count);
    for (Index j = 0; j < count; ++j)
      for (Index k = 0; k < n; ++k) cz(k, j) = Reciprocal(z[j] - dg_.d(k));
    return cz;
  }
  // p'/p at each z.
  void LogDerivatives(const cd* z, Index count, cd* out) const {
    const MatrixXcd cz = Resolvents(z, count);
    const MatrixXcd m = ft_ * cz;
    const MatrixXcd m2 = ft_ * cz.array().square().matrix();
    for (Index j = 0; j < count; ++j) {
      cd s = cz.col(j).sum();
      if (r_ > 0) {
        const Eigen::Map<const MatrixXcd> vru(m.col(j).data(), r_, r_), dm(m2.col(j).data(), r_, r_);
        const MatrixXcd mm = MatrixXcd::Identity(r_, r_) - vru;
        s += Eigen::PartialPivLU<MatrixXcd>(mm).solve(dm).trace();
      }
      out[j] = s;
    }
  }
  MatrixXcd M(const Eigen::Ref<const VectorXcd>& cz) const {
    const VectorXcd m = ft_ * cz;
    return MatrixXcd::Identity(r_, r_) - Eigen::Map<const MatrixXcd>(m.data(), r_, r_);
  }

 private:
  const Diagonal& dg_;
  Index r_;
  MatrixXcd ft_;
};

bool Finite(cd z) { return std::isfinite(z.real()) && std::isfinite(z.imag()); }

// Aberth-Ehrlich on p(z) = det(z - A), started at the blocks' poles moved a
// little apart; nullopt if it does not converge.
std::optional<VectorXcd> Aberth(const Diagonal& dg, const Secular& sec, int threads, int* sweeps) {
  const Index n = dg.d.size();
  double scale = dg.d.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) scale = 1.0;
  VectorXcd z(n);
  constexpr double kGolden = 0.6180339887498949;
  for (Index k = 0; k < n; ++k) {
    const double angle = kTwoPi * std::fmod(kGolden * static_cast<double>(k + 1), 1.0);
    z(k) = dg.d(k) + 1e-6 * (std::abs(dg.d(k)) + 1e-3 * scale) * std::polar(1.0, angle);
  }
  std::vector<char> done(static_cast<std::size_t>(n), 0);
  std::vector<double> last(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  for (int sweep = 1; sweep <= kMaxAberthSweeps; ++sweep) {
    std::vector<Index> active;
    for (Index k = 0; k < n; ++k)
      if (!done[static_cast<std::size_t>(k)]) active.push_back(k);
    if (active.empty()) {
      *sweeps = sweep - 1;
      return z;
    }
    std::vector<cd> step(active.size());
    ParallelForBlocks(
        active.size(), 64,
        [&](std::size_t lo, std::size_t hi) {
          std::vector<cd> pts(hi - lo), logd(hi - lo);
          for (std::size_t i = lo; i < hi; ++i) pts[i - lo] = z(active[i]);
          sec.LogDerivatives(pts.data(), static_cast<Index>(hi - lo), logd.data());
          for (std::size_t i = lo; i < hi; ++i) {
            const Index j = active[i];
            const cd newton = 1.0 / logd[i - lo];
            cd repel = 0.0;
            for (Index k = 0; k < n; ++k)
              if (k != j) repel += Reciprocal(z(j) - z(k));
            step[i] = newton / (1.0 - newton * repel);
          }
        },
        threads);
    for (std::size_t i = 0; i < active.size(); ++i) {
      const Index j = active[i];
      const cd w = step[i];
      if (!Finite(w)) return std::nullopt;
      z(j) -= w;
      const double size = std::abs(w), tol = std::abs(z(j)) + 1e-3 * scale;
      const std::size_t s = static_cast<std::size_t>(j);
      // Converged, or stalled at the level of rounding.
      if (size <= 4.0 * kEps * tol || (size <= 1e-12 * tol && size >= 0.5 * last[s])) done[s] = 1;
      last[s] = size;
    }
  }
  return std::nullopt;
}

}  // namespace

CoupledSolve SolveCoupled(const CoupledRealisation& sys, int threads) {
  CoupledSolve out;
  Diagonal dg = Diagonalise(sys);
  const Index n = dg.d.size();
  if (n == 0) {
    out.why_not = "no states";
    return out;
  }
  CoupledSpectrum sp;
  sp.blocks = static_cast<int>(sys.blocks.size());
  sp.rank = static_cast<int>(dg.u.cols());
  // No coupling at all (a modal path in series with a gain): a coupling of
  // one zero column, which leaves every pole its block's, so that the rows
  // and columns below are never slices of empty matrices.
  if (dg.u.cols() == 0) {
    dg.u = MatrixXcd::Zero(n, 1);
    dg.v = MatrixXcd::Zero(n, 1);
  }
  const Index r = dg.u.cols();
  // A row of U or of V whose part of U V^T is at the level of rounding in A
  // is made zero: the pole of a mode the loop does not drive (U) or does
  // not see (V) is then exactly its block's, and stays out of the iteration.
  const double size_u = dg.u.norm(), size_v = dg.v.norm();
  const double floor = 8.0 * kEps * (dg.d.cwiseAbs().maxCoeff() + size_u * size_v);
  std::vector<Index> free, fixed;
  for (Index k = 0; k < n; ++k) {
    if (dg.u.row(k).norm() * size_v <= floor) dg.u.row(k).setZero();
    if (dg.v.row(k).norm() * size_u <= floor) dg.v.row(k).setZero();
    (dg.u.row(k).squaredNorm() > 0.0 && dg.v.row(k).squaredNorm() > 0.0 ? free : fixed).push_back(k);
  }
  const Index nf = static_cast<Index>(free.size());
  Diagonal sub;
  sub.d = dg.d(free);
  sub.u = dg.u(free, Eigen::all);
  sub.v = dg.v(free, Eigen::all);
  sp.poles.resize(n);
  if (nf > 0) {
    const Secular sec_free(sub);
    std::optional<VectorXcd> z = Aberth(sub, sec_free, threads, &sp.sweeps);
    if (!z) {
      out.why_not = "the poles' iteration did not converge in " + std::to_string(kMaxAberthSweeps) + " sweeps";
      return out;
    }
    sp.poles.head(nf) = *z;
  }
  for (std::size_t i = 0; i < fixed.size(); ++i) sp.poles(nf + static_cast<Index>(i)) = dg.d(fixed[i]);
  const Secular sec(dg);
  // Two invariants of A: a pole lost or found twice shows in them.
  {
    cd trace = dg.d.sum(), trace2 = dg.d.array().square().sum();
    if (r > 0) {
      const MatrixXcd vu = dg.v.transpose() * dg.u;
      trace += vu.trace();
      trace2 += 2.0 * (dg.d.array() * (dg.u.array() * dg.v.array()).rowwise().sum()).sum() + (vu * vu).trace();
    }
    const double size = sp.poles.cwiseAbs().sum(), size2 = sp.poles.cwiseAbs2().sum();
    if (!(std::abs(sp.poles.sum() - trace) <= 1e-9 * size) ||
        !(std::abs(sp.poles.array().square().sum() - trace2) <= 1e-9 * size2)) {
      out.why_not = "the poles found do not reproduce tr A and tr A^2";
      return out;
    }
  }
  // Eigenvectors, in blocks of poles. They are not kept (two n x n complex
  // matrices, 512 MB for a loop around 2000 modes): only what the closed
  // form needs of them, C~ = C V, B~ = W^T B, W^T U and their absolute
  // sums |C| |V|, |W|^T |B|, formed block by block as products.
  const Index p = dg.c.rows(), m = dg.b.cols();
  sp.c_tilde = MatrixXcd::Zero(p, n);
  sp.abs_c_tilde = MatrixXd::Zero(p, n);
  sp.b_tilde = MatrixXcd::Zero(n, m);
  sp.abs_b_tilde = MatrixXd::Zero(n, m);
  sp.wu = MatrixXcd::Zero(n, r);
  sp.y = MatrixXcd::Zero(r, n);
  sp.x = MatrixXcd::Zero(r, n);
  sp.rho = MatrixXcd::Zero(r, n);
  sp.sigma = MatrixXcd::Zero(r, n);
  const MatrixXd abs_c = dg.c.cwiseAbs(), abs_b = dg.b.cwiseAbs();
  // Poles first .. first + count - 1, their right eigenvectors the columns
  // of v (n x count) and left ones the rows of w (count x n).
  const auto keep = [&](Index first, const MatrixXcd& v, const MatrixXcd& w) {
    const Index count = v.cols();
    sp.c_tilde.middleCols(first, count).noalias() = dg.c * v;
    sp.abs_c_tilde.middleCols(first, count).noalias() = abs_c * v.cwiseAbs();
    sp.b_tilde.middleRows(first, count).noalias() = w * dg.b;
    sp.abs_b_tilde.middleRows(first, count).noalias() = w.cwiseAbs() * abs_b;
    sp.wu.middleRows(first, count).noalias() = w * dg.u;
  };
  std::vector<double> kappa(static_cast<std::size_t>(n), 1.0);
  std::vector<char> bad(static_cast<std::size_t>(n), 0);
  // A pole the loop does not move: with U_k = 0 its left eigenvector is e_k
  // and its right one e_k + R~ U s, (I - V^T R~ U) s = V_k, R~ the resolvent
  // at d_k without index k; with V_k = 0 the transposed case. Both
  // satisfy w^T v = 1 as they stand.
  for (std::size_t i = 0; i < fixed.size(); ++i) {
    const Index k = fixed[i], j = nf + static_cast<Index>(i);
    VectorXcd v = VectorXcd::Zero(n), w = VectorXcd::Zero(n);
    v(k) = 1.0;
    w(k) = 1.0;
    const bool driven = dg.u.row(k).squaredNorm() > 0.0, seen = dg.v.row(k).squaredNorm() > 0.0;
    if (driven || seen) {
      VectorXcd cz = sec.Resolvents(&dg.d(k), 1).col(0);
      cz(k) = 0.0;
      const MatrixXcd mk = sec.M(cz);
      const Eigen::PartialPivLU<MatrixXcd> lu(mk);
      if (seen) {
        const VectorXcd s_k = lu.solve(VectorXcd(dg.v.row(k).transpose()));
        v = cz.cwiseProduct(dg.u * s_k);
        v(k) = 1.0;
      } else {
        const VectorXcd t = lu.transpose().solve(VectorXcd(dg.u.row(k).transpose()));
        w = cz.cwiseProduct(dg.v * t);
        w(k) = 1.0;
      }
    }
    keep(j, v, w.transpose());
    kappa[static_cast<std::size_t>(j)] = v.norm() * w.norm();
    if (!std::isfinite(kappa[static_cast<std::size_t>(j)])) bad[static_cast<std::size_t>(j)] = 1;
  }
  ParallelForBlocks(
      static_cast<std::size_t>(nf), 64,
      [&](std::size_t lo, std::size_t hi) {
        const Index count = static_cast<Index>(hi - lo);
        const MatrixXcd cz = sec.Resolvents(sp.poles.data() + lo, count);
        MatrixXcd right = MatrixXcd::Zero(n, count), left = MatrixXcd::Zero(count, n);
        for (std::size_t i = lo; i < hi; ++i) {
          const Index j = static_cast<Index>(i), at = static_cast<Index>(i - lo);
          const auto czj = cz.col(at);
          const MatrixXcd mj = sec.M(czj);
          const Eigen::JacobiSVD<MatrixXcd> svd(mj, Eigen::ComputeFullU | Eigen::ComputeFullV);
          VectorXcd yj = svd.matrixV().col(r - 1), xj = svd.matrixU().col(r - 1);
          VectorXcd v = czj.cwiseProduct(dg.u * yj);
          const double norm = v.norm();
          if (!(norm > 0.0) || !std::isfinite(norm)) {
            bad[i] = 1;
            continue;
          }
          v /= norm;
          yj /= norm;
          VectorXcd w = czj.cwiseProduct(dg.v * xj.conjugate());
          const cd wv = (w.array() * v.array()).sum();
          if (!(std::abs(wv) > 0.0) || !Finite(wv)) {
            bad[i] = 1;
            continue;
          }
          w /= wv;
          xj /= std::conj(wv);
          right.col(at) = v;
          left.row(at) = w.transpose();
          sp.y.col(j) = yj;
          sp.x.col(j) = xj;
          sp.rho.col(j) = -(mj * yj);
          sp.sigma.col(j) = -(mj.adjoint() * xj);
          kappa[i] = w.norm();
        }
        keep(static_cast<Index>(lo), right, left);
      },
      threads);
  if (std::any_of(bad.begin(), bad.end(), [](char b) { return b != 0; })) {
    out.why_not = "a pole found lies on a block's own pole, where its eigenvectors are not finite";
    return out;
  }
  sp.eigenvalue_condition = *std::max_element(kappa.begin(), kappa.end());
  if (!std::isfinite(sp.eigenvalue_condition)) {
    out.why_not = "an eigenvector is not finite";
    return out;
  }
  sp.d = std::move(dg.d_feed);
  out.spectrum = std::move(sp);
  return out;
}

CoupledCovariance CoupledOutputCovariance(const CoupledSpectrum& sp, const std::vector<int>& rows,
                                          const Eigen::MatrixXd& w_two_sided) {
  const Index n = sp.poles.size(), p = static_cast<Index>(rows.size()), r = sp.y.rows();
  DEB_DEMAND(w_two_sided.rows() == sp.b_tilde.cols() && w_two_sided.cols() == sp.b_tilde.cols());
  CoupledCovariance out;
  if (n == 0) {
    out.covariance = MatrixXd::Zero(p, p);
    out.relative_error = Eigen::VectorXd::Zero(p);
    return out;
  }
  MatrixXcd ch(p, n);  // C~ (p x N)
  MatrixXd abs_c(p, n);
  for (Index i = 0; i < p; ++i) {
    ch.row(i) = sp.c_tilde.row(rows[static_cast<std::size_t>(i)]);
    abs_c.row(i) = sp.abs_c_tilde.row(rows[static_cast<std::size_t>(i)]);
  }
  const MatrixXcd w = w_two_sided.cast<cd>();
  const MatrixXcd& bh = sp.b_tilde;  // B~ (N x m)
  const MatrixXcd bw = bh * w, bh_adj = bh.adjoint(), ch_adj = ch.adjoint();
  const MatrixXd abs_bw = sp.abs_b_tilde * w_two_sided.cwiseAbs(), abs_bt = sp.abs_b_tilde.transpose(),
                 abs_ct = abs_c.transpose();

  // The closed form's n x n matrices, G o (B~ W B~^H) and those of its error
  // estimate, are formed a slab of rows at a time and used at once: O(n) of
  // memory per slab instead of O(n^2) (a loop around 2000 modes: 1.66 GB
  // before). The slabs are fixed by n alone (ParallelForBlocks), and their
  // sums are added in order, so that the result does not depend on the
  // thread count. for_slabs: body(slab, first row, rows).
  constexpr std::size_t kSlab = 128;
  const std::size_t slabs = (static_cast<std::size_t>(n) + kSlab - 1) / kSlab;
  const auto for_slabs = [&](const std::function<void(std::size_t, Index, Index)>& body) {
    ParallelForBlocks(static_cast<std::size_t>(n), kSlab, [&](std::size_t begin, std::size_t end) {
      body(begin / kSlab, static_cast<Index>(begin), static_cast<Index>(end - begin));
    });
  };
  // G's rows first .. first + count - 1: G_ij = -1 / (mu_i + conj mu_j).
  const auto g_rows = [&](Index first, Index count) {
    MatrixXcd g(count, n);
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i < count; ++i) g(i, j) = -Reciprocal(sp.poles(first + i) + std::conj(sp.poles(j)));
    return g;
  };
  // A sum over slabs, added in slab order.
  const auto total = [](const auto& parts) {
    auto sum = parts.front();
    for (std::size_t s = 1; s < parts.size(); ++s) sum += parts[s];
    return sum;
  };

  // Pass 1: C~ X C~^H, rho X and the rounding's |C~| |X| |C~|^T, X = G o K,
  // K = B~ W B~^H. X is Hermitian (G_ji = conj G_ij, K too), so a slab of
  // its rows gives the same columns of rho X = rho (X's rows)^H: no sum.
  std::vector<MatrixXcd> cov_parts(slabs, MatrixXcd::Zero(p, p));
  MatrixXcd px = MatrixXcd::Zero(r, n);  // rho X (r x N)
  std::vector<MatrixXd> abs_parts(slabs, MatrixXd::Zero(p, p));
  for_slabs([&](std::size_t s, Index first, Index count) {
    const MatrixXcd g = g_rows(first, count);
    MatrixXcd x = bw.middleRows(first, count) * bh_adj;
    x = g.cwiseProduct(x);
    const MatrixXcd x_ch = x * ch_adj;
    cov_parts[s].noalias() = ch.middleCols(first, count) * x_ch;
    if (r > 0) px.middleCols(first, count).noalias() = sp.rho * x.adjoint();
    MatrixXd abs_x = abs_bw.middleRows(first, count) * abs_bt;
    abs_x = g.cwiseAbs().cwiseProduct(abs_x);
    const MatrixXd abs_x_ct = abs_x * abs_ct;
    abs_parts[s].noalias() = abs_c.middleCols(first, count) * abs_x_ct;
  });
  const MatrixXcd cov = total(cov_parts);
  out.covariance = cov.real();
  const MatrixXd abs_cov = total(abs_parts);

  // The first-order correction L^-1(-R) of the residual R of the computed
  // P, seen through C (coupled_spectrum.h):
  //   C~ (G o (K - Z W Z^H + T + T^H)) C~^H,
  // delta_ij = (-x_i^H rho_j + sigma_i^H y_j) / (mu_j - mu_i) (0 for i = j),
  // Z = B~ + delta B~, T = (W^T U) (rho X + rho X delta^H).
  MatrixXcd correction = MatrixXcd::Zero(p, p);
  if (r > 0) {
    const MatrixXcd x_adj = sp.x.adjoint(), sigma_adj = sp.sigma.adjoint();
    // Pass 2: Z and rho X (I + delta)^H, by slabs of delta's rows.
    MatrixXcd z(n, bh.cols()), pxz(r, n);
    for_slabs([&](std::size_t, Index first, Index count) {
      MatrixXcd delta = -(x_adj.middleRows(first, count) * sp.rho);
      delta.noalias() += sigma_adj.middleRows(first, count) * sp.y;
      for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < count; ++i)
          delta(i, j) = first + i == j ? cd(0.0) : delta(i, j) / (sp.poles(j) - sp.poles(first + i));
      z.middleRows(first, count) = bh.middleRows(first, count);
      z.middleRows(first, count).noalias() += delta * bh;
      pxz.middleCols(first, count) = px.middleCols(first, count);
      pxz.middleCols(first, count).noalias() += px * delta.adjoint();
    });
    const MatrixXcd zw = z * w, z_adj = z.adjoint(), wu_adj = sp.wu.adjoint();
    // Pass 3: the correction, by slabs of rows.
    std::vector<MatrixXcd> parts(slabs, MatrixXcd::Zero(p, p));
    for_slabs([&](std::size_t s, Index first, Index count) {
      MatrixXcd f = bw.middleRows(first, count) * bh_adj;
      f.noalias() -= zw.middleRows(first, count) * z_adj;
      f.noalias() += sp.wu.middleRows(first, count) * pxz;
      f.noalias() += pxz.middleCols(first, count).adjoint() * wu_adj;
      f = g_rows(first, count).cwiseProduct(f);
      const MatrixXcd f_ch = f * ch_adj;
      parts[s].noalias() = ch.middleCols(first, count) * f_ch;
    });
    correction = total(parts);
  }
  // Rounding: each term of the closed form carries a relative error of a
  // few eps, summed here without the cancellation the terms have
  // (coupled_spectrum.h).
  out.relative_error.resize(p);
  for (Index i = 0; i < p; ++i) {
    const double v = out.covariance(i, i);
    const double e = std::abs(correction(i, i)) + std::abs(cov(i, i).imag()) + kRoundingPerTerm * abs_cov(i, i) +
                     kConditionMargin * kEps * sp.eigenvalue_condition * std::abs(v);
    out.relative_error(i) = v > 0.0 ? e / v : (e == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
  }
  return out;
}

}  // namespace deb
