// `deb report RESULT_DIR`: redraws the report of a result directory from its
// result store (result.h5, deb/results/result_store.h) without evaluating
// anything: no budget file, data file or model is read. The report is
// written atomically into RESULT_DIR itself (or --out), with the report
// options of `deb run` (--format, --digits, --asd, --export, ...): the same
// result drawn again, e.g. with another number format, as ASDs, or by a
// newer deb.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

// The command's options are members, bound by Register(); the object must
// outlive the parse of the app it is registered on.
class ReportCommand {
 public:
  ReportCommand();
  ~ReportCommand();
  ReportCommand(const ReportCommand&) = delete;
  ReportCommand& operator=(const ReportCommand&) = delete;

  // Registers `report` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for a missing or malformed store, WriteError for a
  //         report that cannot be written.
  int Run() const;

  struct Options;  // the command line's values (report_command.cpp)

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
