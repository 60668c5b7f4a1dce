#include "deb/core/parallel.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unistd.h>
#include <utility>
#include <vector>

namespace deb {
namespace {

// The blocks ParallelFor hands out, sorted.
std::vector<std::pair<std::size_t, std::size_t>> Blocks(std::size_t n, int threads, std::size_t min_block) {
  std::mutex m;
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
  ParallelFor(
      n,
      [&](std::size_t b, std::size_t e) {
        const std::lock_guard<std::mutex> lock(m);
        blocks.emplace_back(b, e);
      },
      threads, min_block);
  std::sort(blocks.begin(), blocks.end());
  return blocks;
}

}  // namespace

TEST_CASE("ParallelFor covers the range with disjoint contiguous blocks of at least min_block") {
  using Blocks_ = std::vector<std::pair<std::size_t, std::size_t>>;
  CHECK(Blocks(1000, 4, 256) == Blocks_{{0, 250}, {250, 500}, {500, 750}, {750, 1000}});
  CHECK(Blocks(256, 4, 256) == Blocks_{{0, 256}});  // one block: inline
  CHECK(Blocks(300, 4, 256) == Blocks_{{0, 150}, {150, 300}});
  CHECK(Blocks(3, 4, 1) == Blocks_{{0, 1}, {1, 2}, {2, 3}});
  CHECK(Blocks(5, 2, 1) == Blocks_{{0, 2}, {2, 5}});
  CHECK(Blocks(5, 2, 0) == Blocks_{{0, 2}, {2, 5}});  // 0 is taken as 1
  CHECK(Blocks(7, 1, 1) == Blocks_{{0, 7}});
  CHECK(Blocks(0, 4, 1).empty());
}

TEST_CASE("ParallelFor rethrows a block's exception after all blocks end") {
  std::mutex m;
  int ended = 0;
  CHECK_THROWS_WITH_AS(ParallelFor(
                           4,
                           [&](std::size_t b, std::size_t) {
                             {
                               const std::lock_guard<std::mutex> lock(m);
                               ++ended;
                             }
                             if (b == 2) throw std::runtime_error("block 2");
                           },
                           4, 1),
                       "block 2", std::runtime_error);
  CHECK(ended == 4);
}

TEST_CASE("ParallelFor keeps its worker threads from one call to the next") {
  // Kernel thread ids: a new thread gets a new one (std::thread::id, the
  // pthread_t, is reused as soon as a joined thread's memory is).
  const pid_t caller = ::gettid();
  const auto other_threads = [caller] {
    std::mutex m;
    std::vector<pid_t> ids;
    ParallelFor(
        4,
        [&](std::size_t, std::size_t) {
          const std::lock_guard<std::mutex> lock(m);
          if (::gettid() != caller) ids.push_back(::gettid());
        },
        4, 1);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
  };
  // Over many calls of 4 blocks, at most 3 threads other than the caller
  // ever run one (a thread per block per call would give up to 60).
  std::vector<pid_t> all;
  for (int call = 0; call < 20; ++call)
    for (const pid_t id : other_threads())
      if (std::find(all.begin(), all.end(), id) == all.end()) all.push_back(id);
  CHECK(all.size() <= 3);
}

TEST_CASE("a ParallelFor inside a block of another covers its range once") {
  std::vector<std::vector<int>> hits(8, std::vector<int>(1000, 0));
  ParallelFor(
      8,
      [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b)
          ParallelFor(
              1000, [&](std::size_t i0, std::size_t i1) {
                for (std::size_t i = i0; i < i1; ++i) ++hits[b][i];
              },
              4, 100);
      },
      4, 1);
  for (const auto& row : hits) CHECK(std::count(row.begin(), row.end(), 1) == 1000);
}

}  // namespace deb
