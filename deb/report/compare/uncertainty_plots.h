// Internal: not part of the public API.
// The figures of `deb uncertainty`, per output (its total RMS):
//  - <output>_uncertainty: the distribution of the RMS over the samples,
//    a histogram over its empirical CDF on one RMS axis, the requirement a
//    dashed red line (the ECDF's height there is P(meet), named in the
//    title with its 95 % interval) and the nominal design a dotted line;
//    of more than kMaxEcdfSteps samples the ECDF steps at every k-th;
//  - <output>_drivers: the parameters' rank correlations with the RMS
//    (largest magnitude on top), and with --method sobol the first-order
//    and total Sobol indices beside them;
//  - <output>_scatter: the RMS of each sample against its two strongest
//    drivers, the requirement a dashed red line; of more than
//    kMaxScatterPoints samples every k-th is drawn (the caption says so).
#pragma once

#include <string>
#include <vector>

#include "deb/report/figure/plot.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb::report {

inline constexpr std::size_t kMaxScatterPoints = 2000;
inline constexpr std::size_t kMaxEcdfSteps = 1000;

// A probability as the study's documents and figures print it: "73.2 %".
std::string ProbabilityText(double p);

// The parameters of metric `m` by the magnitude of their rank correlation,
// largest first.
std::vector<std::size_t> DriverOrder(const StudyMetric& m);

std::vector<Plot> UncertaintyPlots(const UncertaintyResult& result);

}  // namespace deb::report
