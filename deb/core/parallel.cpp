#include "deb/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "deb/core/error.h"

namespace deb {
namespace {

// One call's blocks: the first exception, and how many blocks are still to
// finish.
struct Batch {
  const std::function<void(std::size_t, std::size_t)>* body = nullptr;
  std::size_t n = 0, blocks = 0;
  std::size_t remaining = 0;  // guarded by the pool's mutex
  std::exception_ptr failure;
};

// Worker threads kept for the life of the process: a ParallelFor call hands
// its blocks to them instead of starting threads of its own (starting and
// joining a thread per block cost a few milliseconds per run of a small
// budget, more than its whole evaluation). The caller runs block 0 itself
// and then any queued block, until its own are done.
class Pool {
 public:
  static Pool& Instance() {
    static Pool pool;
    return pool;
  }

  ~Pool() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
  }

  void Run(Batch& batch) {
    std::unique_lock<std::mutex> lock(mutex_);
    while (workers_.size() + 1 < batch.blocks) workers_.emplace_back([this] { Work(); });
    batch.remaining = batch.blocks;
    for (std::size_t b = 1; b < batch.blocks; ++b) queue_.push_back({&batch, b});
    lock.unlock();
    wake_.notify_all();
    RunBlock(batch, 0);
    lock.lock();
    Finish(batch);
    // Help with whatever is queued (this call's blocks, or a nested call's)
    // until this call's blocks are all done.
    while (batch.remaining > 0) {
      if (!queue_.empty()) RunQueued(lock);
      else done_.wait(lock);
    }
  }

  // True on a pool thread.
  static bool& OnWorker() {
    thread_local bool on_worker = false;
    return on_worker;
  }

 private:
  struct Task {
    Batch* batch;
    std::size_t block;
  };

  static void RunBlock(Batch& batch, std::size_t b) {
    const std::size_t begin = batch.n * b / batch.blocks, end = batch.n * (b + 1) / batch.blocks;
    try {
      (*batch.body)(begin, end);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(Instance().failure_mutex_);
      if (!batch.failure) batch.failure = std::current_exception();
    }
  }

  // Caller holds mutex_.
  void Finish(Batch& batch) {
    if (--batch.remaining == 0) done_.notify_all();
  }

  void Work() {
    OnWorker() = true;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stop_
      RunQueued(lock);
    }
  }

  // Runs the first queued block, unlocked while it runs. The caller holds
  // `lock` on mutex_ and the queue is not empty.
  void RunQueued(std::unique_lock<std::mutex>& lock) {
    const Task t = queue_.front();
    queue_.pop_front();
    lock.unlock();
    RunBlock(*t.batch, t.block);
    lock.lock();
    Finish(*t.batch);
  }

  std::mutex mutex_, failure_mutex_;
  std::condition_variable wake_, done_;
  std::deque<Task> queue_;
  std::vector<std::thread> workers_;
  bool stop_ = false;
};

}  // namespace

int DefaultThreadCount() {
  if (const char* env = std::getenv("DEB_THREADS")) {
    try {
      const int n = std::stoi(env);
      if (n >= 1) return n;
    } catch (const std::exception&) {
    }
  }
  // Asked once: glibc reads /sys/devices/system/cpu/online each time, and a
  // study asks for every budget it evaluates.
  static const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

void ParallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body,
                 int threads, std::size_t min_block) {
  if (n == 0) return;
  if (threads <= 0) threads = DefaultThreadCount();
  min_block = std::max<std::size_t>(min_block, 1);
  const std::size_t blocks =
      std::min<std::size_t>(static_cast<std::size_t>(threads), (n + min_block - 1) / min_block);
  // Inline for one block, and inside a pool thread: a nested call would
  // wait for blocks that only busy workers could run.
  if (blocks <= 1 || Pool::OnWorker()) {
    body(0, n);
    return;
  }
  Batch batch;
  batch.body = &body;
  batch.n = n;
  batch.blocks = blocks;
  Pool::Instance().Run(batch);
  if (batch.failure) std::rethrow_exception(batch.failure);
}

void ParallelForBlocks(std::size_t n, std::size_t block,
                       const std::function<void(std::size_t begin, std::size_t end)>& body, int threads) {
  DEB_DEMAND(block > 0);
  ParallelForEach(
      (n + block - 1) / block, [&](std::size_t b) { body(b * block, std::min(n, (b + 1) * block)); }, threads);
}

void ParallelForEach(std::size_t n, const std::function<void(std::size_t)>& job, int threads) {
  if (n == 0) return;
  if (threads <= 0) threads = DefaultThreadCount();
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(threads), n);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex failure_mutex;
  std::size_t failed_at = n;
  std::exception_ptr failure;
  // One block per worker, each a loop taking the next job: jobs of uneven
  // cost leave no worker idle while another has a queue.
  ParallelFor(
      workers,
      [&](std::size_t, std::size_t) {
        for (std::size_t i; !stop && (i = next++) < n;) {
          try {
            job(i);
          } catch (...) {
            const std::lock_guard<std::mutex> lock(failure_mutex);
            if (i < failed_at) {
              failed_at = i;
              failure = std::current_exception();
            }
            stop = true;
          }
        }
      },
      static_cast<int>(workers), 1);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace deb
