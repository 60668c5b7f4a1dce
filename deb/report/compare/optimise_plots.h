// Internal: not part of the public API.
// The figures of `deb optimise`:
//  - optimise_history: the objective of every budget evaluated, start by
//    start against the evaluation's number (failed designs left out), the
//    nominal design's a dotted line;
//  - optimise_map (two variables): the objective over the box (a grid of
//    designs, DesignMap), the requirements' boundary (largest RMS /
//    requirement = 1) in red, the path of the best start and the optimum.
#pragma once

#include <optional>
#include <vector>

#include "deb/optimise/optimiser.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

std::vector<Plot> OptimisePlots(const OptimiseResult& result, const std::optional<DesignMap>& map);

}  // namespace deb::report
