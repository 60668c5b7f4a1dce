// Files of `deb compare`: reading the figures of a result directory's
// summary.json, and writing a comparison as JSON (for scripts) and CSV (one
// row per compared figure).
#pragma once

#include <string>

#include "deb/budget/comparison.h"

namespace deb {

// The figures in a summary.json written by `deb run`, labelled `label`.
// @throws InputError naming the file and the key path of a missing or
//         malformed entry.
ResultFigures ReadSummaryFigures(const std::string& summary_json_file, const std::string& label);

// compare.json: labels, every figure, the largest changes, unmatched entries.
std::string ComparisonJson(const Comparison& comparison);

// compare.csv: output,unit,contributor,band,rms_a,rms_b,difference,ratio,variance_change_of_total.
std::string ComparisonCsv(const Comparison& comparison);

}  // namespace deb
