#include "deb/systems/modal_response.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/parallel.h"
#include "deb/systems/lapack.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Entries of the per-block matrix of weighted output shapes (rows x modes x
// frequencies) a worker holds in the row form: 3.2 MB of doubles per part, so
// that it and the product's packed copies stay in cache (16 MB ran 1.6x
// slower).
constexpr double kBlockEntries = 4e5;
// The pair form holds (rows x inputs) x modes shape products: up to 2^24 of
// them (128 MiB); a larger model is evaluated in the row form.
constexpr double kMaxPairEntries = 16777216.0;
// Frequencies per block of the pair form: the gains (modes x 2 x this) and
// the product (pairs x 2 x this) of a block, a few MB at 1000 modes and 400
// pairs; the product's packing of the pair shapes is 1/(2 x this) of its work.
// Fewer where the product would exceed kMaxPairBlockValues (16 MB) per
// worker: many channels and few modes.
constexpr int kPairBlock = 128;
constexpr double kMaxPairBlockValues = 2097152.0;

}  // namespace

ModalResponse::ModalResponse(const ModalModel& model, const std::vector<int>& rows, Form form)
    : derivative_(DerivativeOrder(model.quantity)) {
  model.Validate();
  const int n = model.modes();
  w_.resize(n);
  two_zeta_w_.resize(n);
  for (int k = 0; k < n; ++k) {
    w_[k] = kTwoPi * model.f_hz[k];
    two_zeta_w_[k] = model.f_hz[k] > 0.0 ? 2.0 * model.zeta[k] * w_[k] : 0.0;
  }
  phi_out_t_.resize(n, static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    DEB_DEMAND(rows[i] >= 0 && rows[i] < model.phi_out.rows());
    phi_out_t_.col(static_cast<Eigen::Index>(i)) = model.phi_out.row(rows[i]).transpose();
  }
  phi_in_ = model.phi_in;
  if (model.residual.size() > 0) {
    residual_t_.resize(model.phi_in.rows(), static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
      residual_t_.col(static_cast<Eigen::Index>(i)) = model.residual.row(rows[i]).transpose();
  }
  const Eigen::Index p = outputs(), m = inputs();
  if (form == Form::kAuto && static_cast<double>(p) * static_cast<double>(m) * static_cast<double>(n) <= kMaxPairEntries) {
    // pair_shapes_(r + p j, k) = phi_out(r, k) phi_in(j, k)
    pair_shapes_.resize(p * m, n);
    for (Eigen::Index j = 0; j < m; ++j)
      for (Eigen::Index r = 0; r < p; ++r)
        pair_shapes_.row(r + p * j) = phi_out_t_.col(r).transpose().cwiseProduct(phi_in_.row(j));
    if (residual_t_.size() > 0) {
      pair_residual_.resize(p * m);
      for (Eigen::Index j = 0; j < m; ++j)
        for (Eigen::Index r = 0; r < p; ++r) pair_residual_(r + p * j) = residual_t_(j, r);
    }
  }
}

void ModalResponse::Gains(double f_hz, double* gr, double* gi) const {
  if (!std::isfinite(f_hz)) {
    std::ostringstream os;
    os << "frequency response: frequency " << f_hz << " Hz is not finite";
    throw InputError(os.str());
  }
  const double w = kTwoPi * f_hz;
  for (std::size_t k = 0; k < w_.size(); ++k) {
    const double wk = w_[k];
    // D = (w_k - w)(w_k + w) + j 2 zeta_k w_k w;  g = (j w)^n / D = (j w)^n conj(D) / |D|^2
    const double dr = (wk - w) * (wk + w), di = two_zeta_w_[k] * w, dd = dr * dr + di * di;
    if (!(dd > 0.0) || std::sqrt(dd) <= 64.0 * kEps * (wk * wk + w * w)) {
      std::ostringstream os;
      os << "frequency response: frequency " << f_hz << " Hz coincides with a pole of the path (mode "
         << k + 1 << " at " << wk / kTwoPi << " Hz); H is unbounded there, leave this frequency out of the grid";
      throw InputError(os.str());
    }
    double re = dr / dd, im = -di / dd;
    if (derivative_ == 1) {
      const double t = re;
      re = -w * im;
      im = w * t;
    } else if (derivative_ == 2) {
      re *= -w * w;
      im *= -w * w;
    }
    gr[k] = re;
    gi[k] = im;
  }
}

void ModalResponse::EvaluateBlock(const double* f_hz, int count, Eigen::MatrixXd& xr, Eigen::MatrixXd& xi,
                                  Eigen::MatrixXd& hr, Eigen::MatrixXd& hi) const {
  const Eigen::Index p = phi_out_t_.cols(), n = phi_out_t_.rows();
  xr.resize(n, count * p);
  xi.resize(n, count * p);
  std::vector<double> gr(n), gi(n);
  for (int i = 0; i < count; ++i) {
    Gains(f_hz[i], gr.data(), gi.data());
    for (Eigen::Index r = 0; r < p; ++r) {
      const Eigen::Index col = i * p + r;
      const double* a = phi_out_t_.data() + r * n;
      double* outr = xr.data() + col * n;
      double* outi = xi.data() + col * n;
      for (Eigen::Index k = 0; k < n; ++k) {
        outr[k] = a[k] * gr[k];
        outi[k] = a[k] * gi[k];
      }
    }
  }
  hr.noalias() = phi_in_ * xr;
  hi.noalias() = phi_in_ * xi;
  if (residual_t_.size() > 0)
    for (int i = 0; i < count; ++i) hr.middleCols(i * p, p) += residual_t_;
}

void ModalResponse::EvaluatePairs(const double* f_hz, int count, Eigen::MatrixXd& g, Eigen::MatrixXd& h) const {
  const Eigen::Index n = modes();
  g.resize(n, 2 * count);
  for (int i = 0; i < count; ++i) Gains(f_hz[i], g.col(2 * i).data(), g.col(2 * i + 1).data());
  h.resize(pair_shapes_.rows(), 2 * count);
  if (BlasProductIsFaster())
    BlasProduct(pair_shapes_, g, h);
  else
    h.noalias() = pair_shapes_ * g;
  if (pair_residual_.size() > 0)
    for (int i = 0; i < count; ++i) h.col(2 * i) += pair_residual_;
}

void ModalResponse::PairColumnsTo(const Eigen::MatrixXd& h, int i, Eigen::MatrixXcd& out) const {
  const Eigen::Index p = outputs(), m = inputs();
  const double* re = h.col(2 * i).data();
  const double* im = h.col(2 * i + 1).data();
  Complex* o = out.data();  // column-major p x m: entry r + p j
  for (Eigen::Index q = 0; q < p * m; ++q) o[q] = Complex(re[q], im[q]);
}

Eigen::MatrixXcd ModalResponse::At(double f_hz) const {
  if (PairForm()) {
    Eigen::MatrixXd g, hp;
    EvaluatePairs(&f_hz, 1, g, hp);
    Eigen::MatrixXcd h(outputs(), inputs());
    PairColumnsTo(hp, 0, h);
    return h;
  }
  Eigen::MatrixXd xr, xi, hr, hi;
  EvaluateBlock(&f_hz, 1, xr, xi, hr, hi);
  Eigen::MatrixXcd h(hr.cols(), hr.rows());
  h.real() = hr.transpose();
  h.imag() = hi.transpose();
  return h;
}

void ModalResponse::ForEach(const std::vector<double>& f_hz, const Visitor& fn, int threads) const {
  const Eigen::Index p = outputs(), m = inputs();
  if (PairForm()) {
    // Blocks fixed by the frequency count and the model alone, as below.
    const std::size_t block = static_cast<std::size_t>(std::clamp(
        std::floor(kMaxPairBlockValues / std::max(1.0, 2.0 * static_cast<double>(p * m))), 1.0,
        static_cast<double>(kPairBlock)));
    const std::size_t blocks = (f_hz.size() + block - 1) / block;
    ParallelFor(
        blocks,
        [&](std::size_t b0, std::size_t b1) {
          Eigen::MatrixXd g, hp;
          Eigen::MatrixXcd h(p, m);
          for (std::size_t b = b0; b < b1; ++b) {
            const std::size_t k0 = b * block;
            const int count = static_cast<int>(std::min(block, f_hz.size() - k0));
            EvaluatePairs(f_hz.data() + k0, count, g, hp);
            for (int i = 0; i < count; ++i) {
              PairColumnsTo(hp, i, h);
              fn(k0 + i, h);
            }
          }
        },
        threads, 1);
    return;
  }
  const double per_frequency = std::max<double>(1.0, static_cast<double>(p) * std::max(1, modes()));
  const std::size_t block = static_cast<std::size_t>(std::clamp(kBlockEntries / per_frequency, 1.0, 256.0));
  // The blocks are fixed by the frequency count alone and handed out whole:
  // the matrix product sums a column in an order that depends on the block's
  // width and the column's place in it, so blocks cut where a thread's range
  // ends would make the last digits depend on the thread count.
  const std::size_t blocks = (f_hz.size() + block - 1) / block;
  ParallelFor(
      blocks,
      [&](std::size_t b0, std::size_t b1) {
        Eigen::MatrixXd xr, xi, hr, hi;
        Eigen::MatrixXcd h(p, m);
        for (std::size_t b = b0; b < b1; ++b) {
          const std::size_t k0 = b * block;
          const int count = static_cast<int>(std::min(block, f_hz.size() - k0));
          EvaluateBlock(f_hz.data() + k0, count, xr, xi, hr, hi);
          for (int i = 0; i < count; ++i) {
            for (Eigen::Index j = 0; j < m; ++j)
              for (Eigen::Index r = 0; r < p; ++r) h(r, j) = Complex(hr(j, i * p + r), hi(j, i * p + r));
            fn(k0 + i, h);
          }
        }
      },
      threads, 1);
}

void ModalResponse::AddModeParts(double f_hz, const std::vector<int>& columns, const Eigen::MatrixXcd& t,
                                 const std::vector<double>& weight, Eigen::MatrixXd& parts) const {
  const Eigen::Index n = modes(), c = t.cols();
  DEB_DEMAND(t.rows() == inputs() && static_cast<Eigen::Index>(columns.size()) == c &&
             static_cast<Eigen::Index>(weight.size()) == c && parts.rows() == n && parts.cols() == c);
  std::vector<double> gr(static_cast<std::size_t>(n)), gi(static_cast<std::size_t>(n));
  Gains(f_hz, gr.data(), gi.data());
  // a = Phi_in^T t: the modal loads phi_in,k^T t of every column, in real arithmetic.
  const Eigen::MatrixXd ar = phi_in_.transpose() * t.real(), ai = phi_in_.transpose() * t.imag();
  for (Eigen::Index j = 0; j < c; ++j) {
    const int r = columns[static_cast<std::size_t>(j)];
    DEB_DEMAND(r >= 0 && r < outputs());
    const double* shape = phi_out_t_.data() + static_cast<Eigen::Index>(r) * n;
    for (Eigen::Index k = 0; k < n; ++k)  // Re(g_k a_k) phi_out(r, k)
      parts(k, j) += weight[static_cast<std::size_t>(j)] * shape[k] * (gr[k] * ar(k, j) - gi[k] * ai(k, j));
  }
}

namespace {

// ModalOutputCovariance, and with `cross` also Y = M A (modes x rows, M the
// modal covariance, A the rows' output shapes as columns), accumulated in the
// same pass over the mode pairs: the covariance matrix is then A^T Y.
ModalCovariance SolveModalCovariance(const ModalModel& model, const std::vector<int>& rows,
                                     const Eigen::MatrixXd& w_two_sided, Eigen::MatrixXd* cross) {
  model.Validate();
  const int n = model.modes();
  const Eigen::Index m = model.phi_in.rows();
  if (w_two_sided.rows() != m || w_two_sided.cols() != m) {
    std::ostringstream os;
    os << "modal covariance: noise intensity W is " << w_two_sided.rows() << "x" << w_two_sided.cols()
       << ", the model has " << m << " input(s)";
    throw InputError(os.str());
  }
  for (Eigen::Index i = 0; i < m; ++i) {
    if (!std::isfinite(w_two_sided(i, i)) || w_two_sided(i, i) < 0.0)
      throw InputError("modal covariance: W(" + std::to_string(i + 1) + "," + std::to_string(i + 1) +
                       ") must be finite and >= 0");
    for (Eigen::Index j = 0; j < i; ++j)
      if (!(std::abs(w_two_sided(i, j) - w_two_sided(j, i)) <=
            1e-12 * std::max(1.0, std::abs(w_two_sided(i, j)) + std::abs(w_two_sided(j, i)))))
        throw InputError("modal covariance: W is not symmetric");
  }
  for (int k = 0; k < n; ++k)
    if (!(model.f_hz[k] > 0.0))
      throw InputError("exact variance needs a stable path; mode " + std::to_string(k + 1) +
                       " is a rigid-body mode (f = 0 Hz: poles at the origin)");
  const int derivative = DerivativeOrder(model.quantity);
  if (model.residual.size() > 0) {
    const Eigen::MatrixXd dwd = model.residual * w_two_sided * model.residual.transpose();
    for (int r : rows)
      if (dwd(r, r) > 0.0)
        throw InputError("infinite variance: the static residual (residual: static) is a feedthrough D != 0, "
                         "which passes white noise at all frequencies");
  }
  if (derivative == 2) {
    // q'' carries the input directly (D = Phi_out Phi_in^T): infinite
    // variance unless no noise reaches an output through it.
    const Eigen::MatrixXd d = model.phi_out * model.phi_in.transpose();
    const Eigen::MatrixXd dwd = d * w_two_sided * d.transpose();
    for (int r : rows)
      if (dwd(r, r) > 0.0)
        throw InputError("infinite variance: direct feedthrough D != 0 under white noise (an acceleration "
                         "output of a modal path responds to a white force at all frequencies)");
  }
  // Partial fractions of each g_k: its poles and residues.
  std::vector<Complex> pole(n), res_pole(n), res_conj(n);
  for (int k = 0; k < n; ++k) {
    const Complex lambda = ModalPole(model.f_hz[k], model.zeta[k]);
    const Complex diff = lambda - std::conj(lambda);
    Complex num = 1.0, num_conj = 1.0;
    for (int d = 0; d < derivative; ++d) {
      num *= lambda;
      num_conj *= std::conj(lambda);
    }
    pole[k] = lambda;
    res_pole[k] = num / diff;
    res_conj[k] = -num_conj / diff;
  }
  // Term (k, l) of row r: a_rk a_rl F_kl I_kl with the modal forces'
  // intensity F_kl = phi_in,k^T W phi_in,l and I_kl = integral of g_k
  // conj(g_l) dw / 2 pi. The pair (k, l), (l, k) is split half to each mode.
  const Eigen::Index p = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd a(n, p);  // a.row(k): mode k at every row
  for (Eigen::Index i = 0; i < p; ++i) a.col(i) = model.phi_out.row(rows[i]).transpose();
  const Eigen::MatrixXd w_phi = w_two_sided * model.phi_in;  // m x n
  // Rows k in fixed blocks of kCovarianceRows on all threads, each block
  // summing into its own share, rounding and cross terms; the blocks are
  // added in order, so the sums do not depend on the thread count.
  constexpr std::size_t kCovarianceRows = 256;
  struct Partial {
    Eigen::MatrixXd share, cross;
    Eigen::VectorXd rounding;
  };
  std::vector<Partial> partial((static_cast<std::size_t>(n) + kCovarianceRows - 1) / kCovarianceRows);
  ParallelForBlocks(static_cast<std::size_t>(n), kCovarianceRows, [&](std::size_t k0, std::size_t k1) {
    Partial& part = partial[k0 / kCovarianceRows];
    part.share = Eigen::MatrixXd::Zero(n, p);
    part.rounding = Eigen::VectorXd::Zero(p);
    if (cross) part.cross = Eigen::MatrixXd::Zero(n, p);
    for (int k = static_cast<int>(k0); k < static_cast<int>(k1); ++k) {
      const Complex ak[2] = {pole[k], std::conj(pole[k])}, rk[2] = {res_pole[k], res_conj[k]};
      for (int l = 0; l <= k; ++l) {
        const double force = model.phi_in.col(k).dot(w_phi.col(l));
        if (force == 0.0) continue;
        const Complex bl[2] = {pole[l], std::conj(pole[l])}, rl[2] = {res_pole[l], res_conj[l]};
        Complex sum = 0.0;
        double abs_sum = 0.0;  // |re| + |im| of each term: at most sqrt 2 times its modulus, no hypot
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) {
            const Complex t = -rk[i] * std::conj(rl[j]) / (ak[i] + std::conj(bl[j]));
            sum += t;
            abs_sum += std::abs(t.real()) + std::abs(t.imag());
          }
        const double c = force * sum.real(), b = (k == l ? 1.0 : 2.0) * std::abs(force) * abs_sum;
        for (Eigen::Index r = 0; r < p; ++r) {
          const double t = a(k, r) * a(l, r) * c;
          part.share(k, r) += t;
          if (k != l) part.share(l, r) += t;
          part.rounding(r) += std::abs(a(k, r) * a(l, r)) * b;
        }
        if (cross) {  // M_kl = M_lk = c
          part.cross.row(k) += c * a.row(l);
          if (k != l) part.cross.row(l) += c * a.row(k);
        }
      }
    }
  });
  Eigen::MatrixXd share = Eigen::MatrixXd::Zero(n, p);
  Eigen::VectorXd rounding = Eigen::VectorXd::Zero(p);
  if (cross) *cross = Eigen::MatrixXd::Zero(n, p);
  for (const Partial& part : partial) {
    share += part.share;
    rounding += part.rounding;
    if (cross) *cross += part.cross;
  }
  ModalCovariance result;
  result.share = share.transpose();
  result.variance = result.share.rowwise().sum();
  for (Eigen::Index i = 0; i < p; ++i) {
    const double var = result.variance(i), bound = 8.0 * n * kEps * rounding(i);
    if (var == 0.0 && bound == 0.0) continue;
    if (!std::isfinite(var) || var < 0.0 || bound > 1e-6 * var) {
      std::ostringstream os;
      os << "exact variance is not reliable for this model: output " << model.output_names[rows[i]] << " gives "
         << var << " with a rounding bound of " << bound
         << " (its modes cancel each other almost completely)";
      throw InputError(os.str());
    }
  }
  return result;
}

}  // namespace

ModalCovariance ModalOutputCovariance(const ModalModel& model, const std::vector<int>& rows,
                                      const Eigen::MatrixXd& w_two_sided) {
  return SolveModalCovariance(model, rows, w_two_sided, nullptr);
}

Eigen::MatrixXd ModalOutputCovarianceMatrix(const ModalModel& model, const std::vector<int>& rows,
                                            const Eigen::MatrixXd& w_two_sided) {
  Eigen::MatrixXd y;
  const ModalCovariance own = SolveModalCovariance(model, rows, w_two_sided, &y);
  const Eigen::Index p = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd a(model.modes(), p);
  for (Eigen::Index i = 0; i < p; ++i) a.col(i) = model.phi_out.row(rows[static_cast<std::size_t>(i)]).transpose();
  const Eigen::MatrixXd c = a.transpose() * y;
  Eigen::MatrixXd cov = (c + c.transpose()) / 2.0;  // symmetric exactly, not to rounding
  // The diagonal as ModalOutputCovariance sums it (its shares), so that it is
  // each row's exact variance to the bit.
  for (Eigen::Index i = 0; i < p; ++i) cov(i, i) = own.variance(i);
  return cov;
}

}  // namespace deb
