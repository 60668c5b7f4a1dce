#include "deb/systems/real_block_diagonal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
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

// Columns [s, e) of Y back to the identity's from row `lo` down: a group not
// (or no longer) decoupled from the rows above it.
void ResetColumns(Eigen::MatrixXd& y, int lo, int s, int e) {
  y.block(lo, s, e - lo, e - s).setZero();
  y.block(s, s, e - s, e - s).setIdentity();
}

// Decouples blocks [first, last) of T (starts in `blocks`) group by group,
// each from the rows [lo, s) above it: the column block Y(lo:s, s:e) with
//   T(lo:s, lo:s) X - X T(s:e, s:e) = -T(lo:s, s:e).
// A block in the cluster of the one before it joins its group; a group whose
// coupling would exceed max_coupling is merged with the group above and
// solved again. `group_start` holds the groups' starts (those at or above
// lo may be merged into).
void DecoupleBlocks(const Eigen::MatrixXd& t, Eigen::MatrixXd& y, const std::vector<int>& blocks,
                    const std::vector<int>& label, std::size_t first, std::size_t last, int lo, double max_coupling,
                    std::vector<int>& group_start) {
  for (std::size_t b = first; b < last; ++b) {
    int s = blocks[b];
    const int e = blocks[b + 1];
    const auto merge_up = [&] {
      s = group_start.back();
      group_start.pop_back();
      ResetColumns(y, lo, s, e);
    };
    // A cluster is never split: its poles are too close for the coupling
    // to be bounded by anything but rounding.
    if (s > lo && b > 0 && label[b] == label[b - 1]) merge_up();
    while (s > lo) {
      const SylvesterSolution x = SolveSchurCoupling(t, lo, s, e, -t.block(lo, s, s - lo, e - s));
      const double coupling = x.x.cwiseAbs().maxCoeff();
      if (std::isfinite(coupling) && coupling <= max_coupling) {
        y.block(lo, s, s - lo, e - s) = x.x;
        break;
      }
      merge_up();  // and solve again for the merged columns
    }
    group_start.push_back(s);
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

  // Decoupling, in batches of about kBatch states (whole clusters): each
  // batch's groups are first decoupled from each other (DecoupleBlocks on
  // the batch alone), then the batch from everything above it by one
  // level-3 Sylvester solve, Y(0:s, batch) = X Y(batch, batch). Where a
  // group of the batch would then be coupled above max_coupling, the batch
  // is done group by group against all above it, merging as needed.
  constexpr int kBatch = 128;
  const std::vector<int> blocks = SchurBlockStarts(f.t);
  const std::vector<int> label = ClusterLabels(f.eigenvalues, blocks, cluster_gap, floor);
  Eigen::MatrixXd y = Eigen::MatrixXd::Identity(n, n);
  std::vector<int> group_start;  // starts of the groups found so far
  const std::size_t count = blocks.size() - 1;
  for (std::size_t b = 0; b < count;) {
    std::size_t end = b + 1;
    while (end < count && (blocks[end] - blocks[b] < kBatch || label[end] == label[end - 1])) ++end;
    const int s = blocks[b], e = blocks[end];
    bool done = false;
    if (s > 0) {
      std::vector<int> local;
      DecoupleBlocks(f.t, y, blocks, label, b, end, s, max_coupling, local);
      const SylvesterSolution x = SolveSchurCoupling(f.t, 0, s, e, -f.t.block(0, s, s, e - s), true);
      const Eigen::MatrixXd above = x.x * y.block(s, s, e - s, e - s).triangularView<Eigen::UnitUpper>();
      done = above.allFinite();
      local.push_back(e);
      for (std::size_t g = 0; done && g + 1 < local.size(); ++g)
        done = above.middleCols(local[g] - s, local[g + 1] - local[g]).cwiseAbs().maxCoeff() <= max_coupling;
      local.pop_back();
      if (done) {
        y.block(0, s, s, e - s) = above;
        group_start.insert(group_start.end(), local.begin(), local.end());
      } else {
        ResetColumns(y, 0, s, e);
      }
    }
    if (!done) DecoupleBlocks(f.t, y, blocks, label, b, end, 0, max_coupling, group_start);
    b = end;
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

std::shared_ptr<const RealBlockDiagonalForm> SharedRealBlockDiagonal(const Eigen::MatrixXd& a) {
  if (a.rows() < kSharedFormStates) return std::make_shared<const RealBlockDiagonalForm>(RealBlockDiagonal(a));
  struct Entry {
    Eigen::MatrixXd a;
    std::shared_ptr<const RealBlockDiagonalForm> form;
  };
  static std::mutex mutex;
  static std::vector<Entry> kept;  // most recent first
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const Entry& e : kept)
      if (e.a.rows() == a.rows() && e.a.cols() == a.cols() && e.a == a) return e.form;
  }
  auto form = std::make_shared<const RealBlockDiagonalForm>(RealBlockDiagonal(a));
  const std::lock_guard<std::mutex> lock(mutex);
  kept.insert(kept.begin(), Entry{a, form});
  if (kept.size() > 2) kept.pop_back();
  return form;
}

}  // namespace deb
