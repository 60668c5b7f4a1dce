#include "deb/systems/coupled_realisation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"

namespace deb {
namespace {

using Eigen::MatrixXd;

MatrixXd BlockDiag(const MatrixXd& a, const MatrixXd& b) {
  MatrixXd m = MatrixXd::Zero(a.rows() + b.rows(), a.cols() + b.cols());
  // (A block of an empty matrix is not taken: its data pointer is null.)
  if (a.size() > 0) m.topLeftCorner(a.rows(), a.cols()) = a;
  if (b.size() > 0) m.bottomRightCorner(b.rows(), b.cols()) = b;
  return m;
}

double LargestBlockNorm(const std::vector<MatrixXd>& blocks) {
  double s = 0.0;
  for (const MatrixXd& a : blocks) s = std::max(s, a.norm());
  return s;
}

// U V^T recompressed to its numerical rank (see the header).
void Compress(CoupledRealisation* sys) {
  const Eigen::Index q = sys->u.cols();
  const Eigen::Index n = sys->u.rows();
  if (q == 0) return;
  const Eigen::HouseholderQR<MatrixXd> qr_u(sys->u), qr_v(sys->v);
  const Eigen::Index k = std::min(n, q);
  const MatrixXd q_u = qr_u.householderQ() * MatrixXd::Identity(n, k);
  const MatrixXd q_v = qr_v.householderQ() * MatrixXd::Identity(n, k);
  const MatrixXd r_u = qr_u.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  const MatrixXd r_v = qr_v.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  const Eigen::JacobiSVD<MatrixXd> svd(r_u * r_v.transpose(), Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double scale = std::max(s.size() > 0 ? s(0) : 0.0, LargestBlockNorm(sys->blocks));
  const double floor = 8.0 * std::numeric_limits<double>::epsilon() * scale;
  Eigen::Index rank = 0;
  while (rank < s.size() && s(rank) > floor) ++rank;
  const Eigen::VectorXd root = s.head(rank).cwiseSqrt();
  sys->u = q_u * svd.matrixU().leftCols(rank) * root.asDiagonal();
  sys->v = q_v * svd.matrixV().leftCols(rank) * root.asDiagonal();
}

// The couplings of a and b side by side (no coupling between them).
void JoinCouplings(const CoupledRealisation& a, const CoupledRealisation& b, CoupledRealisation* out) {
  out->blocks = a.blocks;
  out->blocks.insert(out->blocks.end(), b.blocks.begin(), b.blocks.end());
  out->u = BlockDiag(a.u, b.u);
  out->v = BlockDiag(a.v, b.v);
}

void AddCoupling(CoupledRealisation* sys, const MatrixXd& u, const MatrixXd& v) {
  DEB_DEMAND(u.rows() == sys->u.rows() && v.rows() == sys->v.rows() && u.cols() == v.cols());
  MatrixXd nu(u.rows(), sys->u.cols() + u.cols()), nv(v.rows(), sys->v.cols() + v.cols());
  nu << sys->u, u;
  nv << sys->v, v;
  sys->u = std::move(nu);
  sys->v = std::move(nv);
}

}  // namespace

int CoupledRealisation::largest_block() const {
  int s = 0;
  for (const MatrixXd& a : blocks) s = std::max(s, static_cast<int>(a.rows()));
  return s;
}

MatrixXd CoupledRealisation::DenseA() const {
  MatrixXd a = u * v.transpose();
  Eigen::Index at = 0;
  for (const MatrixXd& blk : blocks) {
    a.block(at, at, blk.rows(), blk.cols()) += blk;
    at += blk.rows();
  }
  return a;
}

CoupledRealisation CoupledOf(const StateSpace& rational) {
  CoupledRealisation sys;
  if (rational.states() > 0) sys.blocks.push_back(rational.A());
  sys.u = MatrixXd::Zero(rational.states(), 0);
  sys.v = MatrixXd::Zero(rational.states(), 0);
  sys.b = rational.B();
  sys.c = rational.C();
  sys.d = rational.D();
  return sys;
}

CoupledRealisation CoupledOf(const ModalModel& model) {
  // The modal realisation (ModalRealisation: no dense A), each mode's states
  // scaled by diag(w, 1): x = [w q, q'].
  ModalRealisationParts plain = ModalRealisation(model);
  CoupledRealisation sys;
  const int n = model.modes();
  sys.b = std::move(plain.b);
  sys.c = std::move(plain.c);
  sys.d = std::move(plain.d);
  for (int k = 0; k < n; ++k) {
    MatrixXd blk = plain.blocks[static_cast<std::size_t>(k)];
    const double w = kTwoPi * model.f_hz[k];
    if (w > 0.0) {  // T^-1 A T with T = diag(1 / w, 1): x_T = [w q, q']
      blk(0, 1) *= w;
      blk(1, 0) /= w;
      sys.b.row(2 * k) *= w;
      sys.c.col(2 * k) /= w;
    }
    sys.blocks.push_back(std::move(blk));
  }
  sys.u = MatrixXd::Zero(2 * n, 0);
  sys.v = MatrixXd::Zero(2 * n, 0);
  return sys;
}

CoupledRealisation CoupledSeries(const CoupledRealisation& first, const CoupledRealisation& second) {
  if (second.inputs() != first.outputs()) throw InputError("series: sizes do not fit");
  CoupledRealisation sys;
  JoinCouplings(first, second, &sys);
  const Eigen::Index n1 = first.states(), n2 = second.states();
  // [0; B2] [C1 0]
  MatrixXd u = MatrixXd::Zero(n1 + n2, second.inputs()), v = MatrixXd::Zero(n1 + n2, second.inputs());
  u.bottomRows(n2) = second.b;
  v.topRows(n1) = first.c.transpose();
  AddCoupling(&sys, u, v);
  sys.b.resize(n1 + n2, first.inputs());
  sys.b << first.b, second.b * first.d;
  sys.c.resize(second.outputs(), n1 + n2);
  sys.c << second.d * first.c, second.c;
  sys.d = second.d * first.d;
  Compress(&sys);
  return sys;
}

CoupledRealisation CoupledParallel(const CoupledRealisation& a, const CoupledRealisation& b) {
  if (a.inputs() != b.inputs() || a.outputs() != b.outputs()) throw InputError("parallel: sizes do not fit");
  CoupledRealisation sys;
  JoinCouplings(a, b, &sys);
  sys.b.resize(a.states() + b.states(), a.inputs());
  sys.b << a.b, b.b;
  sys.c.resize(a.outputs(), a.states() + b.states());
  sys.c << a.c, b.c;
  sys.d = a.d + b.d;
  return sys;
}

CoupledRealisation CoupledFeedback(const CoupledRealisation& g, const CoupledRealisation& k, int sign) {
  if (k.inputs() != g.outputs() || k.outputs() != g.inputs()) throw InputError("feedback: sizes do not fit");
  const double s = static_cast<double>(sign);
  const Eigen::Index ng = g.states(), nk = k.states(), m = g.inputs();
  const MatrixXd loop = MatrixXd::Identity(m, m) - s * k.d * g.d;
  const Eigen::FullPivLU<MatrixXd> lu(loop);
  if (!lu.isInvertible()) throw InputError("feedback: the algebraic loop I - sign D_k D_p is singular");
  const MatrixXd f = lu.inverse();
  CoupledRealisation sys;
  JoinCouplings(g, k, &sys);
  // [B_g; B_k D_g] F [s D_k C_g, s C_k]
  MatrixXd left(ng + nk, m), right(ng + nk, m);
  left << g.b, k.b * g.d;
  right << (s * f * k.d * g.c).transpose(), (s * f * k.c).transpose();
  AddCoupling(&sys, left, right);
  // [0; B_k] [C_g, 0]
  MatrixXd u2 = MatrixXd::Zero(ng + nk, g.outputs()), v2 = MatrixXd::Zero(ng + nk, g.outputs());
  u2.bottomRows(nk) = k.b;
  v2.topRows(ng) = g.c.transpose();
  AddCoupling(&sys, u2, v2);
  sys.b.resize(ng + nk, m);
  sys.b << g.b * f, k.b * g.d * f;
  sys.c.resize(g.outputs(), ng + nk);
  sys.c << g.c + g.d * f * s * k.d * g.c, g.d * f * s * k.c;
  sys.d = g.d * f;
  Compress(&sys);
  return sys;
}

CoupledRealisation CoupledSelectOutputs(const CoupledRealisation& sys, const std::vector<int>& rows) {
  CoupledRealisation out = sys;
  out.c.resize(static_cast<Eigen::Index>(rows.size()), sys.states());
  out.d.resize(static_cast<Eigen::Index>(rows.size()), sys.inputs());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    DEB_DEMAND(rows[i] >= 0 && rows[i] < sys.outputs());
    out.c.row(static_cast<Eigen::Index>(i)) = sys.c.row(rows[i]);
    out.d.row(static_cast<Eigen::Index>(i)) = sys.d.row(rows[i]);
  }
  return out;
}

}  // namespace deb
