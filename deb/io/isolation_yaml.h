// Internal: not part of the public API.
// YAML -> the rigid-body active vibration isolation model (deb/models), as a
// path entry of type `isolation_system`. One entry yields several paths,
// named "<name>.floor", "<name>.floor_open", "<name>.sensor_noise",
// "<name>.actuator", "<name>.actuator_open" (the closed-loop ones only when
// the model has sensors, actuators and gains), each with the six CoG
// velocities x_dot ... gamma_dot as outputs.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/path.h"
#include "deb/io/yaml_reader.h"

namespace deb::io {

struct ParsedModel {
  std::vector<Path> paths;
  std::string report;  // natural frequencies, mode shapes, pre-stress (plain text)
};

ParsedModel ParseIsolationSystem(const YamlNode& node);

}  // namespace deb::io
