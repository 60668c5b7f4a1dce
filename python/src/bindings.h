// Internal: not part of the public API.
// The Python module deb._deb (docs/python.md): the C++ objects it holds and
// the functions that add each part to the module. Thin over the public
// library: a budget is loaded and evaluated by the same calls `deb run`
// makes, and a result's arrays are views of the BudgetResult's vectors.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/result.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/result_writer.h"

namespace deb::python {

namespace py = pybind11;

// A loaded budget and what a report records of where it came from.
struct LoadedBudget {
  std::shared_ptr<const Budget> budget;
  std::string file;                 // the budget file; "" when loaded from text
  std::optional<std::string> text;  // the YAML text, when loaded from text
};

// An evaluated budget. `info` is what summary.json and the report say of
// the run (the file or text, the evaluation's wall time).
struct EvaluatedBudget {
  std::shared_ptr<const BudgetResult> result;
  RunInfo info;
};

// set= as the loader takes it: (key path, value text) pairs -> overrides.
// @throws InputError as ParseBudgetOverride.
std::vector<BudgetOverride> ToOverrides(const std::vector<std::pair<std::string, std::string>>& pairs);

// threads=None: every core (0 for the library); otherwise >= 1.
// @throws InputError naming `threads` for a count below 1.
int ThreadCount(const std::optional<int>& threads);

// Evaluate with the GIL released, timed for RunInfo::seconds.
EvaluatedBudget EvaluateLoaded(const LoadedBudget& budget, int threads);

void BindErrors(py::module_& m);    // InputError and WriteError as Python exceptions
void BindBudget(py::module_& m);    // Budget, load_file, load_text
void BindResult(py::module_& m);    // evaluate, Result, Output, Contributor, bands, requirements
void BindResponse(py::module_& m);  // frequency_response
void BindStudies(py::module_& m);   // sweep, compare, write_report
void BindDesignStudies(py::module_& m);  // uncertainty_file, optimise_file

}  // namespace deb::python
