#include "deb/systems/block_triangular.h"

#include <algorithm>
#include <utility>

#include "deb/systems/lapack.h"
#include "deb/systems/state_space.h"

namespace deb {

BlockTriangularForm BlockTriangular(const Eigen::MatrixXd& a) {
  // Tarjan's strongly connected components, emitted driven-before-driver,
  // which makes A(perm, perm) block upper triangular.
  const int n = static_cast<int>(a.rows());
  BlockTriangularForm form;
  std::vector<int> index(n, -1), low(n, 0), stack;
  std::vector<bool> on_stack(n, false);
  int counter = 0;
  form.start.assign(1, 0);
  // Iterative depth-first search over edges j -> i for A(i, j) != 0.
  std::vector<std::pair<int, int>> frames;  // (node, next candidate i)
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    frames.push_back({root, 0});
    index[root] = low[root] = counter++;
    stack.push_back(root);
    on_stack[root] = true;
    while (!frames.empty()) {
      auto& [v, next] = frames.back();
      bool descended = false;
      while (next < n) {
        const int w = next++;
        if (w == v || a(w, v) == 0.0) continue;
        if (index[w] < 0) {
          index[w] = low[w] = counter++;
          stack.push_back(w);
          on_stack[w] = true;
          frames.push_back({w, 0});
          descended = true;
          break;
        }
        if (on_stack[w]) low[v] = std::min(low[v], index[w]);
      }
      if (descended) continue;
      const int done = v;
      if (low[done] == index[done]) {
        int w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = false;
          form.perm.push_back(w);
        } while (w != done);
        form.start.push_back(static_cast<int>(form.perm.size()));
      }
      frames.pop_back();
      if (!frames.empty()) low[frames.back().first] = std::min(low[frames.back().first], low[done]);
    }
  }
  return form;
}

constexpr int kLapackEigenvalueStates = 200;

Eigen::VectorXcd BlockEigenvalues(const Eigen::MatrixXd& a) {
  const BlockTriangularForm form = BlockTriangular(a);
  Eigen::VectorXcd lambda(a.rows());
  for (int b = 0; b < form.blocks(); ++b) {
    const int at = form.start[b], size = form.start[b + 1] - at;
    const std::vector<int> states(form.perm.begin() + at, form.perm.begin() + at + size);
    const Eigen::MatrixXd block = a(states, states);
    if (size == 1) {
      lambda(at) = block(0, 0) + 0.0;  // -0 is 0, as from the eigenvalue solver
      continue;
    }
    // Large blocks through LAPACK (dgees on 2000 states: 1.3 s with
    // OpenBLAS against 7 s for Eigen's EigenSolver), small ones through Eigen.
    if (size > kLapackEigenvalueStates) {
      lambda.segment(at, size) = RealEigenvalues(block);
      continue;
    }
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(block, false);
    if (eig.info() != Eigen::Success) ThrowNotConverged(a);
    lambda.segment(at, size) = eig.eigenvalues();
  }
  return lambda;
}

bool HasCoupledBlocks(const Eigen::MatrixXd& a) { return HasCoupledBlocks(a, BlockTriangular(a)); }

bool HasCoupledBlocks(const Eigen::MatrixXd& a, const BlockTriangularForm& form) {
  if (form.blocks() <= 1) return false;
  std::vector<int> block_of(form.perm.size());
  for (int b = 0; b < form.blocks(); ++b)
    for (int k = form.start[b]; k < form.start[b + 1]; ++k) block_of[form.perm[k]] = b;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (a(i, j) != 0.0 && block_of[i] != block_of[j]) return true;
  return false;
}

}  // namespace deb
