// Internal: not part of the public API.
// Splits an index range across threads. Frequency-by-frequency work (frequency
// responses, propagation) is independent per frequency, so it parallelises
// without locks; each worker gets one contiguous block. The workers are
// started once and kept for the life of the process.
#pragma once

#include <cstddef>
#include <functional>

namespace deb {

// Number of worker threads deb uses by default: DEB_THREADS if set (>= 1),
// otherwise std::thread::hardware_concurrency().
int DefaultThreadCount();

// Calls body(begin, end) on disjoint blocks covering [0, n). threads <= 0 means
// DefaultThreadCount(). A block holds at least min_block indices (runs
// inline when n <= min_block or threads == 1): the default suits cheap work
// per index, 1 suits indices that are themselves blocks of work. A call from
// inside a block of another call runs inline on that block's thread. An
// exception thrown by a block is rethrown in the caller after all blocks end.
void ParallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body,
                 int threads = 0, std::size_t min_block = 256);

}  // namespace deb
