// Internal: not part of the public API.
// YAML -> Source: the `sources:` entries of a budget (flat, vc, measured,
// timeseries, reference), converted at load to deb's internal convention (one-sided PSD, unit^2/Hz).
#pragma once

#include <string>

#include "deb/budget/source.h"
#include "deb/load/yaml_reader.h"

namespace deb::load {

Source ParseSource(const YamlNode& node, const std::string& base_dir);

}  // namespace deb::load
