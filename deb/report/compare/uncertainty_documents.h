// Internal: not part of the public API.
// The document of `deb uncertainty` (study_document.h: uncertainty.md,
// uncertainty.html, uncertainty.pdf): the study's settings and P(all
// requirements met); the parameters and their distributions; per output
// the RMS's statistics (total, contributors, band requirements), P(meet)
// of each requirement, the drivers, the worst corner and the figures
// (uncertainty_plots.h).
#pragma once

#include <string>
#include <vector>

#include "deb/report/compare/study_document.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb::report {

StudyDocument UncertaintyDocument(const std::string& budget_name, const UncertaintyResult& result,
                                  const std::vector<Plot>& plots);

}  // namespace deb::report
