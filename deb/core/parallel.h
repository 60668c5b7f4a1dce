// Splits an index range across threads. Frequency-by-frequency work (frequency
// responses, propagation) is independent per frequency, so it parallelises
// without locks; each worker gets one contiguous block.
#pragma once

#include <cstddef>
#include <functional>

namespace deb {

// Number of worker threads deb uses by default: DEB_THREADS if set (>= 1),
// otherwise std::thread::hardware_concurrency().
int DefaultThreadCount();

// Calls body(begin, end) on disjoint blocks covering [0, n). threads <= 0 means
// DefaultThreadCount(). Runs inline when n is small or threads == 1. An
// exception thrown by a block is rethrown in the caller after all blocks end.
void ParallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body,
                 int threads = 0);

}  // namespace deb
