#include "deb/io/isolation_yaml.h"

#include <cmath>

#include "deb/models/isolation_model.h"
#include "deb/units/unit.h"

namespace deb::io {
namespace {

Eigen::Vector3d Vector3(const YamlNode& node) {
  const auto v = node.AsDoubles();
  if (v.size() != 3) node.Fail("expected 3 numbers [x, y, z] (or [p, q, r]), got " + std::to_string(v.size()));
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

Eigen::Matrix3d Inertia(const YamlNode& node) {
  if (node.IsSequence() && node.size() == 3 && !node.Elements()[0].IsSequence()) {
    return Vector3(node).asDiagonal();  // principal moments [J_xx, J_yy, J_zz]
  }
  const Eigen::MatrixXd j = node.AsMatrix();
  if (j.rows() != 3 || j.cols() != 3) node.Fail("inertia must be [J_xx, J_yy, J_zz] or a 3x3 matrix");
  return j;
}

// The model's units must be one consistent set: mass = force s^2 / length.
void CheckUnitSet(const YamlNode& node, const std::string& length, const std::string& mass, const std::string& force) {
  const std::string derived = "(" + force + ") s^2/(" + length + ")";
  const UnitConversion c = AtNode(node, [&] { return ConvertUnit(mass, derived); });
  if (!c.IsPureScale() || std::abs(c.scale - 1.0) > 1e-9) {
    node.Fail("units are not one consistent set: 1 " + mass + " must equal 1 " + force + " s^2/" + length +
              " (e.g. kg with m and N, or t with mm and N)");
  }
}

}  // namespace

ParsedModel ParseIsolationSystem(const YamlNode& node) {
  node.AllowOnly({"name", "description", "type", "units", "body", "isolators", "sensors", "actuators", "control"});
  const std::string name = node.Required("name").AsString();
  std::string length = "m", mass = "kg", force = "N";
  if (auto u = node.Optional("units")) {
    u->AllowOnly({"length", "mass", "force"});
    if (auto v = u->Optional("length")) length = v->AsString();
    if (auto v = u->Optional("mass")) mass = v->AsString();
    if (auto v = u->Optional("force")) force = v->AsString();
    CheckUnitSet(*u, length, mass, force);
  }

  IsolationSystem sys;
  const YamlNode body = node.Required("body");
  body.AllowOnly({"mass", "inertia", "gravity"});
  sys.body.mass = body.Required("mass").AsDouble();
  sys.body.inertia = Inertia(body.Required("inertia"));
  if (auto g = body.Optional("gravity")) sys.body.gravity = g->AsNonNegative();
  AtNode(body, [&] { sys.body.Validate(); });

  for (const auto& n : node.Required("isolators").Elements()) {
    n.AllowOnly({"name", "position", "stiffness", "damping", "rotation_deg", "spring_length"});
    Isolator iso;
    iso.name = n.Required("name").AsString();
    iso.position = Vector3(n.Required("position"));
    iso.stiffness = Vector3(n.Required("stiffness"));
    iso.damping = Vector3(n.Required("damping"));
    if (auto r = n.Optional("rotation_deg")) iso.rotation_rad = r->AsDouble() * std::acos(-1.0) / 180.0;
    if (auto l = n.Optional("spring_length")) iso.spring_length = l->AsPositive();
    sys.isolators.push_back(iso);
  }
  if (auto sensors = node.Optional("sensors")) {
    for (const auto& n : sensors->Elements()) {
      n.AllowOnly({"name", "isolator", "axis"});
      VelocitySensor s;
      s.name = n.Required("name").AsString();
      s.isolator = n.Required("isolator").AsString();
      const YamlNode axis = n.Required("axis");
      s.axis = AtNode(axis, [&] { return ParseBodyAxis(axis.AsString()); });
      sys.sensors.push_back(s);
    }
  }
  if (auto actuators = node.Optional("actuators")) {
    for (const auto& n : actuators->Elements()) {
      n.AllowOnly({"name", "isolator", "axis"});
      ForceActuator a;
      a.name = n.Required("name").AsString();
      a.isolator = n.Required("isolator").AsString();
      const YamlNode axis = n.Required("axis");
      a.axis = AtNode(axis, [&] { return ParseLocalAxis(axis.AsString()); });
      sys.actuators.push_back(a);
    }
  }
  if (auto control = node.Optional("control")) {
    control->AllowOnly({"sensing", "motor", "gains"});
    if (auto f = control->Optional("sensing")) sys.control.sensing = f->AsMatrix();
    if (auto m = control->Optional("motor")) sys.control.motor = m->AsMatrix();
    const YamlNode gains = control->Required("gains");
    const auto g = gains.AsDoubles();
    if (g.size() == 1) sys.control.gains.setConstant(g[0]);
    else if (g.size() == 6) sys.control.gains = Eigen::Map<const Vector6d>(g.data());
    else gains.Fail("gains: one number for all six logical axes, or six numbers, got " + std::to_string(g.size()));
  }

  const IsolationModel model = AtNode(node, [&] { return IsolationModel(sys); });
  const std::string velocity = length + "/s";
  const std::vector<std::string> out_units = {velocity, velocity, velocity, "rad/s", "rad/s", "rad/s"};
  const auto out_names = IsolationModel::OutputNames(IsolationModel::Outputs::kVelocity);
  const auto make = [&](const std::string& suffix, const std::string& what, StateSpace s,
                        std::vector<std::string> in_names, const std::string& in_unit) {
    Path p;
    p.name = name + "." + suffix;
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

  ParsedModel out;
  using Loop = IsolationModel::Loop;
  out.paths.push_back(make("floor_open", "floor velocity -> CoG velocities, passive (open loop)",
                           model.FloorToCog(Loop::kOpen), IsolationModel::FloorInputNames(), velocity));
  if (!actuator_names.empty())
    out.paths.push_back(make("actuator_open", "actuator force -> CoG velocities, open loop",
                             model.ActuatorToCog(Loop::kOpen), actuator_names, force));
  if (model.has_control() && node.Has("control")) {
    AtNode(node.Required("control"), [&] {
      out.paths.push_back(make("floor", "floor velocity -> CoG velocities, closed loop (eq. 3-43)",
                               model.FloorToCog(Loop::kClosed), IsolationModel::FloorInputNames(), velocity));
      out.paths.push_back(make("sensor_noise", "sensor noise -> CoG velocities, closed loop (eq. 3-44)",
                               model.SensorNoiseToCog(), sensor_names, velocity));
      out.paths.push_back(make("actuator", "actuator force -> CoG velocities, closed loop",
                               model.ActuatorToCog(Loop::kClosed), actuator_names, force));
    });
  }
  out.report = "model " + name + " (units: length " + length + ", mass " + mass + ", force " + force + ")\n" +
               model.Summary().Report();
  return out;
}

}  // namespace deb::io
