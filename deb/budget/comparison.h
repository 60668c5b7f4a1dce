// Comparing two evaluated budgets (design options: isolator height, gain,
// floor class, sensor): RMS per output, per contributor and per band side by
// side, with the difference B - A and the ratio B / A, and the contributors
// whose variance changed most. Figures are matched by output name,
// contributor name and band edges; what exists on one side only is listed,
// not compared. Figures come from an evaluation (FiguresOf) or from a
// result directory's summary.json (deb/io/comparison_files.h).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/engine.h"

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
  std::vector<Output> outputs;
};

ResultFigures FiguresOf(const std::string& label, const BudgetResult& result);

// A figure whose variance is below this fraction of its output's total
// variance (in the same result) is negligible: below what the CPS plot of
// `deb run` can show (its display floor, kDisplayTail of the report). Its
// ratio says nothing about the design: a 1e-13 term that becomes 1e-1 reads
// "from ≈0", not B / A = 1e12.
inline constexpr double kNegligibleShare = 1e-3;

// One compared figure. band is empty for the whole grid; contributor is
// "total" for the output's total. rms_b - rms_a and rms_b / rms_a (none when
// rms_a is 0, or when either side is negligible).
struct ComparedFigure {
  std::string output;
  std::string unit;
  std::string contributor;
  std::string band;  // "lo-hi Hz", or empty
  double rms_a = 0.0, rms_b = 0.0;
  double difference = 0.0;
  std::optional<double> ratio;
  // Change of variance as a fraction of the larger total variance of the
  // output: ranks the contributors that changed most.
  double variance_change_of_total = 0.0;
  // Below kNegligibleShare of the output's total variance in A, in B.
  bool negligible_a = false, negligible_b = false;

  // |B - A| / A > rel, for a figure that is not negligible on both sides;
  // one that is negligible on one side only has moved by any rel.
  bool MovedBy(double rel) const;
};

struct Comparison {
  std::string label_a, label_b;
  std::vector<ComparedFigure> figures;  // per output: total, contributors, then bands
  std::vector<std::string> unmatched;   // sentences: what only one side has, unit mismatches

  // Contributor figures (whole grid) by |variance_change_of_total|, largest
  // first, at most `count` per output.
  std::vector<ComparedFigure> LargestChanges(std::size_t count = 3) const;
  // The figures that moved by more than rel (MovedBy), in table order.
  std::vector<ComparedFigure> Moved(double rel) const;
};

Comparison Compare(const ResultFigures& a, const ResultFigures& b);

}  // namespace deb
