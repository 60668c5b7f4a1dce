#include "deb/core/parallel.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <string>
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

TEST_CASE("ParallelForEach runs every job exactly once, for any thread count") {
  for (int threads : {1, 2, 5, 0}) {
    std::vector<std::atomic<int>> runs(97);
    ParallelForEach(runs.size(), [&](std::size_t i) { ++runs[i]; }, threads);
    for (std::size_t i = 0; i < runs.size(); ++i) CHECK(runs[i] == 1);
  }
  bool called = false;
  ParallelForEach(0, [&](std::size_t) { called = true; }, 4);
  CHECK_FALSE(called);
}

TEST_CASE("ParallelForEach lets a free thread take the next job while another runs a long one") {
  // Job 0 blocks until every other job has run: with 2 threads the second
  // takes jobs 1..9 one after the other (fixed blocks would give it half).
  std::atomic<int> others{0};
  ParallelForEach(
      10,
      [&](std::size_t i) {
        if (i > 0) {
          ++others;
          return;
        }
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (others < 9 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
      },
      2);
  CHECK(others == 9);
}

TEST_CASE("ParallelForEach rethrows the lowest failing job's exception after the started jobs end") {
  // Serially, job 3 throws first and no later job starts.
  std::vector<int> ran;
  CHECK_THROWS_WITH_AS(ParallelForEach(
                           8,
                           [&](std::size_t i) {
                             ran.push_back(static_cast<int>(i));
                             if (i == 3 || i == 5) throw std::runtime_error("job " + std::to_string(i));
                           },
                           1),
                       "job 3", std::runtime_error);
  CHECK(ran == std::vector<int>{0, 1, 2, 3});
  // On 4 threads, job 5 may fail before job 3 does: job 3's is still the
  // one rethrown, and jobs 0-3 (started before job 5) all ran to the end.
  for (int repeat = 0; repeat < 20; ++repeat) {
    std::vector<std::atomic<int>> ended(8);
    CHECK_THROWS_WITH_AS(ParallelForEach(
                             8,
                             [&](std::size_t i) {
                               if (i == 3) std::this_thread::sleep_for(std::chrono::milliseconds(2));
                               ++ended[i];
                               if (i == 3 || i == 5) throw std::runtime_error("job " + std::to_string(i));
                             },
                             4),
                         "job 3", std::runtime_error);
    for (std::size_t i = 0; i <= 3; ++i) CHECK(ended[i] == 1);
  }
}

TEST_CASE("a ParallelForEach inside a job of another runs each inner job once") {
  std::vector<std::vector<std::atomic<int>>> hits(6);
  for (auto& row : hits) row = std::vector<std::atomic<int>>(50);
  ParallelForEach(
      hits.size(),
      [&](std::size_t b) {
        ParallelForEach(hits[b].size(), [&](std::size_t i) { ++hits[b][i]; }, 3);
        ParallelFor(
            hits[b].size(),
            [&](std::size_t i0, std::size_t i1) {
              for (std::size_t i = i0; i < i1; ++i) ++hits[b][i];
            },
            3, 1);
      },
      3);
  for (const auto& row : hits)
    for (const auto& h : row) CHECK(h == 2);
}

}  // namespace deb
