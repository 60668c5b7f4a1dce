// Internal: not part of the public API.
// MPI for deb (the only code that uses it; built with DEB_MPI): the
// process's MPI session, and a work queue that spreads a study's
// evaluations over the ranks of mpirun. Rank 0 hands out blocks of
// evaluation indices to the other ranks one at a time as they finish (a
// chunked queue: budgets differ in cost), gathers their values in index
// order and, alone, returns them; the others evaluate and return nothing.
// Each rank evaluates its block with its own threads. A rank's error ends
// the run on rank 0 with that error (the others are told to stop); a rank
// that does not answer within the timeout ends it with MPI_Abort.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace deb {

// MPI_Init on construction when the process was started by mpirun (OpenMPI's
// OMPI_COMM_WORLD_SIZE or PMIx's PMIX_RANK set), MPI_Finalize on
// destruction; otherwise nothing, and the process is a world of one.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  // Of the running session: 0 and 1 without one.
  static int Rank();
  static int Size();

 private:
  bool active_ = false;
};

// Evaluates indices [begin, end): one byte string per index (its result,
// encoded; the ranks are assumed to share one byte order and type sizes).
using BlockEvaluator = std::function<std::vector<std::string>(std::size_t begin, std::size_t end)>;

// Collective over MPI_COMM_WORLD (Size() >= 2). On rank 0: the results of
// every index in [0, total), evaluated by the other ranks. Elsewhere: empty.
// @throws InputError on rank 0 with the first error a rank reported
//   (evaluate's message); the other ranks then return empty. A rank that
//   holds a block longer than timeout_s seconds (> 0; 0: no limit) ends the
//   run: rank 0 prints which and calls MPI_Abort.
// Blocks hold about total / (8 workers) indices, at most max_block (>= 1):
// 1 for jobs as long and uneven as an optimiser's starts.
std::vector<std::string> DistributeBlocks(std::size_t total, const BlockEvaluator& evaluate, double timeout_s,
                                          std::size_t max_block = 256);

// A vector of doubles as bytes and back (a study's metric values).
std::string DoublesToBytes(const std::vector<double>& v);
std::vector<double> DoublesFromBytes(const std::string& bytes);

}  // namespace deb
