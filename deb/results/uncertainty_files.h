// The files of an uncertainty study (deb uncertainty): summary.json for
// scripts (the study's settings, the parameters' distributions, and per
// output, contributor and band requirement the statistics of its RMS,
// P(meet) with its 95 % Wilson interval, the drivers and the worst corner)
// and samples.csv (one row per sample: the parameter values in their units,
// then every metric's RMS).
#pragma once

#include <string>

#include "deb/uncertainty/uncertainty_study.h"

namespace deb {

std::string UncertaintySummaryJson(const std::string& budget_name, const UncertaintyResult& result);
std::string UncertaintySamplesCsv(const UncertaintyResult& result);

}  // namespace deb
