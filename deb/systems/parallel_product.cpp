#include "deb/systems/parallel_product.h"

#include <cstddef>

#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/systems/lapack.h"

namespace deb {

void ForColumnBlocks(Eigen::Index cols, const std::function<void(Eigen::Index first, Eigen::Index count)>& fn) {
  DEB_DEMAND(cols >= 0);
  ParallelForBlocks(static_cast<std::size_t>(cols), static_cast<std::size_t>(kProductColumns),
                    [&](std::size_t begin, std::size_t end) {
                      fn(static_cast<Eigen::Index>(begin), static_cast<Eigen::Index>(end - begin));
                    });
}

Eigen::MatrixXd ParallelProduct(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  DEB_DEMAND(a.cols() == b.rows());
  Eigen::MatrixXd out(a.rows(), b.cols());
  // The BLAS's AVX-512 product in one call: faster than blocks of columns
  // on worker threads even where the BLAS runs them at once, since each
  // block packs all of a again (the dense 1000-mode run: 5.5-6.3 s wall
  // against 6.1-6.8 s on 2 cores, 2026-12-07).
  if (BlasProductIsFaster()) {
    BlasProduct(a, b, out);
    return out;
  }
  ForColumnBlocks(b.cols(), [&](Eigen::Index first, Eigen::Index count) {
    out.middleCols(first, count).noalias() = a * b.middleCols(first, count);
  });
  return out;
}

}  // namespace deb
