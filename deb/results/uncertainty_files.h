// The files of an uncertainty study (deb uncertainty): summary.json for
// scripts (the study's settings, the parameters' distributions, and per
// output, contributor and band requirement the statistics of its RMS,
// P(meet) with its 95 % Wilson interval, the drivers and the worst corner)
// and samples.csv (one row per sample: the parameter values in their units,
// then every metric's RMS).
#pragma once

#include <string>

#include "deb/core/output_dir.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb {

std::string UncertaintySummaryJson(const std::string& budget_name, const UncertaintyResult& result);
std::string UncertaintySamplesCsv(const UncertaintyResult& result);
// The same, line by line into `put` (samples.csv written without holding it whole).
void UncertaintySamplesCsv(const UncertaintyResult& result, const TextSink& put);

// result.h5 of a study (docs/uncertainty.md lists its objects): under
// /uncertainty the settings, the parameters (names, units, nominal values,
// every sample's values in their units), and per metric its name, unit,
// limit (NaN without one), every sample's RMS, the statistics, P(meet)
// with its interval (NaN without a limit), the first-order sd, the rank
// correlations and Sobol indices (metrics x parameters) and the worst
// corner. @throws WriteError as Hdf5Writer.
void WriteUncertaintyStore(const std::string& path, const std::string& budget_name, const UncertaintyResult& result);

}  // namespace deb
