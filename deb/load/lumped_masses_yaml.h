// Internal: not part of the public API.
// The path type `lumped_masses` (deb/models/lumped_masses.h) from YAML:
//   masses: {table: 400 kg, head: m_head}
//   couplings: [{between: [table, ground], k: 2.3e4 N/m, c: 480 N s/m}, ...]
//   inputs:  [{name: F_act, force: [head, table]}, {name: floor_acc, ground: acceleration}]
//   outputs: [{name: gap, displacement: [head, table]}]
// docs/budget_reference.md, "type: lumped_masses".
#pragma once

#include <set>
#include <string>
#include <vector>

#include "deb/load/yaml_reader.h"
#include "deb/systems/state_space.h"

namespace deb::load {

// The keys of a lumped_masses path besides name, description, type and the
// unit keys.
std::set<std::string> LumpedMassesKeys();

struct LumpedMassesPath {
  StateSpace system = StateSpace::Gain(Eigen::MatrixXd(0, 0));  // SI: N or m/s^2 in, m or m/s out
  std::vector<std::string> input_names, output_names;
  std::vector<std::string> input_si_units, output_si_units;  // "N", "m/s^2"; "m", "m/s"
};

// @throws InputError located at the offending key.
LumpedMassesPath ParseLumpedMasses(const YamlNode& node);

}  // namespace deb::load
