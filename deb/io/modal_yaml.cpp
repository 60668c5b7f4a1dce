#include "deb/io/modal_yaml.h"

#include <cctype>
#include <filesystem>

#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/systems/modal_csv.h"
#include "deb/units/unit.h"

namespace deb::io {

const char* const kModalKeys[7] = {"modes",         "frequencies_hz",  "damping",         "input_shapes",
                                   "output_shapes", "output_quantity", "max_frequency_hz"};

namespace {

std::string Resolve(const std::string& base_dir, const std::string& file) {
  std::filesystem::path f(file);
  if (f.is_relative()) f = std::filesystem::path(base_dir) / f;
  return f.lexically_normal().string();
}

// The modes and where they came from (for the shapes' count message).
struct Modes {
  ModeTable table;
  std::string source;
};

Modes ParseModes(const YamlNode& node, const std::string& base_dir) {
  const auto file = node.Optional("modes");
  const auto freqs = node.Optional("frequencies_hz");
  const auto damping = node.Optional("damping");
  if (file) {
    if (freqs || damping)
      (freqs ? *freqs : *damping).Fail("give 'modes' (a mode table file) or 'frequencies_hz' and 'damping', not both");
    const std::string name = file->AsString();
    return {AtNode(*file, [&] { return ReadModeTable(Resolve(base_dir, name)); }), "the mode table '" + name + "'"};
  }
  if (!freqs) node.Fail("missing 'modes' (a mode table file) or 'frequencies_hz' (with 'damping')");
  if (!damping) node.Fail("missing 'damping': one damping ratio for all modes, or one per mode");
  if (freqs->IsSequence() && freqs->size() > static_cast<std::size_t>(limits::kMaxModes))
    freqs->Fail(std::to_string(freqs->size()) + " modes; at most " + std::to_string(limits::kMaxModes) +
                " are allowed");
  Modes m;
  m.source = "frequencies_hz";
  const std::vector<YamlNode> f_nodes = freqs->IsSequence() ? freqs->Elements() : std::vector<YamlNode>{*freqs};
  if (f_nodes.empty()) freqs->Fail("no modes: list at least one frequency");
  std::vector<YamlNode> z_nodes;
  if (damping->IsSequence()) {
    z_nodes = damping->Elements();
    if (z_nodes.size() != f_nodes.size())
      damping->Fail(std::to_string(z_nodes.size()) + " damping ratio(s) for " + std::to_string(f_nodes.size()) +
                    " mode(s); give one for all, or one per mode");
  } else {
    z_nodes.assign(f_nodes.size(), *damping);
  }
  for (std::size_t k = 0; k < f_nodes.size(); ++k) {
    const double f = f_nodes[k].AsDouble(), z = z_nodes[k].AsDouble();
    if (const std::string p = ModeFrequencyProblem(f); !p.empty()) f_nodes[k].Fail(p);
    if (const std::string p = ModeDampingProblem(f, z); !p.empty()) z_nodes[k].Fail(p);
    m.table.f_hz.push_back(f);
    m.table.zeta.push_back(z);
  }
  return m;
}

ShapeTable ParseShapes(const YamlNode& node, const char* key, const Modes& modes, const std::string& base_dir) {
  const YamlNode shapes = node.Required(key);
  const int n = static_cast<int>(modes.table.f_hz.size());
  if (shapes.IsScalar()) {
    const std::string file = shapes.AsString();
    return AtNode(shapes, [&] { return ReadShapeTable(Resolve(base_dir, file), n, modes.source); });
  }
  if (!shapes.IsMap())
    shapes.Fail("expected a shape table file, or a map of DOF names to one value per mode ({F1: [0.3, -0.1]})");
  const std::vector<std::string> dofs = shapes.Keys();
  if (dofs.empty()) shapes.Fail("no DOFs: give at least one (DOF: [value per mode])");
  if (dofs.size() > static_cast<std::size_t>(limits::kMaxChannels))
    shapes.Fail(std::to_string(dofs.size()) + " DOFs; at most " + std::to_string(limits::kMaxChannels) +
                " are allowed");
  ShapeTable s;
  s.values.resize(static_cast<Eigen::Index>(dofs.size()), n);
  for (std::size_t r = 0; r < dofs.size(); ++r) {
    const YamlNode row = shapes.Required(dofs[r]);
    if (dofs[r].empty()) row.Fail("empty DOF name");
    const std::vector<double> v = row.AsDoubles();
    if (static_cast<int>(v.size()) != n)
      row.Fail(std::to_string(v.size()) + " value(s), but " + modes.source + " has " + std::to_string(n) +
               " mode(s); give one value per mode, in its order");
    for (int k = 0; k < n; ++k) s.values(static_cast<Eigen::Index>(r), k) = v[k];
    s.dofs.push_back(dofs[r]);
  }
  return s;
}

bool IsPlainUnit(const std::string& u) {
  for (char c : u)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return !u.empty();
}

}  // namespace

ModalModel ParseModalModel(const YamlNode& node, const std::string& base_dir) {
  const Modes modes = ParseModes(node, base_dir);
  ModalModel model;
  model.f_hz = modes.table.f_hz;
  model.zeta = modes.table.zeta;
  const ShapeTable in = ParseShapes(node, "input_shapes", modes, base_dir);
  const ShapeTable out = ParseShapes(node, "output_shapes", modes, base_dir);
  model.input_names = in.dofs;
  model.phi_in = in.values;
  model.output_names = out.dofs;
  model.phi_out = out.values;
  if (auto q = node.Optional("output_quantity"))
    model.quantity = AtNode(*q, [&] { return ParseModalQuantity(q->AsString()); });
  if (auto m = node.Optional("max_frequency_hz")) {
    const double max_hz = m->AsPositive();
    model = model.Truncated(max_hz);
    if (model.modes() == 0) {
      double lowest = modes.table.f_hz.front();
      for (double f : modes.table.f_hz) lowest = std::min(lowest, f);
      m->Fail("no mode at or below " + NumberText(max_hz) + " Hz (the lowest is at " + NumberText(lowest) +
              " Hz): raise max_frequency_hz or remove it");
    }
  }
  AtNode(node, [&] { model.Validate(); });
  return model;
}

std::string ModalOutputUnit(const std::string& displacement_unit, ModalQuantity q) {
  ValidateUnit(displacement_unit);
  const int order = DerivativeOrder(q);
  if (order == 0) return displacement_unit;
  const std::string display = DisplayUnit(displacement_unit);
  const std::string base = IsPlainUnit(display) ? display : "(" + display + ")";
  const std::string unit = base + (order == 1 ? "/s" : "/s^2");
  ValidateUnit(unit);
  return unit;
}

}  // namespace deb::io
