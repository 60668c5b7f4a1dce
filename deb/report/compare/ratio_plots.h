// Internal: not part of the public API.
// Ratio plots of `deb compare`: per output present in both results, B's PSD
// over A's against frequency, the total in black and every contributor the
// two share in its report colour, so that a change of a few tenths of a
// percent, invisible on an overlay spanning decades, reads off the axis.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// The value of `y` (on the rising frequencies `f_hz`) at `f`: straight
// between neighbours over log f and log y where both are positive, over
// log f and y otherwise; NaN outside f_hz.
double AtFrequency(const std::vector<double>& f_hz, const std::vector<double>& y, double f);

// One plot per output name found in both a and b with the same unit, named
// <output>_ratio: PSD_B(f) / PSD_A(f) on A's grid where the grids overlap
// (B's values at A's frequencies by AtFrequency; exactly B's where the grids
// are the same), over either result's display range; NaN where either PSD
// is zero. A contributor is drawn when both results have it and it holds at
// least kNegligibleShare of the variance in each (else it has no ratio, as
// in the comparison's tables). The y axis is
// linear while every ratio shown lies within [1/3, 3], else logarithmic.
std::vector<Plot> RatioPlots(const std::string& label_a, const BudgetResult& a, const std::string& label_b,
                             const BudgetResult& b);

// The figures of a comparison, per shared output: the PSD and CPS overlays
// (overlay_plots.h), then the ratio.
std::vector<Plot> ComparisonPlots(const std::string& label_a, const BudgetResult& a, const std::string& label_b,
                                  const BudgetResult& b);

}  // namespace deb::report
