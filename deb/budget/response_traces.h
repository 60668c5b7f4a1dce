// Internal: not part of the public API.
// The transfers a report draws, evaluated once on the budget's grid by the
// engine (EngineOptions::response_traces): every contributor's path to every
// output (path_response.h) and the loop gain of every single-channel
// feedback loop. With them a result describes its own plots: the report
// draws from a BudgetResult alone, and so can a result read back from its
// store (deb/results/result_store.h) without any model.
#pragma once

#include <complex>
#include <optional>
#include <utility>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/path_response.h"
#include "deb/budget/result.h"

namespace deb {

struct LoopTrace {
  // The grid frequencies where the loop's data are defined, as its margins
  // used; empty where the loop is not drawn (not evaluated, or several
  // channels).
  std::vector<double> f_hz;
  std::vector<std::complex<double>> loop_gain;  // L(j 2 pi f), one per f_hz
};

struct ResponseTraces {
  // paths[c][o]: contributor c (budget order) to output o on the grid.
  std::vector<std::vector<PathResponse>> paths;
  // poles_hz[c]: the lowest and highest natural frequency of the modes of
  // contributor c's path within the grid; none for a path with measured
  // data or without modes.
  std::vector<std::optional<std::pair<double, double>>> poles_hz;
  // loops[i] belongs to BudgetResult::loops[i].
  std::vector<LoopTrace> loops;
};

// The traces of an evaluated budget (`result` from Evaluate of `budget`,
// with its path analyses): recorded[c] is contributor c's paths as its
// propagation recorded them (PathResponseRecorder), one per contributor;
// the loops' gains are evaluated here.
// @throws InputError where a loop's data are not defined on the grid.
ResponseTraces ComputeResponseTraces(const Budget& budget, const BudgetResult& result,
                                     std::vector<std::vector<PathResponse>> recorded);

}  // namespace deb
