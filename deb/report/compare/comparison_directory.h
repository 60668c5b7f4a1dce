// Internal: not part of the public API.
// The directories of `deb compare`: the result directories it reads as
// inputs (ReadComparisonResult; a budget input is evaluated by the caller,
// FiguresOf), and the directory it writes for one comparison of A and B,
// atomically (ReplaceDirectory): compare.json and compare.csv (the figures,
// deb/results/comparison_files.h), compare.md and compare.html (the documents,
// comparison_documents.h), compare.pdf, and the overlay plots under plots/
// when there are any.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/budget/result.h"
#include "deb/core/output_dir.h"
#include "deb/report/compare/study_document.h"
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

// A result directory of `deb run` or its summary.json: the figures of
// summary.json, labelled with the directory's name; and, for a directory
// when `with_result`, its result store's result if it has one.
// @throws InputError for a directory without summary.json, and as
//         ReadSummaryFigures and ReadResultStore.
ComparisonInput ReadComparisonResult(const std::string& path, bool with_result);

// reports/compare_<A>_vs_<B>, the labels made file-name words.
std::string DefaultComparisonDirectory(const std::string& label_a, const std::string& label_b);

// Writes the directory (the plots drawn by `threads` gnuplot processes at a
// time; none drawn when `plots` is empty).
// @throws WriteError as ReplaceDirectory; InputError if gnuplot is missing
//         or fails.
// `sources`: what A and B were (StampSources).
void WriteComparisonDirectory(const Comparison& comparison, const std::vector<Plot>& plots, const std::string& out_dir,
                              const ReplaceOptions& replace, int threads, const std::vector<StudySource>& sources = {});

}  // namespace deb::report
