// Internal: not part of the public API.
// YAML -> the parameters of the rigid-body active vibration isolation model
// (deb/models), a path entry of type `isolation_system`; the paths it yields
// are made by deb/budget/isolation_paths.h.
#pragma once

#include "deb/budget/isolation_paths.h"
#include "deb/load/yaml_reader.h"

namespace deb::load {

IsolationPaths ParseIsolationSystem(const YamlNode& node);

}  // namespace deb::load
