// `deb uncertainty BUDGET.yaml`: samples the budget's uncertain parameters
// (their `distribution:` and the budget's `correlations:`,
// deb/load/uncertainty_yaml.h), evaluates every sample's budget in parallel
// (deb/uncertainty/uncertainty_study.h), prints per output the RMS's
// distribution, P(meet) of each requirement with its 95 % Wilson interval,
// the drivers and the worst corner, and writes summary.json, samples.csv,
// uncertainty.md/.html/.pdf and plots/ atomically into
// reports/<budget-name>_uncertainty/ (or --out).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

#include "deb/load/budget_yaml.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb::tools {

// The digest that ties a sharded study's parts together: SHA-256 of the
// budget document (extends resolved, --set applied), the method, seed and
// samples, and deb's version.
std::string UncertaintyDigest(const std::string& budget_text, const UncertaintyOptions& options);

// Writes the study's directory atomically (out_dir "":
// reports/<name>_uncertainty) and, unless quiet, prints the study's summary
// and where its report is (deb uncertainty, deb merge).
// `budget_file`: the budget as given, named in the documents with its digest.
void WriteUncertaintyStudy(const std::string& budget_name, const UncertaintyResult& result,
                           const std::string& budget_file, const std::string& out_dir, bool force, bool plots, bool quiet,
                           int threads);

class UncertaintyCommand {
 public:
  UncertaintyCommand();
  ~UncertaintyCommand();
  UncertaintyCommand(const UncertaintyCommand&) = delete;
  UncertaintyCommand& operator=(const UncertaintyCommand&) = delete;

  // Registers `uncertainty` on app.
  CLI::App* Register(CLI::App& app);
  // Runs it, after parsing; returns the exit code.
  // @throws InputError for bad input, WriteError for output that cannot be written.
  int Run() const;

  struct Options;

 private:
  std::unique_ptr<Options> options_;
};

}  // namespace deb::tools
