// Loads a budget from a YAML file (the schema is documented in README.md and
// in the example budgets). Everything the budget says is checked here or by
// Budget::Validate(); any error is an InputError whose message starts with
// "file:line:col: key.path:" and names the value and the rule.
#pragma once

#include <string>

#include "deb/budget/budget.h"

namespace deb {

// @throws InputError as described above.
Budget LoadBudgetFile(const std::string& path);

// Same from text; `name` stands for the file in messages, `base_dir` resolves
// relative data-file paths.
Budget LoadBudgetText(const std::string& text, const std::string& name, const std::string& base_dir = ".");

// "file:line:col: key_path: message" for an error found after loading (the
// engine knows key paths, not positions): the budget at `path` is read again
// to find where key_path, or its closest parent, stands.
std::string LocateInBudgetFile(const std::string& path, const std::string& key_path, const std::string& message);

}  // namespace deb
