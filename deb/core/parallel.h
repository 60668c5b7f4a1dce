// Internal: not part of the public API.
// Work on several threads, on workers started once and kept for the life of
// the process. Two calls:
// - ParallelFor: an index range of small, even work (one frequency of a
//   response or a propagation), cut into one contiguous block per thread.
// - ParallelForEach: a list of coarse jobs of uneven cost (a sweep variant,
//   a gnuplot process, a Welch segment's FFT); each thread takes the next job
//   not yet started.
// A call wakes the workers: microseconds, more on a busy machine, before a
// second thread starts; after that a ParallelForEach job costs an atomic
// counter step (0.012 us an empty job, measured). So "small" work (well under a
// microsecond an index) goes to ParallelFor, which groups min_block indices
// into a block; a ParallelForEach job should be 0.1 ms or more (an FFT of
// 2^14 samples), else several go into one job.
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

// Calls job(i) once for every i in [0, n) on up to `threads` threads (<= 0:
// DefaultThreadCount()), the caller's among them; each takes the next job
// not yet started, in index order. A call from inside a job of another call
// on a worker thread runs inline. Once a job has thrown, jobs not yet started
// are skipped, and after the started ones end the exception of the lowest
// failing index is rethrown: the one a serial loop would have thrown.
void ParallelForEach(std::size_t n, const std::function<void(std::size_t)>& job, int threads = 0);

// body(begin, end) for the blocks [0, block), [block, 2 block), ... covering
// [0, n) (the last one shorter), as ParallelForEach jobs. The blocks do not
// depend on the thread count, so neither does a result summed block by
// block (a matrix product over column blocks, partial sums added in order).
void ParallelForBlocks(std::size_t n, std::size_t block,
                       const std::function<void(std::size_t begin, std::size_t end)>& body, int threads = 0);

}  // namespace deb
