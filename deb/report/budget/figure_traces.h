// Internal: not part of the public API.
// The path responses a report keeps. The engine's traces (ResponseTraces)
// hold every contributor's path to every output on the whole grid, often
// 10^4 frequencies and more, because the output covariance reads them
// there; a figure draws a few hundred of them (PlotPoints). A report and
// its result store keep each response at the frequencies that draw it as
// the whole grid would, to a tolerance far below what a figure resolves.
#pragma once

#include "deb/budget/result.h"

namespace deb::report {

// What a response keeps: straight lines over log f through the kept values
// draw |h|^2 of every channel to kTraceTolerance decade (|h| to half of
// it, 0.023 %) and its phase to kTraceTolerance times the largest |phase|
// (at most pi: 0.036 degree). A path plot then draws |h| to its own
// 0.002 decade from these. (PlotPoints keeps the points for the gains and
// for the phases each to half the tolerance: a segment of their union may
// end where only the other needed a point.)
inline constexpr double kTraceTolerance = 2e-4;

// `result` with every path response still on the grid (PathResponse::f_hz
// empty) reduced to its own frequencies; a response already reduced, as in
// a result read back from its store, is kept as it is, so that the report
// redrawn from a store is the report of the run.
BudgetResult WithFigureTraces(const BudgetResult& result, int threads = 0);

}  // namespace deb::report
