// Internal: not part of the public API.
// `extends: base.yaml`: a budget file written as the changes to another.
// The base (itself possibly extending another, up to kMaxExtendsDepth files)
// is read first; the extending file's keys are then merged into it key by
// key: a map merges into the base's map of the same key, anything else (a
// value, a list) replaces the base's, and `null` removes the base's key.
// Relative data-file paths in a base (`file`, `modes`, `input_shapes`,
// `output_shapes`) stay relative to the base's own directory. Every key path
// keeps its position in the file that gave it, so an error in the merged
// budget is located in the base or in the extending file.
#pragma once

#include <string>

#include "deb/load/yaml_reader.h"

namespace deb::load {

inline constexpr int kMaxExtendsDepth = 16;

// The budget file at `path` with its `extends:` chain resolved (the file as
// FromFile reads it when it has none).
// @throws InputError "file:line:col: extends: ..." for a base that cannot be
//         read, is not a map, or closes a cycle (naming the chain), and for a
//         chain deeper than kMaxExtendsDepth.
YamlReader ReadBudgetFile(const std::string& path);

}  // namespace deb::load
