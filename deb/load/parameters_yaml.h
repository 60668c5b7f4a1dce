// Internal: not part of the public API.
// A budget's `parameters:` section (docs/budget_reference.md, "Parameters
// and expressions"): each entry NAME: EXPRESSION or NAME: {value:
// EXPRESSION, description: TEXT}, evaluated together
// (deb/parameters/parameter_set.h).
#pragma once

#include <memory>

#include "deb/load/yaml_reader.h"
#include "deb/parameters/parameter_set.h"

namespace deb::load {

// @throws InputError located at the offending parameter's value, and for a
// bad expression at the column where it goes wrong.
std::shared_ptr<const ParameterSet> ParseParameters(const YamlNode& node);

}  // namespace deb::load
