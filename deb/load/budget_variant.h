// Internal: not part of the public API.
// A changed copy of a loaded budget given as its YAML document, not as text
// (LoadBudgetVariant's text is parsed again): for studies that load many
// variants of one budget, each a copy of the parsed document with a few
// values written in (an uncertainty study's samples). Errors and
// Budget::positions are the original's, each message starting with `note`.
#pragma once

#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>

#include "deb/budget/budget.h"

namespace deb {

// A variant is a point: the budget's study sections (sweep, correlations)
// and its parameters' study keys (distribution, min, max) are removed from
// its document, having been checked once with the budget. Otherwise a
// changed value would meet rules of the nominal one (a bound it now
// crosses, a distribution on what is now an expression).
void RemoveStudyKeys(YAML::Node& root);

Budget LoadBudgetVariantNode(const YAML::Node& root, const std::shared_ptr<const KeyPositions>& original,
                             const std::string& note, const std::string& base_dir);

}  // namespace deb
