// `deb sweep BUDGET.yaml`: evaluates every variant of a budget's `sweep`
// section (deb/load/sweep_yaml.h), variants in parallel, and writes sweep.csv
// (one row per variant: parameter values, RMS per output and contributor)
// and plots/<output>_sweep.png (RMS against the first parameter) atomically
// into reports/<budget-name>_sweep/ (or --out).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/budget/sweep.h"

namespace deb::tools {

// The digest that ties a sharded sweep's parts together: SHA-256 of the
// budget document (extends resolved, --set applied) and deb's version.
std::string SweepDigest(const std::string& budget_text);

// Writes the sweep's directory atomically (out_dir "": reports/<name>_sweep)
// and, unless quiet, prints the best variants and where the report is.
// `budget_file`: the budget as given, named in the documents with its digest.
void WriteSweepStudy(const std::string& name, const SweepSpec& spec, const std::vector<BudgetResult>& results,
                     const std::string& budget_file, const std::string& out_dir, bool force, bool plots, bool quiet,
                     int threads);

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
