#include "deb/systems/axis_cancellation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/lapack.h"
#include "deb/systems/modes.h"

namespace deb {

std::optional<AxisCancellation> CancelAxisPoles(const StateSpace& sys) {
  const int n = sys.states();
  if (n == 0) return std::nullopt;
  const StateSpace balanced = sys.Balanced();
  RealSchurForm form;
  try {
    form = RealSchur(balanced.A());
  } catch (const InputError&) {
    return std::nullopt;
  }
  const PoleStability stability = ClassifyPoles(form.eigenvalues);
  if (!stability.unstable.empty() || stability.marginal.empty()) return std::nullopt;
  std::vector<bool> stable(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) stable[static_cast<std::size_t>(k)] = IsStrictlyStable(form.eigenvalues(k));
  int ns = 0;
  try {
    ns = ReorderRealSchur(form, stable);
  } catch (const InputError&) {
    return std::nullopt;
  }
  // The reordering may move an eigenvalue across the rule by rounding.
  if (ClassifyPoles(form.eigenvalues.head(ns)).marginal.size() != 0 ||
      ClassifyPoles(form.eigenvalues.tail(n - ns)).marginal.size() != static_cast<std::size_t>(n - ns))
    return std::nullopt;
  const int nm = n - ns;
  const Eigen::MatrixXd t11 = form.t.topLeftCorner(ns, ns), t12 = form.t.topRightCorner(ns, nm),
                        t22 = form.t.bottomRightCorner(nm, nm);
  const SylvesterSolution x = SolveQuasiTriangularSylvesterMinus(t11, t22, -t12);
  if (x.near_singular || !x.x.allFinite()) return std::nullopt;
  const double x_norm = x.x.norm();
  if (x_norm > kMaxDecoupling) return std::nullopt;

  const Eigen::MatrixXd bq = form.u.transpose() * balanced.B(), cq = balanced.C() * form.u;
  const Eigen::MatrixXd b2 = bq.bottomRows(nm);
  const Eigen::MatrixXd cm = cq.leftCols(ns) * x.x + cq.rightCols(nm);
  // The size of the terms each Markov parameter sums, entry by entry: what
  // its rounding is relative to, whatever the scaling of the states.
  const Eigen::MatrixXd cq_abs = balanced.C().cwiseAbs() * form.u.cwiseAbs();
  const Eigen::MatrixXd b2_abs = form.u.rightCols(nm).transpose().cwiseAbs() * balanced.B().cwiseAbs();
  const Eigen::MatrixXd cm_abs = cq_abs.leftCols(ns) * x.x.cwiseAbs() + cq_abs.rightCols(nm);
  const Eigen::MatrixXd t22_abs = t22.cwiseAbs();
  double worst = 0.0;
  Eigen::MatrixXd power_b = b2, power_b_abs = b2_abs;  // T22^k B2, |T22|^k |B2|
  for (int k = 0; k < nm; ++k) {
    const Eigen::MatrixXd markov = cm * power_b, terms = cm_abs * power_b_abs;
    for (Eigen::Index i = 0; i < markov.rows(); ++i)
      for (Eigen::Index j = 0; j < markov.cols(); ++j) {
        const double m = std::abs(markov(i, j));
        if (m == 0.0) continue;
        if (!(terms(i, j) > 0.0)) return std::nullopt;
        worst = std::max(worst, m / terms(i, j));
      }
    power_b = t22 * power_b;
    power_b_abs = t22_abs * power_b_abs;
  }
  if (!(worst <= kCancellationTolerance)) return std::nullopt;

  AxisCancellation result{StateSpace(t11, bq.topRows(ns) - x.x * b2, cq.leftCols(ns), balanced.D()),
                          form.eigenvalues.tail(nm), worst};
  return result;
}

}  // namespace deb
