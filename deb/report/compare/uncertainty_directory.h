// Internal: not part of the public API.
// The directory `deb uncertainty` writes, atomically (deb/core/output_dir.h):
// summary.json, samples.csv and result.h5 (deb/results/uncertainty_files.h),
// uncertainty.md, uncertainty.html and uncertainty.pdf
// (uncertainty_documents.h) and plots/ (uncertainty_plots.h: PNG, CSV and
// gnuplot script of each figure; none with --no-plots).
#pragma once

#include <string>
#include <vector>

#include "deb/core/output_dir.h"
#include "deb/report/compare/study_document.h"
#include "deb/report/figure/plot.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb::report {

// reports/<budget name>_uncertainty
std::string DefaultUncertaintyDirectory(const std::string& budget_name);

// `sources`: the budget file (StampSources).
void WriteUncertaintyDirectory(const std::string& budget_name, const UncertaintyResult& result,
                               const std::vector<Plot>& plots, const std::string& out_dir,
                               const ReplaceOptions& replace, int threads,
                               const std::vector<StudySource>& sources = {});

}  // namespace deb::report
