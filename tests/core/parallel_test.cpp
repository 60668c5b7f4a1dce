#include "deb/core/parallel.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
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

}  // namespace deb
