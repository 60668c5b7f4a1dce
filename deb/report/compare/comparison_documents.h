// Internal: not part of the public API.
// The documents of `deb compare`: compare.md, compare.html and compare.pdf
// (study_document.h), with the headline, one table per output (RMS of A and
// B per contributor and band, B - A, B / A), the contributors that changed
// most, the parameters that differ, and the figures.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/compare/study_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// B / A with 4 significant digits; where there is none "from ≈0" (A is
// negligible, B is not), "to ≈0" (the reverse) or "–" (both negligible, 0 / 0).
std::string RatioText(const ComparedFigure& f);

// A total whose B / A is within this of 1 is "unchanged": a design change
// that moves an RMS by 0.3 % is below what a model of a machine can tell
// (at 5e-4, compare.pdf called h = 0 against h = 210 mm "worse" for 1.003).
inline constexpr double kUnchangedRel = 0.01;
// "better" (B's RMS is lower), "worse", "unchanged" or "–" (no ratio).
std::string Verdict(const ComparedFigure& total);

// Per output: total RMS of A and B, B / A, the verdict and the contributors
// whose variance changed most.
Table HeadlineTable(const Comparison& cmp);

// The headline, one table per output, the largest changes, and with a
// tolerance the figures that moved beyond it.
std::vector<Table> ComparisonTables(const Comparison& cmp);

// The comparison as a document; `plots` outlive it.
StudyDocument ComparisonDocument(const Comparison& cmp, const std::vector<Plot>& plots);

}  // namespace deb::report
