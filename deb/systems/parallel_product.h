// Internal: not part of the public API.
// Dense matrix products of the one-off reductions (n of 1000 and more), on
// all threads: the right-hand matrix's columns in fixed blocks, so that each
// column is summed in the same order whatever the thread count.
#pragma once

#include <Eigen/Dense>
#include <functional>

namespace deb {

// fn(first, count) for consecutive blocks of kProductColumns columns
// covering [0, cols), the last one shorter, on worker threads
// (ParallelForBlocks).
inline constexpr Eigen::Index kProductColumns = 128;
void ForColumnBlocks(Eigen::Index cols, const std::function<void(Eigen::Index first, Eigen::Index count)>& fn);

// a * b: by the BLAS's dgemm in one call where that is faster than Eigen's
// product (BlasProductIsFaster, lapack.h), else by Eigen's, each block of
// columns on a worker thread.
Eigen::MatrixXd ParallelProduct(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace deb
