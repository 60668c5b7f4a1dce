// Loads a budget from a YAML file (the schema is documented in
// docs/budget_reference.md and in the example budgets). Everything the budget
// says is checked here or by Budget::Validate(); any error is an InputError
// whose message starts with "file:line:col: key.path:" and names the value and
// the rule.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "deb/budget/budget.h"

namespace deb {

// @throws InputError as described above.
Budget LoadBudgetFile(const std::string& path);

// A change made to a budget file before it is loaded (`--set KEY.PATH=VALUE`
// on the command line): whatever the key path reaches, which must exist, is
// replaced by the value read as YAML (a number, a word, a list [1, 2], a map
// {type: flat, level: 1}). Key paths are those of deb's error messages.
struct BudgetOverride {
  std::string key_path;
  std::string value;
};

// "KEY.PATH=VALUE", split at the first '='.
// @throws InputError for text without '=', or with an empty key path or value.
BudgetOverride ParseBudgetOverride(const std::string& text);

// LoadBudgetFile of the file with the overrides applied in order. An error in
// an overridden value is located at that key in the file, its message naming
// the overrides. @throws InputError also for a key path that reaches nothing
// ("--set sources[0].spectrum.levle=2: sources[0].spectrum has no key 'levle',
// did you mean 'level'? ...") and for a value that is not YAML.
Budget LoadBudgetFile(const std::string& path, const std::vector<BudgetOverride>& overrides);

// Same from text; `name` stands for the file in messages, `base_dir` resolves
// relative data-file paths.
Budget LoadBudgetText(const std::string& text, const std::string& name, const std::string& base_dir = ".");
// LoadBudgetText with overrides applied in order, located and named as
// LoadBudgetFile's (the Python module's deb.load(text, set=...)).
Budget LoadBudgetText(const std::string& text, const std::string& name, const std::string& base_dir,
                      const std::vector<BudgetOverride>& overrides);

// An error found after loading (by the engine, which knows key paths, not
// positions) is located by the loaded budget itself: Budget::Locate.

// A changed copy of a loaded budget file (a sweep variant, a scaled
// parameter), whose key paths are those of the original: `text` is loaded,
// and its errors and Budget::positions are the original's positions, each
// message starting with `note` (e.g. "sweep variant 2: ...").
Budget LoadBudgetVariant(const std::string& text, const std::shared_ptr<const KeyPositions>& original,
                         const std::string& note, const std::string& base_dir);

}  // namespace deb
