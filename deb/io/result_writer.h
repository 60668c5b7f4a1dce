// Writes the result of `deb run`: summary.json (the figures a script reads)
// and one CSV per output (frequency, PSD and CPS per contributor and total).
// Everything goes to a temporary directory beside the target, which replaces
// the target only when complete: a failed run leaves no half-written report.
#pragma once

#include <functional>
#include <string>

#include "deb/budget/budget.h"
#include "deb/budget/engine.h"

namespace deb {

struct RunInfo {
  std::string budget_file;
  double seconds = 0.0;  // wall time of the evaluation
};

// summary.json's text.
std::string SummaryJson(const Budget& budget, const BudgetResult& result, const RunInfo& info);

// File name used for an output's CSV: the name with characters outside
// [A-Za-z0-9_.-] replaced by '_', plus ".csv".
std::string OutputCsvName(const std::string& output_name);

// One output's CSV text.
std::string OutputCsv(const BudgetResult& result, const OutputResult& output);

// Creates a temporary directory beside out_dir, lets fill(tmp_dir) write into
// it, then replaces out_dir by it. If fill throws, the temporary directory is
// removed and out_dir is left as it was.
// @throws InputError if the directory cannot be created or replaced.
void WriteDirectoryAtomically(const std::string& out_dir, const std::function<void(const std::string&)>& fill);

// summary.json and the CSVs, atomically, into out_dir.
void WriteResultDirectory(const Budget& budget, const BudgetResult& result, const RunInfo& info,
                          const std::string& out_dir);

}  // namespace deb
