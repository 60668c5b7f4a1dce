// `deb check BUDGET.yaml`: validates a budget as `deb run` would before
// computing (every sweep variant too, as `deb sweep` would) and describes it
// (deb/budget/budget_description.h), the warnings on stderr after it.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class CheckCommand {
 public:
  CheckCommand();
  ~CheckCommand();
  CheckCommand(const CheckCommand&) = delete;
  CheckCommand& operator=(const CheckCommand&) = delete;

  // Registers `check` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for a budget that is not valid.
  int Run() const;

  struct Options;  // the command line's values (check_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
