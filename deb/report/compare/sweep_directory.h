// Internal: not part of the public API.
// The directory `deb sweep` writes, atomically (ReplaceDirectory): sweep.csv
// (one row per variant: parameter values, RMS per output and contributor;
// deb/budget/sweep.h SweepCsv), sweep.md, sweep.html and sweep.pdf
// (sweep_documents.h),
// and plots/<output>_sweep.png (sweep_plots.h) when there are plots.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/budget/sweep.h"
#include "deb/core/output_dir.h"
#include "deb/report/compare/study_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// reports/<budget-name>_sweep.
std::string DefaultSweepDirectory(const std::string& budget_name);

// Writes the sweep of budget `name`: one result per variant of `spec`, the
// plots drawn by `threads` gnuplot processes at a time (none when `plots`
// is empty).
// @throws WriteError as ReplaceDirectory; InputError if gnuplot is missing
//         or fails.
// `sources`: the budget file (StampSources).
void WriteSweepDirectory(const std::string& name, const SweepSpec& spec, const std::vector<BudgetResult>& results,
                         const std::vector<Plot>& plots, const std::string& out_dir, const ReplaceOptions& replace,
                         int threads, const std::vector<StudySource>& sources = {});

}  // namespace deb::report
