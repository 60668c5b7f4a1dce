#include "deb/core/parallel.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace deb {

int DefaultThreadCount() {
  if (const char* env = std::getenv("DEB_THREADS")) {
    try {
      const int n = std::stoi(env);
      if (n >= 1) return n;
    } catch (const std::exception&) {
    }
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

void ParallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body,
                 int threads, std::size_t min_block) {
  if (n == 0) return;
  if (threads <= 0) threads = DefaultThreadCount();
  min_block = std::max<std::size_t>(min_block, 1);
  const std::size_t blocks =
      std::min<std::size_t>(static_cast<std::size_t>(threads), (n + min_block - 1) / min_block);
  if (blocks <= 1) {
    body(0, n);
    return;
  }
  std::exception_ptr failure;
  std::mutex failure_mutex;
  std::vector<std::thread> workers;
  workers.reserve(blocks - 1);
  const auto run = [&](std::size_t b) {
    const std::size_t begin = n * b / blocks;
    const std::size_t end = n * (b + 1) / blocks;
    try {
      body(begin, end);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  for (std::size_t b = 1; b < blocks; ++b) workers.emplace_back(run, b);
  run(0);
  for (auto& w : workers) w.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace deb
