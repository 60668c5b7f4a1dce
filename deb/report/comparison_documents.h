// Internal: not part of the public API.
// The documents of `deb compare`: compare.md and compare.html (one
// self-contained page; the plots are files beside it under plots/), with one
// table per output (RMS of A and B per contributor and band, B - A, B / A)
// and the contributors that changed most.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/report/plot.h"
#include "deb/report/report_tables.h"

namespace deb::report {

// B / A with 4 significant digits, "–" where there is none (A is 0, B is not).
std::string RatioText(const ComparedFigure& f);

// One table per output, then the largest changes.
std::vector<Table> ComparisonTables(const Comparison& cmp);

// The plots are referenced as plots/<name>.png.
std::string ComparisonMarkdown(const Comparison& cmp, const std::vector<Plot>& plots);
std::string ComparisonHtml(const Comparison& cmp, const std::vector<Plot>& plots);

}  // namespace deb::report
