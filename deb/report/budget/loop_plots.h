// Internal: not part of the public API.
// Figures of every distinct feedback loop of the budget's paths
// (BudgetResult::loops, loop_margins.h): the Bode plot of the loop gain L
// with its crossovers and margins marked, |S| and |T| on one plot, and the
// Nyquist plot of L with the unit circle, the point -1 and the circle of
// the modulus margin around it. Loops with one channel whose margins were
// evaluated; the others are skipped (deb check states why).
#pragma once

#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/result.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// Three plots per loop, loops in the order of result.loops.
// @throws InputError as FeedbackLoop::LoopGainAt.
std::vector<Plot> LoopPlots(const BudgetResult& result, int digits = 4);

}  // namespace deb::report
