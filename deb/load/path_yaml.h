// Internal: not part of the public API.
// YAML -> Path: the `paths:` entries of a budget (transfer_function,
// state_space (A, B, C, D inline or from a MATLAB file, deb/formats/mat_file.h), gain, frf (a measured frequency response from a file), modal
// (finite-element modes, deb/load/modal_yaml.h), and
// series/parallel/feedback of earlier paths, composed by
// deb/budget/path_composition.h), and output weightings.
#pragma once

#include <map>
#include <vector>
#include <string>

#include "deb/budget/budget.h"
#include "deb/budget/path.h"
#include "deb/load/yaml_reader.h"

namespace deb::load {

class PathContext {
 public:
  explicit PathContext(std::string base_dir) : base_dir_(std::move(base_dir)) {}

  // Parses one entry; composite paths may name entries parsed before. A model
  // entry (type isolation_system) yields several paths and a model report.
  std::vector<Path> Parse(const YamlNode& node);
  const std::vector<ModelReport>& models() const { return models_; }

 private:
  const Path& Lookup(const YamlNode& name_node) const;
  Path Compose(const YamlNode& node, const std::string& type, const Path& entry) const;
  std::string base_dir_;
  std::map<std::string, Path> parsed_;
  std::vector<ModelReport> models_;
};

Weighting ParseWeighting(const YamlNode& node);

}  // namespace deb::load
