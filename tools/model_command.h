// `deb model BUDGET.yaml`: describes the physical models of a budget (paths
// of type isolation_system): natural frequencies, mode shapes, static
// pre-stress, and the paths made from them.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class ModelCommand {
 public:
  ModelCommand();
  ~ModelCommand();
  ModelCommand(const ModelCommand&) = delete;
  ModelCommand& operator=(const ModelCommand&) = delete;

  // Registers `model` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for a budget that is not valid.
  int Run() const;

  struct Options;  // the command line's values (model_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
