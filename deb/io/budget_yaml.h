// Loads a budget from a YAML file (the schema is documented in README.md and
// in the example budgets). Everything the budget says is checked here or by
// Budget::Validate(); any error is an InputError whose message starts with
// "file:line:col: key.path:" and names the value and the rule.
#pragma once

#include <memory>
#include <string>

#include "deb/budget/budget.h"

namespace deb {

// @throws InputError as described above.
Budget LoadBudgetFile(const std::string& path);

// Same from text; `name` stands for the file in messages, `base_dir` resolves
// relative data-file paths.
Budget LoadBudgetText(const std::string& text, const std::string& name, const std::string& base_dir = ".");

// An error found after loading (by the engine, which knows key paths, not
// positions) is located by the loaded budget itself: Budget::Locate.

// A changed copy of a loaded budget file (a sweep variant, a scaled
// parameter), whose key paths are those of the original: `text` is loaded,
// and its errors and Budget::positions are the original's positions, each
// message starting with `note` (e.g. "sweep variant 2: ...").
Budget LoadBudgetVariant(const std::string& text, const std::shared_ptr<const KeyPositions>& original,
                         const std::string& note, const std::string& base_dir);

}  // namespace deb
