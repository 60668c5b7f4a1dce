#include "deb/budget/isolation_paths.h"

#include <cmath>
#include <memory>
#include <utility>

#include "deb/core/at_key_path.h"
#include "deb/core/error.h"
#include "deb/models/isolation_model.h"
#include "deb/units/unit.h"

namespace deb {
void CheckIsolationUnits(const IsolationUnits& units) {
  const std::string derived = "(" + units.force + ") s^2/(" + units.length + ")";
  const UnitConversion c = ConvertUnit(units.mass, derived);
  if (!c.IsPureScale() || std::abs(c.scale - 1.0) > 1e-9)
    throw InputError("units are not one consistent set: 1 " + units.mass + " must equal 1 " + units.force + " s^2/" +
                     units.length + " (e.g. kg with m and N, or t with mm and N)");
}

IsolationPaths MakeIsolationPaths(const IsolationPathsSpec& spec) {
  const IsolationSystem& sys = spec.system;
  const IsolationModel model = AtKeyPath(spec.key_path, [&] { return IsolationModel(sys); });
  const std::string velocity = spec.units.length + "/s";
  const std::vector<std::string> out_units = {velocity, velocity, velocity, "rad/s", "rad/s", "rad/s"};
  const auto out_names = IsolationModel::OutputNames(IsolationModel::Outputs::kVelocity);
  const auto make = [&](const std::string& suffix, const std::string& what, StateSpace s,
                        std::vector<std::string> in_names, const std::string& in_unit) {
    Path p;
    p.name = spec.name + "." + suffix;
    p.description = what;
    p.system = std::move(s);
    p.input_units.assign(in_names.size(), in_unit);
    p.input_names = std::move(in_names);
    p.output_names = out_names;
    p.output_units = out_units;
    return p;
  };
  std::vector<std::string> sensor_names, actuator_names;
  for (const auto& s : sys.sensors) sensor_names.push_back(s.name);
  for (const auto& a : sys.actuators) actuator_names.push_back(a.name);

  IsolationPaths out;
  using Loop = IsolationModel::Loop;
  const std::string& force = spec.units.force;
  out.paths.push_back(make("floor_open", "floor velocity -> CoG velocities, passive (open loop)",
                           model.FloorToCog(Loop::kOpen), IsolationModel::FloorInputNames(), velocity));
  if (!actuator_names.empty())
    out.paths.push_back(make("actuator_open", "actuator force -> CoG velocities, open loop",
                             model.ActuatorToCog(Loop::kOpen), actuator_names, force));
  if (model.has_control() && spec.control) {
    AtKeyPath(spec.control_key_path, [&] {
      out.paths.push_back(make("floor", "floor velocity -> CoG velocities, closed loop (eq. 3-43)",
                               model.FloorToCog(Loop::kClosed), IsolationModel::FloorInputNames(), velocity));
      out.paths.push_back(make("sensor_noise", "sensor noise -> CoG velocities, closed loop (eq. 3-44)",
                               model.SensorNoiseToCog(), sensor_names, velocity));
      out.paths.push_back(make("actuator", "actuator force -> CoG velocities, closed loop",
                               model.ActuatorToCog(Loop::kClosed), actuator_names, force));
    });
  }
  const auto shared = std::make_shared<const IsolationModel>(model);
  out.report = [shared, heading = "model " + spec.name + " (units: length " + spec.units.length + ", mass " +
                                  spec.units.mass + ", force " + force + ")\n"] {
    return heading + shared->Summary().Report();
  };
  return out;
}

}  // namespace deb
