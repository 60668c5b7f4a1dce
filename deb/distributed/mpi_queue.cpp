#include "deb/distributed/mpi_queue.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
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

std::vector<std::vector<double>> DistributeBlocks(std::size_t total, const BlockEvaluator& evaluate, double timeout_s) {
  const int size = MpiSession::Size(), rank = MpiSession::Rank();
  DEB_DEMAND(size >= 2);
  if (rank != 0) {
    // Ask, evaluate, send back (the result is the next request), until told to stop.
    MPI_Send(nullptr, 0, MPI_DOUBLE, 0, kRequest, MPI_COMM_WORLD);
    while (true) {
      MPI_Status status;
      std::uint64_t block[2] = {0, 0};
      MPI_Recv(block, 2, MPI_UINT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
      if (status.MPI_TAG == kStop) return {};
      try {
        const std::vector<std::vector<double>> values =
            evaluate(static_cast<std::size_t>(block[0]), static_cast<std::size_t>(block[1]));
        std::vector<double> message = {static_cast<double>(block[0]), static_cast<double>(block[1]),
                                       static_cast<double>(values.empty() ? 0 : values[0].size())};
        for (const std::vector<double>& v : values) {
          if (v.size() != static_cast<std::size_t>(message[2])) throw InputError("unequal counts of values in a block");
          message.insert(message.end(), v.begin(), v.end());
        }
        MPI_Send(message.data(), static_cast<int>(message.size()), MPI_DOUBLE, 0, kResult, MPI_COMM_WORLD);
      } catch (const InputError& e) {
        const std::string what = e.what();
        MPI_Send(what.data(), static_cast<int>(what.size()), MPI_CHAR, 0, kError, MPI_COMM_WORLD);
      }
    }
  }

  // Rank 0: blocks of about total / (8 workers), at most 256 indices, so
  // that a slow block leaves the others work to do.
  const std::size_t workers = static_cast<std::size_t>(size - 1);
  const std::size_t chunk = std::clamp<std::size_t>(total / (8 * workers), 1, 256);
  std::vector<std::vector<double>> values(total);
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
      MPI_Get_count(&status, MPI_DOUBLE, &n);
      std::vector<double> message(static_cast<std::size_t>(n));
      MPI_Recv(message.data(), n, MPI_DOUBLE, from, kResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto begin = static_cast<std::size_t>(message[0]), end = static_cast<std::size_t>(message[1]);
      const auto m = static_cast<std::size_t>(message[2]);
      DEB_DEMAND(end <= total && begin < end && message.size() == 3 + (end - begin) * m);
      for (std::size_t e = begin; e < end; ++e)
        values[e].assign(message.begin() + static_cast<long>(3 + (e - begin) * m),
                         message.begin() + static_cast<long>(3 + (e - begin + 1) * m));
    }
    give(from);
  }
  if (!error.empty()) throw InputError(error);
  return values;
}

}  // namespace deb
