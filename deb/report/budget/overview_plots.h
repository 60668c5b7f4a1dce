// Internal: not part of the public API.
// The budget report's overview: per output a panel of bars, the RMS of every
// contributor and the total, against the requirement line, the title
// stating the verdict; at most eight panels per page, outputs spread evenly
// over the pages.
#pragma once

#include <vector>

#include "deb/budget/result.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

std::vector<Plot> OverviewFigures(const BudgetResult& result, int digits = 4);

}  // namespace deb::report
