#include "deb/systems/parallel_product.h"

#include <algorithm>
#include <cstddef>

#include "deb/core/error.h"
#include "deb/core/parallel.h"

namespace deb {

void ForColumnBlocks(Eigen::Index cols, const std::function<void(Eigen::Index first, Eigen::Index count)>& fn) {
  DEB_DEMAND(cols >= 0);
  const std::size_t blocks = static_cast<std::size_t>((cols + kProductColumns - 1) / kProductColumns);
  ParallelForEach(blocks, [&](std::size_t b) {
    const Eigen::Index first = static_cast<Eigen::Index>(b) * kProductColumns;
    fn(first, std::min(kProductColumns, cols - first));
  });
}

Eigen::MatrixXd ParallelProduct(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  DEB_DEMAND(a.cols() == b.rows());
  Eigen::MatrixXd out(a.rows(), b.cols());
  ForColumnBlocks(b.cols(), [&](Eigen::Index first, Eigen::Index count) {
    out.middleCols(first, count).noalias() = a * b.middleCols(first, count);
  });
  return out;
}

}  // namespace deb
