// `deb sensitivity BUDGET.yaml -p KEY.PATH [-p ...]`: the derivative of every
// output's variance (total and per contributor) with respect to each named
// parameter, by central differences in ln p (deb/budget/sensitivity.h),
// ranked per output; sensitivity.csv and sensitivity.md are written
// atomically into reports/<budget-name>_sensitivity/ (or --out).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class SensitivityCommand {
 public:
  SensitivityCommand();
  ~SensitivityCommand();
  SensitivityCommand(const SensitivityCommand&) = delete;
  SensitivityCommand& operator=(const SensitivityCommand&) = delete;

  // Registers `sensitivity` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for bad input, WriteError for output that cannot be written.
  int Run() const;

  struct Options;  // the command line's values (sensitivity_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
