// `deb optimise BUDGET.yaml --vary A,B`: chooses the named parameters within
// their bounds (`min`, `max` in the budget) to minimise an output's RMS (or
// the largest RMS / requirement) while meeting every requirement
// (deb/optimise/optimiser.h), prints the optimum and which requirements are
// active, and writes summary.json, history.csv, optimum.yaml (the optimum as
// a budget that extends the original), the optimum's full report (report/)
// and plots/ (the history; for two variables the objective's map over a
// 21 x 21 grid of the bounds) atomically into reports/<budget-name>_optimum/ (or --out).
// Exit code 5 when no design within the bounds meets every requirement (the
// least violating one is written).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

class OptimiseCommand {
 public:
  OptimiseCommand();
  ~OptimiseCommand();
  OptimiseCommand(const OptimiseCommand&) = delete;
  OptimiseCommand& operator=(const OptimiseCommand&) = delete;

  CLI::App* Register(CLI::App& app);
  // @throws InputError for bad input, WriteError for output that cannot be written.
  int Run() const;

  struct Options;

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
