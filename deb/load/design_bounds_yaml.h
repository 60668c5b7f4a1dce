// Internal: not part of the public API.
// The bounds of design variables: a parameter written as a map may give
// `min` and `max`, the range `deb optimise` may choose its value in
// (docs/budget_reference.md, "Design variables"):
//   parameters:
//     Kv: {value: 50, min: 10, max: 200}
//     h:  {value: 210 mm, min: 0 mm, max: 400 mm}
// A number with a unit must be the parameter's quantity; a plain number is
// in the unit its value is written in.
#pragma once

#include <string>
#include <vector>

#include "deb/load/yaml_reader.h"
#include "deb/optimise/optimiser.h"
#include "deb/parameters/parameter_set.h"

namespace deb::load {

// Every parameter of `root`'s `parameters:` with bounds, in the order
// defined. @throws InputError located at the key: only one of min and max,
// min >= max, a value outside [min, max], bounds on a derived parameter, a
// bound of another quantity.
std::vector<DesignVariable> ParseDesignBounds(const YamlNode& root, const ParameterSet& parameters);

}  // namespace deb::load
