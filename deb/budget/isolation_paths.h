// The rigid-body active vibration isolation model (deb/models) as budget
// paths. One model yields the paths "<name>.floor_open" and, with actuators,
// "<name>.actuator_open"; with sensors, actuators and a control section also
// the closed-loop "<name>.floor" (eq. 3-43), "<name>.sensor_noise" (eq. 3-44)
// and "<name>.actuator". Each has the six CoG velocities x_dot ... gamma_dot
// as outputs, in length/s and rad/s.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "deb/budget/path.h"
#include "deb/models/isolation_system.h"

namespace deb {

// The model's units; they must be one consistent set: mass = force s^2/length.
struct IsolationUnits {
  std::string length = "m", mass = "kg", force = "N";
};

// @throws InputError if 1 mass is not 1 force s^2/length.
void CheckIsolationUnits(const IsolationUnits& units);

struct IsolationPathsSpec {
  std::string name;  // the paths are "<name>.<suffix>"
  IsolationSystem system;
  IsolationUnits units;
  bool control = false;  // a control section was given: form the closed-loop paths
  // Where the caller described the model and its control, for errors (empty: none).
  std::string key_path, control_key_path;
};

struct IsolationPaths {
  std::vector<Path> paths;
  // Natural frequencies, mode shapes, pre-stress (plain text), computed
  // when called.
  std::function<std::string()> report;
};

// @throws InputError at spec.key_path if the model cannot be built (IsolationSystem::Validate and
//   IsolationModel), at spec.control_key_path if its closed loop cannot.
IsolationPaths MakeIsolationPaths(const IsolationPathsSpec& spec);

}  // namespace deb
