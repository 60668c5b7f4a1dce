#include "deb/budget/budget_outline.h"

#include <algorithm>

#include "deb/core/error.h"
#include "deb/units/quantity.h"

namespace deb {

const SourceOutline& BudgetOutline::SourceOf(const Contributor& contributor) const {
  const auto s = std::find_if(sources.begin(), sources.end(),
                              [&](const SourceOutline& source) { return source.name == contributor.source; });
  DEB_DEMAND(s != sources.end());
  return *s;
}

BudgetOutline OutlineOf(const Budget& budget) {
  BudgetOutline outline;
  outline.name = budget.name;
  outline.description = budget.description;
  outline.grid_kind = budget.grid.kind;
  outline.bands = budget.bands;
  for (const Source& s : budget.sources) outline.sources.push_back({s.name, s.description, s.unit, s.channel_names});
  outline.contributors = budget.contributors;
  for (const Output& o : budget.outputs) {
    OutputOutline& out = outline.outputs.emplace_back();
    if (o.weighting) out.weighting = WeightingOutline{o.weighting->unit, o.weighting->description};
    out.combination = o.combination;
  }
  outline.covariance = budget.covariance;
  outline.parameters = OutlineOf(budget.parameters);
  outline.has_sweep = budget.has_sweep;
  outline.uncertain_parameters = budget.uncertain_parameters;
  return outline;
}

std::vector<ParameterOutline> OutlineOf(const std::vector<Parameter>& parameters) {
  std::vector<ParameterOutline> outlines;
  for (const Parameter& p : parameters) {
    ParameterOutline& out = outlines.emplace_back();
    out.name = p.definition.name;
    out.expression = p.definition.expression;
    out.description = p.definition.description;
    out.derived = p.derived;
    if (!p.unit.empty()) {
      out.value = ValueIn(p.value, p.unit);
      out.unit = p.unit;
    } else {
      out.value = p.value.value;
      out.unit = p.value.dimension.IsNone() ? "" : p.value.dimension.Text();
    }
  }
  return outlines;
}

}  // namespace deb
