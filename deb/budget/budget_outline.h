// What a result keeps of the budget it was evaluated from: names,
// descriptions, units, the sources' channels, the contributors, and what a
// report says of an output beyond its figures (its weighting filter and the
// terms of a combined output). It holds no spectrum, path or model. Evaluate
// fills it (BudgetResult::outline) and the result store saves it, so the
// result files and the report are functions of the result alone, whether it
// was just evaluated or read back from its store.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/path_composition.h"

namespace deb {

// A source without its spectrum.
struct SourceOutline {
  std::string name;
  std::string description;
  std::string unit;                   // of the signal; its PSD is in unit^2/Hz
  std::vector<std::string> channels;  // Source::channel_names
};

// A weighting filter as a report states it, without the filter.
struct WeightingOutline {
  std::string unit;  // of the filter's gain
  std::string description;
};

// What a report says of an output beyond its OutputResult.
struct OutputOutline {
  std::optional<WeightingOutline> weighting;  // none: the output is not weighted
  std::vector<SignalTerm> combination;        // Output::combination; empty unless combined
};

// A budget parameter as a report lists it.
struct ParameterOutline {
  std::string name;
  std::string expression;  // as written: "2100 kg", "sqrt(4*k/m)/(2*pi)"
  std::string description;
  bool derived = false;    // a formula of other parameters
  double value = 0.0;      // in `unit`
  // A literal's unit as written ("kg"); a derived one's SI base units
  // ("s-1"); "" for a dimensionless value.
  std::string unit;
};

struct BudgetOutline {
  std::string name;
  std::string description;
  GridKind grid_kind = GridKind::kAuto;
  std::vector<Band> bands;                // the budget's; empty: decades of the grid
  std::vector<SourceOutline> sources;
  std::vector<Contributor> contributors;  // in budget order, as every OutputResult lists them
  std::vector<OutputOutline> outputs;     // outputs[o] describes BudgetResult::outputs[o]
  std::vector<std::string> covariance;    // Budget::covariance
  std::vector<ParameterOutline> parameters;  // Budget::parameters, in order
  bool has_sweep = false;                    // Budget::has_sweep: a run evaluates the budget as written only
  std::size_t uncertain_parameters = 0;      // Budget::uncertain_parameters: a run takes their nominal values

  // The source a contributor of this outline names; aborts (DEB_DEMAND) if
  // the outline holds none of that name.
  const SourceOutline& SourceOf(const Contributor& contributor) const;
};

// The outline of a validated budget.
BudgetOutline OutlineOf(const Budget& budget);
// Its parameters' part (BudgetOutline::parameters).
std::vector<ParameterOutline> OutlineOf(const std::vector<Parameter>& parameters);

}  // namespace deb
