// `deb run BUDGET.yaml`: evaluates a budget (or, with --group, one sub-tree
// of it), prints its console summary, and writes its report directory
// atomically into reports/<budget-name> (or --out), with the report options
// of report_flags.h. With --strict an output that fails its requirement
// makes the exit code kExitRequirement (the report is written all the same).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class RunCommand {
 public:
  // The exit code of `deb run --strict` when an output fails.
  static constexpr int kExitRequirement = 5;

  RunCommand();
  ~RunCommand();
  RunCommand(const RunCommand&) = delete;
  RunCommand& operator=(const RunCommand&) = delete;

  // Registers `run` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for bad input, WriteError for a report that cannot be
  //         written.
  int Run() const;

  struct Options;  // the command line's values (run_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
