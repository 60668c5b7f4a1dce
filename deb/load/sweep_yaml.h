// Budgets with a `sweep` section: the section names numeric parameters by
// key path and their values; every variant is the budget file with those
// values written in, loaded as any budget is (so every rule still applies).
//
//   sweep:
//     mode: grid                                  # grid (every combination) | zip
//     parameters:
//       - {path: "paths[0].isolators[*].position[2]", linear: {from: 0, to: -300, count: 7}}
//       - {path: "paths[0].control.gains", values: [0, 50, 100, 200]}
//       - {path: "sources[1].spectrum.level", log: {from: 1, to: 100, count: 5}}
//
// A path segment is a map key with optional [i] (an element) or [*] (every
// element). The value it reaches must be a number, or a list of numbers
// (then every element is set). `values` that are not all numbers (e.g.
// [VC-C, VC-D]) make a textual parameter: each word replaces a single value.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/sweep.h"
#include "deb/load/budget_yaml.h"

namespace deb {

struct SweepBudget {
  std::string name;  // the budget's name as written
  // The budget document as read (extends resolved, --set applied): what a
  // sharded sweep's parts must all have been made from.
  std::string text;
  SweepSpec spec;
  std::size_t variant_count = 0;  // spec.Variants().size()
  // Loads variant i (row i of spec.Variants()); may be called from several
  // threads at once, so that a sweep loads each variant in the job that
  // evaluates it. @throws InputError: the variant's own load errors, located
  // in the user's file, naming the variant.
  std::function<Budget(std::size_t)> variant;
};

// Reads the sweep section and checks every key path; loads no variant.
// @throws InputError "file:line:col: sweep....: ..." for a missing section, a
//         key path that does not reach a number, an empty range, zipped
//         lists of different lengths.
// With overrides (--set), every variant starts from the overridden budget;
// an override may not change the sweep section itself.
SweepBudget LoadSweepFile(const std::string& path, const std::vector<BudgetOverride>& overrides = {});
SweepBudget LoadSweepText(const std::string& text, const std::string& name, const std::string& base_dir = ".",
                          const std::vector<BudgetOverride>& overrides = {});

// Every variant, in order, loaded `threads` at a time (<= 0: the default
// count). @throws InputError of the first variant that fails to load.
std::vector<Budget> LoadSweepVariants(const SweepBudget& sweep, int threads = 0);

// The budget in `path` (its sweep section ignored) with every number that
// key_path reaches multiplied by factor: the perturbed budgets of a
// finite-difference sensitivity.
// @throws InputError for a malformed key path or one that reaches no number,
//         and for the budget's own load errors.
Budget LoadBudgetWithScaledParameter(const std::string& path, const std::string& key_path, double factor,
                                     const std::vector<BudgetOverride>& overrides = {});

// The numbers key_path reaches in the budget in `path` (with `overrides`
// applied), in document order: the nominal values of a sensitivity's parameter.
// @throws InputError as LoadBudgetWithScaledParameter.
std::vector<double> ParameterValues(const std::string& path, const std::string& key_path,
                                    const std::vector<BudgetOverride>& overrides = {});

}  // namespace deb
