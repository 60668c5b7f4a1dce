// Internal: not part of the public API.
// Applies `--set` overrides (BudgetOverride, budget_yaml.h) to a budget
// file's YAML before it is loaded: by `deb run`/`check`/`compare` through
// LoadBudgetFile, and by sweeps and sensitivities, whose variants start from
// the overridden text.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "deb/load/budget_yaml.h"

namespace deb::load {

// Applies the overrides to `root` (the document of `file`) in order.
// @throws InputError "file: --set KEY=VALUE: why" for a malformed key path,
//         one that reaches nothing, or a value that is not YAML.
void ApplyOverrides(YAML::Node root, const std::vector<BudgetOverride>& overrides, const std::string& file);

// "--set a=1, --set b=[2, 3]": the note every message about the changed
// budget starts with.
std::string OverridesNote(const std::vector<BudgetOverride>& overrides);

// The text of the file with the overrides applied; the file's text unchanged
// when there are none.
std::string OverriddenText(const std::string& text, const std::vector<BudgetOverride>& overrides,
                           const std::string& file);

}  // namespace deb::load
