// Comparing two evaluated budgets (design options: isolator height, gain,
// floor class, sensor): RMS per output, per contributor and per band side by
// side, with the difference B - A and the ratio B / A, and the contributors
// whose variance changed most. Figures are matched by output name,
// contributor name and band edges; what exists on one side only is listed,
// not compared. Figures come from an evaluation (FiguresOf) or from a
// result directory's summary.json (deb/results/comparison_files.h).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb {

// The figures of one result that a comparison reads.
struct ResultFigures {
  struct Contributor {
    std::string name;
    double variance = 0.0;
  };
  struct Band {
    double lo_hz = 0.0, hi_hz = 0.0;
    double variance = 0.0;
    std::vector<double> contributor_variance;  // same order as Output::contributors
  };
  struct Output {
    std::string name;
    std::string unit;
    double variance = 0.0;
    std::optional<double> rms_max;
    std::vector<Contributor> contributors;
    std::vector<Band> bands;
  };
  std::string label;  // how the result is named in tables (budget name, directory)
  // SHA-256 of the budget file the figures are of (64 hex digits; a result
  // directory's from its summary.json), "" where unknown.
  std::string budget_sha256;
  std::vector<Output> outputs;
  std::vector<ParameterOutline> parameters;  // the budget's, if it has any
};

// A parameter whose value, unit or formula differs between A and B, or that
// only one has ("" on the other side).
struct ParameterChange {
  std::string name;
  std::string a, b;  // "52000 N/m", "1.58395 s-1 = sqrt(4*k/m)/(2*pi)"
};

ResultFigures FiguresOf(const std::string& label, const BudgetResult& result);

// A figure whose variance is below this fraction of its total (in the same
// result) is negligible: its RMS is below 1e-3 of the total's, so it moves
// the total's RMS by less than 5e-7 (root sum of squares), below the 4
// digits the tables print, and its layer of the run's CPS plot is below a
// pixel. Its ratio says nothing about the design: a 1e-13 term that becomes
// 1e-1 reads "from ≈0", not B / A = 1e12. The total of a whole-grid contributor is its output's; of a band's
// contributor, the band's; a band's total is negligible only at 0.
inline constexpr double kNegligibleShare = 1e-6;

// One compared figure. band is empty for the whole grid; contributor is
// "total" for the output's total. rms_b - rms_a and rms_b / rms_a (none when
// rms_a is 0, or when either side is negligible).
struct ComparedFigure {
  std::string output;
  std::string unit;
  std::string contributor;
  std::string band;  // "lo-hi Hz", or empty (a key of compare.json and .csv)
  double rms_a = 0.0, rms_b = 0.0;
  double difference = 0.0;
  std::optional<double> ratio;
  // Change of variance as a fraction of the larger total variance of the
  // output: ranks the contributors that changed most.
  double variance_change_of_total = 0.0;
  // Below kNegligibleShare of its total's variance in A, in B.
  bool negligible_a = false, negligible_b = false;
  double band_lo_hz = 0.0, band_hi_hz = 0.0;  // the band's edges, where band is not empty

  // |B - A| / A > rel, for a figure that is not negligible on both sides;
  // one that is negligible on one side only has moved by any rel.
  bool MovedBy(double rel) const;
};

struct Comparison {
  std::string label_a, label_b;
  std::vector<ComparedFigure> figures;  // per output: total, contributors, then bands
  std::vector<std::string> unmatched;   // sentences: what only one side has, unit mismatches
  // `deb compare --tolerance`: the relative change beyond which a figure has
  // moved (documents list Moved(*tolerance)); none when not asked.
  std::optional<double> tolerance;
  // The parameters that differ (pygwinc's --diff), in A's order then B's.
  std::vector<ParameterChange> parameters;

  // Contributor figures (whole grid) by |variance_change_of_total|, largest
  // first, at most `count` per output.
  std::vector<ComparedFigure> LargestChanges(std::size_t count = 3) const;
  // The figures that moved by more than rel (MovedBy), in table order.
  std::vector<ComparedFigure> Moved(double rel) const;
};

Comparison Compare(const ResultFigures& a, const ResultFigures& b);

}  // namespace deb
