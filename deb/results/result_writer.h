// Writes the result of `deb run`: summary.json (the figures a script reads)
// and one CSV per output (frequency, PSD and CPS per contributor and total).
// Everything goes to a temporary directory beside the target, which replaces
// the target only when complete: a failed run leaves no half-written report.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "deb/budget/result.h"
#include "deb/core/output_dir.h"

namespace deb {

struct RunInfo {
  RunInfo() = default;
  RunInfo(std::string budget_file_, std::optional<double> seconds_ = std::nullopt, int threads_ = 0)
      : budget_file(std::move(budget_file_)), seconds(seconds_), threads(threads_) {}

  std::string budget_file;
  // Wall time of the evaluation; none for a reproducible report
  // (SOURCE_DATE_EPOCH set: two runs give byte-identical files).
  std::optional<double> seconds;
  // Threads that format the result files (one file each); <= 0:
  // DefaultThreadCount(). The files are the same for any count.
  int threads = 0;
  // The budget file's text and its SHA-256 (lower-case hex) as the result
  // was made from it, e.g. read back from a result store (result_store.h);
  // none / empty: read and computed from budget_file when the report is
  // written.
  std::optional<std::string> budget_text;
  std::string budget_sha256;
};

// summary.json's text.
std::string SummaryJson(const BudgetResult& result, const RunInfo& info);

// File name used for an output's CSV: the name with characters outside
// [A-Za-z0-9_.-] replaced by '_', plus ".csv".
std::string OutputCsvName(const std::string& output_name);

// One output's CSV text.
std::string OutputCsv(const BudgetResult& result, const OutputResult& output);

// summary.json into the existing directory `dir` (each output's CSV is an
// export: result_exports.h).
// @throws WriteError if a file cannot be written.
void WriteResultFiles(const BudgetResult& result, const RunInfo& info, const std::string& dir);

// summary.json, atomically, into out_dir (deb/core/output_dir.h:
// replaced only if deb wrote it, unless options.force).
// @throws WriteError if out_dir is not deb's or cannot be written.
void WriteResultDirectory(const BudgetResult& result, const RunInfo& info, const std::string& out_dir,
                          const ReplaceOptions& options = {});

}  // namespace deb
