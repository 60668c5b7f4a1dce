// Internal: not part of the public API.
// Magnitude plots of each contributor's transfer to each output (the thesis'
// transmissibility and sensor-sensitivity plots), one line per source
// channel, in output unit per source unit, with exactly the unit factors and
// weighting the engine applies (ComputePathResponse). Several channels are
// drawn in the channel styles (ChannelStyle), not in contributor colours;
// channels whose curves coincide are drawn once, titled "z1 = z4".
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// Frequencies a path plot shows. The output's display range (DisplayRange)
// follows the variance and can hide a resonance of the path above or below
// it; a magnitude plot shows every pole of its path whose natural frequency
// lies within the grid: `display` is widened to whole decades reaching at
// least half a decade beyond each such f_n, within the grid. A measured path
// (Path::HasMeasuredData) keeps `display`. `poles` are the lowest and
// highest such f_n (ResponseTraces::poles_hz: none for a measured path).
FrequencyRange PathRange(const std::optional<std::pair<double, double>>& poles, const FrequencyRange& display,
                         const FrequencyGrid& grid);

// One plot per (contributor, output), contributors outer, from the result's
// traces (BudgetResult::traces, DEB_DEMANDed); contributors that see the same
// transfer share a plot. Built on `threads` threads (<= 0: the default count).
std::vector<Plot> PathPlots(const BudgetResult& result, int threads = 0);

}  // namespace deb::report
