// Budgets with uncertain parameters (their `distribution:` and the budget's
// `correlations:`, deb/load/distributions_yaml.h; docs/budget_reference.md,
// "Uncertain parameters"), for an uncertainty study
// (deb/uncertainty/uncertainty_study.h): the spec, and the budget at any
// values of those parameters, loaded as any budget is (so every rule still
// applies to each sample).
#pragma once

#include <string>
#include <vector>

#include "deb/load/budget_yaml.h"
#include "deb/uncertainty/uncertainty_study.h"
namespace deb {

struct UncertaintyBudget {
  std::string name;  // the budget's name as written
  // The budget document as read (its extends: resolved, --set applied):
  // what a sharded study's parts must all have been made from.
  std::string text;
  UncertaintySpec spec;
  // The budget with the uncertain parameters at the given values (SI, spec
  // order); may be called from several threads at once. Its errors are
  // located in the user's file and name the values.
  VariantLoader variant;
};

// @throws InputError located in the file for a budget without uncertain
// parameters ("no parameter has a distribution") and every rule of the
// distributions (distributions_yaml.h); with overrides (--set) every sample starts from the
// overridden budget.
UncertaintyBudget LoadUncertaintyFile(const std::string& path, const std::vector<BudgetOverride>& overrides = {});

}  // namespace deb
