// `deb compare A B [C ...]`: compares design options. Each argument is a
// budget (evaluated here) or a result directory of `deb run` (its
// summary.json is read). Every further argument is compared with the first;
// each comparison is written, atomically, as compare.json, compare.md,
// compare.html and compare.csv (and overlay plots when both are budgets, or
// result directories with their result store)
// into reports/compare_<A>_vs_<B>/ (or --out for two arguments). With
// --tolerance REL it is a regression gate: every figure that moved by more
// than REL relative is printed, and the command fails (FiguresMoved).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <stdexcept>

namespace deb::tools {

// `deb compare --tolerance REL` found figures that moved by more than REL
// (the reports are written); deb_main maps it to exit code 6.
struct FiguresMoved : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class CompareCommand {
 public:
  CompareCommand();
  ~CompareCommand();
  CompareCommand(const CompareCommand&) = delete;
  CompareCommand& operator=(const CompareCommand&) = delete;

  // Registers `compare` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for bad input, WriteError for output that cannot be
  // written, FiguresMoved when --tolerance is exceeded.
  int Run() const;

  struct Options;  // the command line's values (compare_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
