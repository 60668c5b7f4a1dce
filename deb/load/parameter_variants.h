// Internal: not part of the public API.
// A budget at other values of some of its named parameters, many times over
// (an uncertainty study's samples, an optimiser's evaluations): the budget
// file (with --set applied) parsed and checked once; each variant a copy of
// that document with the values written in as text with their units
// (parameters.NAME, or parameters.NAME.value), loaded as any budget is, so
// that every rule applies to every variant. The parameters' study keys
// (distribution, min, max) and the budget's correlations are left out of the
// copies: a variant is a point, checked once at the nominal values.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/yaml_reader.h"
#include "deb/parameters/parameter_set.h"

namespace deb::load {

// A parameter a study sets: its name and the unit its values are written in.
struct VariedParameter {
  std::string name;
  std::string unit;       // "" for a plain number
  double unit_si = 1.0;   // one `unit` in SI
};

// The budget file read for a study: its name, the checked budget at its own
// values, its document (for the study's keys) and its evaluated parameters.
struct StudyBudget {
  Budget checked;
  std::string text;  // with --set applied
  std::shared_ptr<const YamlReader> reader;  // of `text`
  std::shared_ptr<const ParameterSet> parameters;
};
// @throws InputError as LoadBudgetFile.
StudyBudget ReadStudyBudget(const std::string& path, const std::vector<BudgetOverride>& overrides);

// The loader of variants: values in SI, in the order of `varied`; may be
// called from several threads at once. `note` starts each error message
// ("uncertainty sample"), followed by the values.
std::function<Budget(const std::vector<double>&)> ParameterVariants(const StudyBudget& budget, const std::string& path,
                                                                    const std::vector<BudgetOverride>& overrides,
                                                                    const std::vector<VariedParameter>& varied,
                                                                    const std::string& note);

}  // namespace deb::load
