// Internal: not part of the public API.
// The tornado chart of `deb sensitivity`, one per output: a horizontal bar
// per parameter and term, the parameters ordered by the magnitude of their
// elasticity of the total variance (largest on top). Under each parameter's
// total bar (black), each contributor's share of it,
// (d var_c / d ln p) / var_total, in its report colour: these sum to the
// total's elasticity, so a reader sees which contributor a parameter moves.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/budget/sensitivity.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// One bar of a tornado chart, top to bottom.
struct TornadoBar {
  std::string parameter;
  std::string contributor;  // "total", or the contributor's name
  std::size_t contributor_index = 0;  // into the output's contributors (for its colour); unused for the total
  double value = 0.0;  // the total's elasticity, or the contributor's share of it
};

// The bars of output `output`, top to bottom. Contributors whose share is
// below 1e-3 of the largest bar are left out.
std::vector<TornadoBar> TornadoBars(const std::vector<Sensitivity>& all, const OutputResult& output);

// One plot per output of nominal that has sensitivities; a parameter is
// named by its label where `labels` (by key path) gives one.
std::vector<Plot> TornadoPlots(const std::vector<Sensitivity>& all, const BudgetResult& nominal,
                               const std::map<std::string, std::string>& labels = {});

}  // namespace deb::report
