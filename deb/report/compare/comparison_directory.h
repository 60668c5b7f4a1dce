// Internal: not part of the public API.
// The directory `deb compare` writes for one comparison of A and B, written
// atomically (ReplaceDirectory): compare.json and compare.csv (the figures,
// deb/io/comparison_files.h), compare.md and compare.html (the documents,
// comparison_documents.h), compare.pdf, and the overlay plots under plots/
// when there are any. What can be compared is read by LoadComparisonInput.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/budget/result.h"
#include "deb/core/output_dir.h"
#include "deb/io/budget_yaml.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// One input of a comparison: its figures, and its full result where there
// is one (a budget, or a result directory with its result store), for the
// overlay plots.
struct ComparisonInput {
  ResultFigures figures;
  std::optional<BudgetResult> result;
};

// True when `path` names a budget file, not a result directory or its
// summary.json.
bool IsComparisonBudgetFile(const std::string& path);

// A budget file is loaded with `overrides` and evaluated on `threads`
// (without response traces); a result directory's summary.json is read (the
// label: the directory's name), and its result store too when
// `with_result`; a summary.json file is read (the label: its directory's
// name).
// @throws InputError for a directory without summary.json, and as
//         LoadBudgetFile, Evaluate, ReadSummaryFigures and ReadResultStore.
ComparisonInput LoadComparisonInput(const std::string& path, const std::vector<BudgetOverride>& overrides, int threads,
                                    bool with_result);

// reports/compare_<A>_vs_<B>, the labels made file-name words.
std::string DefaultComparisonDirectory(const std::string& label_a, const std::string& label_b);

// Writes the directory (the plots drawn by `threads` gnuplot processes at a
// time; none drawn when `plots` is empty).
// @throws WriteError as ReplaceDirectory; InputError if gnuplot is missing
//         or fails.
void WriteComparisonDirectory(const Comparison& comparison, const std::vector<Plot>& plots, const std::string& out_dir,
                              const ReplaceOptions& replace, int threads);

}  // namespace deb::report
