#include "deb/distributed/mpi_queue.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "deb/core/error.h"

namespace deb {

namespace {

bool g_active = false;

enum Tag : int { kRequest = 1, kWork = 2, kStop = 3, kResult = 4, kError = 5 };

using Clock = std::chrono::steady_clock;

}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) {
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK")) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  active_ = g_active = true;
}

MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
  g_active = false;
}

int MpiSession::Rank() {
  if (!g_active) return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int MpiSession::Size() {
  if (!g_active) return 1;
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

std::string DoublesToBytes(const std::vector<double>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

std::vector<double> DoublesFromBytes(const std::string& bytes) {
  DEB_DEMAND(bytes.size() % sizeof(double) == 0);
  std::vector<double> v(bytes.size() / sizeof(double));
  std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

std::vector<std::string> DistributeBlocks(std::size_t total, const BlockEvaluator& evaluate, double timeout_s,
                                          std::size_t max_block) {
  const int size = MpiSession::Size(), rank = MpiSession::Rank();
  DEB_DEMAND(size >= 2 && max_block >= 1);
  if (rank != 0) {
    // Ask, evaluate, send back (the result is the next request), until told to stop.
    MPI_Send(nullptr, 0, MPI_DOUBLE, 0, kRequest, MPI_COMM_WORLD);
    while (true) {
      MPI_Status status;
      std::uint64_t block[2] = {0, 0};
      MPI_Recv(block, 2, MPI_UINT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
      if (status.MPI_TAG == kStop) return {};
      try {
        // [begin, end, the results' sizes], then the results' bytes.
        const std::vector<std::string> results =
            evaluate(static_cast<std::size_t>(block[0]), static_cast<std::size_t>(block[1]));
        DEB_DEMAND(results.size() == block[1] - block[0]);
        std::vector<std::uint64_t> head = {block[0], block[1]};
        for (const std::string& r : results) head.push_back(r.size());
        std::string message(reinterpret_cast<const char*>(head.data()), head.size() * sizeof(std::uint64_t));
        for (const std::string& r : results) message += r;
        MPI_Send(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, kResult, MPI_COMM_WORLD);
      } catch (const InputError& e) {
        const std::string what = e.what();
        MPI_Send(what.data(), static_cast<int>(what.size()), MPI_CHAR, 0, kError, MPI_COMM_WORLD);
      }
    }
  }

  // Rank 0: blocks of about total / (8 workers), at most max_block indices,
  // so that a slow block leaves the others work to do.
  const std::size_t workers = static_cast<std::size_t>(size - 1);
  const std::size_t chunk = std::clamp<std::size_t>(total / (8 * workers), 1, max_block);
  std::vector<std::string> values(total);
  std::size_t next = 0, stopped = 0;
  std::string error;
  std::vector<Clock::time_point> since(static_cast<std::size_t>(size));
  std::vector<std::pair<std::size_t, std::size_t>> holds(static_cast<std::size_t>(size), {0, 0});
  const auto give = [&](int to) {
    if (next < total && error.empty()) {
      const std::uint64_t block[2] = {next, std::min(total, next + chunk)};
      holds[static_cast<std::size_t>(to)] = {next, static_cast<std::size_t>(block[1])};
      since[static_cast<std::size_t>(to)] = Clock::now();
      next = static_cast<std::size_t>(block[1]);
      MPI_Send(block, 2, MPI_UINT64_T, to, kWork, MPI_COMM_WORLD);
    } else {
      holds[static_cast<std::size_t>(to)] = {0, 0};
      MPI_Send(nullptr, 0, MPI_UINT64_T, to, kStop, MPI_COMM_WORLD);
      ++stopped;
    }
  };
  while (stopped < workers) {
    int ready = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &ready, &status);
    if (!ready) {
      if (timeout_s > 0.0)
        for (int r = 1; r < size; ++r) {
          const auto [b, e] = holds[static_cast<std::size_t>(r)];
          if (e > b && std::chrono::duration<double>(Clock::now() - since[static_cast<std::size_t>(r)]).count() > timeout_s) {
            std::fprintf(stderr,
                         "deb: error: rank %d has not returned evaluations %zu to %zu within --timeout %g s; "
                         "stopping every rank, nothing written\n",
                         r, b + 1, e, timeout_s);
            std::fflush(stderr);
            MPI_Abort(MPI_COMM_WORLD, 3);
          }
        }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    const int from = status.MPI_SOURCE;
    if (status.MPI_TAG == kRequest) {
      MPI_Recv(nullptr, 0, MPI_DOUBLE, from, kRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else if (status.MPI_TAG == kError) {
      int n = 0;
      MPI_Get_count(&status, MPI_CHAR, &n);
      std::string text(static_cast<std::size_t>(n), '\0');
      MPI_Recv(text.data(), n, MPI_CHAR, from, kError, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (error.empty()) error = text;
    } else {
      int n = 0;
      MPI_Get_count(&status, MPI_BYTE, &n);
      std::string message(static_cast<std::size_t>(n), '\0');
      MPI_Recv(message.data(), n, MPI_BYTE, from, kResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto word = [&](std::size_t i) {
        std::uint64_t w = 0;
        DEB_DEMAND((i + 1) * sizeof w <= message.size());
        std::memcpy(&w, message.data() + i * sizeof w, sizeof w);
        return static_cast<std::size_t>(w);
      };
      const std::size_t begin = word(0), end = word(1);
      DEB_DEMAND(begin < end && end <= total);
      std::size_t at = (2 + end - begin) * sizeof(std::uint64_t);
      for (std::size_t e = begin; e < end; ++e) {
        const std::size_t length = word(2 + e - begin);
        DEB_DEMAND(at + length <= message.size());
        values[e] = message.substr(at, length);
        at += length;
      }
    }
    give(from);
  }
  if (!error.empty()) throw InputError(error);
  return values;
}

}  // namespace deb
