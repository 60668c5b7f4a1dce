// `deb sweep BUDGET.yaml`: evaluates every variant of a budget's `sweep`
// section (deb/load/sweep_yaml.h), variants in parallel, and writes sweep.csv
// (one row per variant: parameter values, RMS per output and contributor)
// and plots/<output>_sweep.png (RMS against the first parameter) atomically
// into reports/<budget-name>_sweep/ (or --out).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class SweepCommand {
 public:
  SweepCommand();
  ~SweepCommand();
  SweepCommand(const SweepCommand&) = delete;
  SweepCommand& operator=(const SweepCommand&) = delete;

  // Registers `sweep` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for bad input, WriteError for output that cannot be written.
  int Run() const;

  struct Options;  // the command line's values (sweep_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
