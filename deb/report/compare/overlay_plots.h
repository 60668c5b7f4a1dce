// Internal: not part of the public API.
// Overlay plots of `deb compare`: per output present in both results, the
// PSD and the CPS of A (solid) and B (dashed) in one figure each, the total
// in black and every contributor in its report colour, so that a reader
// sees where in frequency two design options differ.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// Depth of the PSD overlay's axis below its peak, as in the run's PSD plot.
inline constexpr double kOverlayPsdDecades = 10.0;

// Whether contributor c of `o` holds at least kNegligibleShare of its
// variance: drawn in a comparison's figures.
bool ShownInComparison(const OutputResult& o, std::size_t c);

// Two plots (PSD, CPS) per output name found in both a and b with the same
// unit, drawn on the axis rules of `deb run`: the frequencies of either
// result's DisplayRange, a PSD axis at most kOverlayPsdDecades deep, a linear
// CPS axis from 0 (variance left, RMS right) with the requirement; a
// contributor below kNegligibleShare of the variance in both is left out.
std::vector<Plot> OverlayPlots(const std::string& label_a, const BudgetResult& a, const std::string& label_b,
                               const BudgetResult& b);

// Writes every plot's CSV, script and PNG into plots_dir (which must exist);
// also used for the plots of deb sweep. `threads` gnuplot processes at a
// time (<= 0: DefaultThreadCount()).
// @throws InputError if gnuplot is missing or fails (FindGnuplot, RunGnuplot).
void WritePlotsAsPng(const std::vector<Plot>& plots, const std::string& plots_dir, int threads = 0);

}  // namespace deb::report
