#include "deb/load/isolation_yaml.h"

#include <cmath>

#include "deb/core/math_constants.h"
#include "deb/models/isolation_system.h"

namespace deb::load {
namespace {

// [x, y, z] (or [p, q, r]), each a number in `unit` or a quantity
// converted to it.
Eigen::Vector3d Vector3(const YamlNode& node, const std::string& unit) {
  if (!node.IsSequence() || node.size() != 3)
    node.Fail("expected 3 numbers [x, y, z] (or [p, q, r]), got " +
              (node.IsSequence() ? std::to_string(node.size()) : std::string("a single value")));
  const std::vector<YamlNode> e = node.Elements();
  return Eigen::Vector3d(e[0].AsValueIn(unit), e[1].AsValueIn(unit), e[2].AsValueIn(unit));
}

Eigen::Matrix3d Inertia(const YamlNode& node, const std::string& unit) {
  if (node.IsSequence() && node.size() == 3 && !node.Elements()[0].IsSequence()) {
    return Vector3(node, unit).asDiagonal();  // principal moments [J_xx, J_yy, J_zz]
  }
  if (!node.IsSequence() || node.size() != 3) node.Fail("inertia must be [J_xx, J_yy, J_zz] or a 3x3 matrix");
  Eigen::Matrix3d j;
  const std::vector<YamlNode> rows = node.Elements();
  for (int r = 0; r < 3; ++r) {
    if (!rows[r].IsSequence() || rows[r].size() != 3) node.Fail("inertia must be [J_xx, J_yy, J_zz] or a 3x3 matrix");
    j.row(r) = Vector3(rows[r], unit).transpose();
  }
  return j;
}

}  // namespace

IsolationPaths ParseIsolationSystem(const YamlNode& node) {
  node.AllowOnly({"name", "description", "type", "units", "body", "isolators", "sensors", "actuators", "control"});
  const std::string name = node.Required("name").AsString();
  IsolationPathsSpec spec;
  spec.name = name;
  if (auto u = node.Optional("units")) {
    u->AllowOnly({"length", "mass", "force"});
    if (auto v = u->Optional("length")) spec.units.length = v->AsString();
    if (auto v = u->Optional("mass")) spec.units.mass = v->AsString();
    if (auto v = u->Optional("force")) spec.units.force = v->AsString();
    AtNode(*u, [&] { CheckIsolationUnits(spec.units); });
  }

  IsolationSystem& sys = spec.system;
  const YamlNode body = node.Required("body");
  body.AllowOnly({"mass", "inertia", "gravity"});
  // Every dimensional number in the model's units (a plain number), or a
  // quantity converted to them: `position: [0.615 m, 570, -h]` in mm.
  const IsolationUnits& u = spec.units;
  const std::string length = "(" + u.length + ")", mass = "(" + u.mass + ")", force = "(" + u.force + ")";
  sys.body.mass = body.Required("mass").AsValueIn(mass);
  sys.body.inertia = Inertia(body.Required("inertia"), mass + " " + length + "^2");
  if (auto g = body.Optional("gravity")) sys.body.gravity = g->AsNonNegativeIn(length + "/s^2");
  AtNode(body, [&] { sys.body.Validate(); });

  for (const auto& n : node.Required("isolators").Elements()) {
    n.AllowOnly({"name", "position", "stiffness", "damping", "rotation_deg", "spring_length"});
    Isolator iso;
    iso.name = n.Required("name").AsString();
    iso.position = Vector3(n.Required("position"), length);
    iso.stiffness = Vector3(n.Required("stiffness"), force + "/" + length);
    iso.damping = Vector3(n.Required("damping"), force + " s/" + length);
    if (auto r = n.Optional("rotation_deg")) iso.rotation_rad = r->AsDouble() * kPi / 180.0;
    if (auto l = n.Optional("spring_length")) iso.spring_length = l->AsPositiveIn(length);
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

  spec.control = node.Has("control");
  spec.key_path = node.key();
  std::vector<YamlNode> located = {node};
  if (spec.control) {
    located.push_back(node.Required("control"));
    spec.control_key_path = located.back().key();
  }
  return AtNodes(node, located, [&] { return MakeIsolationPaths(spec); });
}

}  // namespace deb::load
