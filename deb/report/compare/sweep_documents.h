// Internal: not part of the public API.
// The documents of `deb sweep`: sweep.md, sweep.html and sweep.pdf
// (study_document.h). They lead with the best variant of each output and how
// many variants pass, then list every variant best first (RankVariants) with
// PASS/FAIL per output, then the figures.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/budget/sweep.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/compare/study_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// "11.3 PASS", "87.6 FAIL" (any requirement of the output, band included)
// or "11.3" (none); "≈ 0" where the variance is at most 1e-24 of
// `largest_variance` (the output's largest over the variants,
// LargestVariance; RoundingZero): a variant the model leaves unexcited, by
// symmetry, computed as rounding (then *rounding, if given, is set).
std::string VariantCell(const OutputResult& output, double largest_variance, bool* rounding = nullptr);
// The largest variance of output `o` over the variants.
double LargestVariance(const std::vector<BudgetResult>& results, std::size_t o);

// The settings of variant `row` (one value per parameter), "K_v = 25 N/(mm/s), h = -210 mm".
std::string VariantSettings(const SweepSpec& spec, const std::vector<double>& row);

// [0] per output: the best variant (lowest RMS), its RMS, status and how many
// variants pass; [1] every variant best first: rank, the parameters, per output VariantCell.
// DEB_DEMANDs one result per variant of spec.
std::vector<Table> SweepTables(const SweepSpec& spec, const std::vector<BudgetResult>& results);

// The sweep of budget `name` as a document; `plots` outlive it.
StudyDocument SweepDocument(const std::string& name, const SweepSpec& spec, const std::vector<BudgetResult>& results,
                            const std::vector<Plot>& plots);

}  // namespace deb::report
