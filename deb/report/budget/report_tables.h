// Internal: not part of the public API.
// The tables of a report, built once and rendered three ways: HTML for
// index.html, Markdown for report.md and aligned monospace text for the
// title pages of report.pdf, so that all three say the same thing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/result.h"

namespace deb::report {

struct Table {
  std::string title;
  std::vector<std::string> header;
  std::vector<bool> numeric;  // per column: right-aligned
  std::vector<std::vector<std::string>> rows;
  std::vector<std::vector<bool>> emphasis;  // per cell (may be empty): bold
  std::vector<std::string> notes;  // sentences set below the table, each its own line
};

// The budget's parameters: name, value, unit, expression (for a derived
// one), description; no rows if it has none.
Table ParametersTable(const BudgetOutline& outline, int digits = 4);

// One row per output: unit, RMS, requirement, margin, status, largest
// contributor (share of the variance); then one per band requirement, its
// largest contributor within the band (share of the band's variance).
// Numbers to `digits` significant digits (ReportOptions::digits).
Table SummaryTable(const BudgetResult& result, int digits = 4);

// One row per contributor of an output, by share: source, path, RMS, share,
// exact (Lyapunov) RMS or why there is none; with a requirement, the
// allocation factor k, or for a failing output the reduction of each
// contributor's RMS that meets the limit (failure_guidance.h).
Table ContributorTable(const OutputResult& output, int digits = 4);

// What would fix a failing output, one sentence (GuidanceSentence, units as
// the documents print them); "" when it meets every requirement.
std::string GuidanceText(const OutputResult& output, const FrequencyGrid& grid);

// Rows: contributors by share, then the total; columns: the bands and the
// whole grid. The largest contributor of each band is emphasised.
Table BandTable(const OutputResult& output, int digits = 4);

// The modes carrying each modal contributor's exact variance (ModeShare):
// contributor, mode, f_n, zeta, RMS-equivalent share; no rows without any.
Table ModeTable(const OutputResult& output);

// The source channels of each contributor with `breakdown: channels`
// (ContributorResult::channels), largest first under their contributor: RMS,
// share of the output, share of the contributor; with correlated channels a
// last row per contributor for the cross terms (a variance, which may be
// negative). No rows without a breakdown.
Table ChannelTable(const OutputResult& output, int digits = 4);

// The output's groups (groups.h), depth first, each indented by its depth:
// RMS, share, and RMS per band; no rows when no contributor names a group.
Table GroupTable(const OutputResult& output, int digits = 4);

// Per reference (a measured spectrum of the output) and band it covers, and
// over all it covers: the budget's RMS, the measured RMS, measured / budget
// and the unexplained RMS, sqrt(max(measured^2 - budget^2, 0)); no rows
// without references.
Table ReferenceTable(const OutputResult& output, int digits = 4);

// Measured and budget RMS further apart than this factor over a
// measurement's span: the verdict is said to rest on an incomplete (or
// pessimistic) budget.
inline constexpr double kReferenceMismatch = 1.2;
// One sentence per measured reference whose RMS over its span differs from
// the budget's by more than kReferenceMismatch, for the first page: how
// much of the measured variance the budget explains and what that means for
// the verdict; none where the budget and the measurements agree.
std::vector<std::string> MeasurementWarnings(const BudgetResult& result, int digits = 4);

// The budget's `covariance:` (output_covariance.h), one row per pair of
// outputs: correlation, covariance, exact correlation (where there is an
// exact matrix), and the
// contributor with the largest |part| of the covariance, with its part in
// percent (parts may be negative: a contributor may anti-correlate the pair).
// A pair whose |correlation| is below kRoundingCorrelation reads "≈ 0" with
// no contributor, and a note says why; another note explains parts above
// 100 % or below 0.
inline constexpr double kRoundingCorrelation = 1e-9;
Table CovarianceTable(const CovarianceResult& covariance, int digits = 4);

// A fact about the run for the head of every document.
struct ReportFact {
  std::string label, value;
  // What report.pdf's first page says anyway (the budget's name is its
  // title, deb's version is in every footer, the requirements are the
  // verdict box): left out of its facts there.
  bool shown_elsewhere_on_pdf_title_page = false;
};
struct ReportFacts {
  std::vector<ReportFact> items;
  std::vector<std::string> conventions;  // one sentence each
};
ReportFacts MakeFacts(const BudgetResult& result, const std::string& budget_file, const std::string& sha256,
                      const std::string& date, std::optional<double> seconds);

// `table` with each long text said once: a text cell of at least
// `min_characters` that several rows hold in one column, or any in the column headed
// "note", becomes a mark (¹ ² ...) and its text a note, in `notes` as
// "¹ text" in the order the marks first appear.
Table WithNotesBelow(const Table& table, std::vector<std::string>* notes, std::size_t min_characters = 24);

std::string HtmlEscape(const std::string& text);
// The table with its repeated notes below it (WithNotesBelow).
std::string ToHtml(const Table& table);
std::string ToMarkdown(const Table& table);
// Aligned columns, a header line and a rule; cells longer than max_cell
// characters are shortened with "…", except the last column, which may use
// what is left of max_line. With `shortened`, each cell cut so is added to it
// in full, as "ROW: HEADER: TEXT" (ROW the row's first cell), so that a
// document can print what the table could not.
std::vector<std::string> ToText(const Table& table, std::size_t max_cell = 30, std::size_t max_line = 128,
                                std::vector<std::string>* shortened = nullptr);

}  // namespace deb::report
