#include "deb/systems/real_block_diagonal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "deb/core/error.h"
#include "deb/systems/lapack.h"

namespace deb {
namespace {

// The first rows of T's 1x1 and 2x2 diagonal blocks, then n.
std::vector<int> SchurBlockStarts(const Eigen::MatrixXd& t) {
  const int n = static_cast<int>(t.rows());
  std::vector<int> starts;
  for (int i = 0; i < n; i += (i + 1 < n && t(i + 1, i) != 0.0) ? 2 : 1) starts.push_back(i);
  starts.push_back(n);
  return starts;
}

int Root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// A cluster label per block (blocks of the same label have poles within
// `gap` of each other, relative, or within `floor` absolutely; transitively).
std::vector<int> ClusterLabels(const Eigen::VectorXcd& eigenvalues, const std::vector<int>& starts, double gap,
                               double floor) {
  const int blocks = static_cast<int>(starts.size()) - 1;
  std::vector<int> parent(blocks), by_size(blocks);
  std::iota(parent.begin(), parent.end(), 0);
  std::iota(by_size.begin(), by_size.end(), 0);
  const auto pole = [&](int b) { return eigenvalues(starts[b]); };
  std::sort(by_size.begin(), by_size.end(), [&](int a, int b) { return std::abs(pole(a)) < std::abs(pole(b)); });
  // |p - q| <= gap max(|p|, |q|) + floor needs ||p| - |q|| within the same.
  for (int i = 0; i < blocks; ++i)
    for (int j = i + 1; j < blocks; ++j) {
      const std::complex<double> p = pole(by_size[i]), q = pole(by_size[j]);
      const double reach = gap * std::abs(q) + floor;
      if (std::abs(q) - std::abs(p) > reach) break;
      if (std::abs(p - q) <= reach) parent[Root(parent, by_size[i])] = Root(parent, by_size[j]);
    }
  std::vector<int> label(blocks);
  for (int b = 0; b < blocks; ++b) label[b] = Root(parent, b);
  return label;
}

// Makes each cluster's blocks adjacent, moving later members up to the
// first member's run. A swap LAPACK refuses leaves that member where it
// stopped (counted in `failed`); the coupling test below still keeps the
// form exact.
void GatherClusters(RealSchurForm& f, double gap, double floor, int& failed) {
  std::size_t at = 0;  // index of the block whose cluster is being gathered
  for (;;) {
    const std::vector<int> starts = SchurBlockStarts(f.t);
    const std::vector<int> label = ClusterLabels(f.eigenvalues, starts, gap, floor);
    const std::size_t blocks = label.size();
    bool moved = false;
    while (at < blocks && !moved) {
      std::size_t run = at + 1;
      while (run < blocks && label[run] == label[at]) ++run;
      std::size_t next = run;
      while (next < blocks && label[next] != label[at]) ++next;
      if (next == blocks) {
        at = run;
        continue;
      }
      int from = starts[next], to = starts[run];
      if (!MoveRealSchurBlock(f, from, to)) {
        ++failed;
        at = run;  // leave the rest of this cluster where it is
      }
      moved = true;
    }
    if (!moved) return;
  }
}

}  // namespace

int RealBlockDiagonalForm::largest_group() const {
  int largest = 0;
  for (int g = 0; g < groups(); ++g) largest = std::max(largest, group_size(g));
  return largest;
}

Eigen::MatrixXd RealBlockDiagonalForm::Left(const Eigen::MatrixXd& c) const {
  return (c * u) * y.triangularView<Eigen::UnitUpper>();
}

Eigen::MatrixXd RealBlockDiagonalForm::Right(const Eigen::MatrixXd& b) const {
  return y.triangularView<Eigen::UnitUpper>().solve(u.transpose() * b);
}

RealBlockDiagonalForm RealBlockDiagonal(const Eigen::MatrixXd& a, double max_coupling, double cluster_gap) {
  DEB_DEMAND(max_coupling > 0.0 && cluster_gap >= 0.0);
  RealSchurForm f = RealSchur(a);
  const int n = static_cast<int>(a.rows());
  RealBlockDiagonalForm form;
  form.start.push_back(0);
  if (n == 0) return form;
  const double floor = 1e3 * std::numeric_limits<double>::epsilon() * a.norm();
  GatherClusters(f, cluster_gap, floor, form.swaps_failed);

  // Decoupling, group by group from the top.
  const std::vector<int> blocks = SchurBlockStarts(f.t);
  const std::vector<int> label = ClusterLabels(f.eigenvalues, blocks, cluster_gap, floor);
  Eigen::MatrixXd y = Eigen::MatrixXd::Identity(n, n);
  std::vector<int> group_start;  // starts of the groups found so far
  for (std::size_t b = 0; b + 1 < blocks.size(); ++b) {
    int s = blocks[b];
    const int e = blocks[b + 1];
    // A cluster is never split: its poles are too close for the coupling
    // to be bounded by anything but rounding.
    if (b > 0 && label[b] == label[b - 1]) {
      s = group_start.back();
      group_start.pop_back();
      y.block(0, s, e, e - s).setZero();
      y.block(s, s, e - s, e - s).setIdentity();
    }
    for (;;) {
      if (s == 0) break;  // nothing above: a group of its own
      const SylvesterSolution x = SolveSchurCoupling(f.t, s, e, -f.t.block(0, s, s, e - s));
      const double coupling = x.x.cwiseAbs().maxCoeff();
      if (std::isfinite(coupling) && coupling <= max_coupling) {
        y.block(0, s, s, e - s) = x.x;
        break;
      }
      // Merge with the group above and solve again for the merged columns.
      s = group_start.back();
      group_start.pop_back();
      y.block(0, s, e, e - s).setZero();
      y.block(s, s, e - s, e - s).setIdentity();
    }
    group_start.push_back(s);
  }
  form.start = group_start;
  form.start.push_back(n);
  form.condition = UnitUpperTriangularCondition(y);
  form.t = std::move(f.t);
  form.u = std::move(f.u);
  form.y = std::move(y);
  form.eigenvalues = std::move(f.eigenvalues);
  return form;
}

}  // namespace deb
