// `deb merge PART... [--out DIR]`: joins the parts of a sharded uncertainty
// study (deb uncertainty --shard K/N, each a directory with part.json) into
// the directory the unsharded study writes, byte for byte: it checks that the
// parts belong to one study (same digest of budget and settings, same shard
// count) and cover every shard exactly once, reloads the budget (which must
// not have changed), and summarises every evaluation as one run would.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace deb::tools {

class MergeCommand {
 public:
  MergeCommand();
  ~MergeCommand();
  MergeCommand(const MergeCommand&) = delete;
  MergeCommand& operator=(const MergeCommand&) = delete;

  // Registers `merge` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for parts that do not make one study, WriteError for
  //   output that cannot be written.
  int Run() const;

  struct Options;

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
