#include "deb/load/modal_yaml.h"

#include <cctype>
#include <filesystem>

#include "deb/core/limits.h"
#include "deb/core/matrix_size_text.h"
#include "deb/core/number_text.h"
#include "deb/formats/mat_file.h"
#include "deb/formats/nastran_modes.h"
#include "deb/formats/op4_file.h"
#include "deb/systems/modal_csv.h"
#include "deb/units/unit.h"

namespace deb::load {
using formats::MatFile;

const char* const kModalKeys[16] = {"file",          "modes",           "frequencies_hz",  "damping",
                                   "input_shapes",  "output_shapes",   "output_quantity", "max_frequency_hz",
                                   "residual",      "inputs",          "outputs",         "length_unit",
                                   "force_unit",    "rigid_modes",     "matrices",        "rows"};

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

// The DOF names in variable `var`, or u1, u2, ... (`stem` alone for one DOF)
// when the file has none, as for the channels of other paths.
std::vector<std::string> DofNames(const MatFile& f, const std::string& var, const std::string& shapes,
                                  Eigen::Index rows, const std::string& stem) {
  if (f.Has(var)) {
    std::vector<std::string> names = f.Names(var);
    if (static_cast<Eigen::Index>(names.size()) != rows)
      throw InputError(f.path() + ": " + var + " holds " + std::to_string(names.size()) + " name(s) but " + shapes +
                       " has " + std::to_string(rows) + " row(s), one per DOF");
    return names;
  }
  if (rows == 1) return {stem};
  std::vector<std::string> names;
  for (Eigen::Index i = 1; i <= rows; ++i) names.push_back(stem + std::to_string(i));
  return names;
}

// The modes saved in MATLAB (save -v7.3 frame.mat f_hz zeta phi_in phi_out):
// f_hz (a vector), zeta (a vector or one value for all), phi_in (inputs x
// modes), phi_out (outputs x modes), optional input_names / output_names.
// Every rule of ModalModel::Validate is checked here, for all modes, with
// the variable and index in the message.
ModalModel ReadModalMat(const std::string& path) {
  const MatFile f(path);
  ModalModel model;
  model.f_hz = f.Vector("f_hz");
  const std::size_t n = model.f_hz.size();
  const std::string modes = "f_hz has " + std::to_string(n) + " mode(s)";
  if (n > static_cast<std::size_t>(limits::kMaxModes))
    throw InputError(path + ": " + modes + "; at most " + std::to_string(limits::kMaxModes) + " are allowed");
  const std::vector<double> zeta = f.Vector("zeta");
  if (zeta.size() != 1 && zeta.size() != n)
    throw InputError(path + ": zeta has " + std::to_string(zeta.size()) + " value(s) but " + modes +
                     "; give one damping ratio for all, or one per mode");
  model.zeta = zeta.size() == 1 ? std::vector<double>(n, zeta[0]) : zeta;
  for (std::size_t k = 0; k < n; ++k) {
    const std::string index = "(" + std::to_string(k + 1) + ")";
    if (const std::string p = ModeFrequencyProblem(model.f_hz[k]); !p.empty())
      throw InputError(path + ": f_hz" + index + " = " + NumberText(model.f_hz[k]) + ": " + p);
    if (const std::string p = ModeDampingProblem(model.f_hz[k], model.zeta[k]); !p.empty())
      throw InputError(path + ": zeta" + (zeta.size() == 1 ? "" : index) + " = " + NumberText(model.zeta[k]) +
                       (zeta.size() == 1 ? " (for mode " + std::to_string(k + 1) + " at " +
                                               NumberText(model.f_hz[k]) + " Hz)"
                                         : "") +
                       ": " + p);
  }
  model.phi_in = f.Matrix("phi_in");
  model.phi_out = f.Matrix("phi_out");
  for (const auto* phi : {&model.phi_in, &model.phi_out}) {
    const std::string var = phi == &model.phi_in ? "phi_in" : "phi_out";
    if (phi->cols() != static_cast<Eigen::Index>(n))
      throw InputError(path + ": " + var + " is " + SizeText(*phi) + " but " + modes + ": " + var +
                       " needs one column per mode (" + (var == "phi_in" ? "inputs" : "outputs") + " x modes)");
    if (phi->rows() == 0) throw InputError(path + ": " + var + " is " + SizeText(*phi) + ": give at least one DOF");
    if (phi->rows() > limits::kMaxChannels)
      throw InputError(path + ": " + var + " is " + SizeText(*phi) + ": " + std::to_string(phi->rows()) +
                       " DOFs; at most " + std::to_string(limits::kMaxChannels) + " are allowed");
  }
  model.input_names = DofNames(f, "input_names", "phi_in", model.phi_in.rows(), "u");
  model.output_names = DofNames(f, "output_names", "phi_out", model.phi_out.rows(), "y");
  try {
    model.Validate();
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  return model;
}

bool IsPlainUnit(const std::string& u) {
  for (char c : u)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return !u.empty();
}

}  // namespace

ModalModel ParseModalModel(const YamlNode& node, const std::string& base_dir, ModalFileUnits& units) {
  ModalModel model;
  const auto file = node.Optional("file");
  const std::string file_path = file ? Resolve(base_dir, file->AsString()) : "";
  bool nastran_keys = false;
  for (const char* key : kNastranModalKeys) nastran_keys = nastran_keys || node.Has(key);
  // A Nastran file by its content, or by the keys only such a path has (the
  // file's reader then says why it is not one).
  if (file && (nastran_keys || formats::LooksLikeOp4File(file_path) ||
               !AtNode(*file, [&] { return formats::NastranFormatOf(file_path); }).empty())) {
    for (const char* key : {"frequencies_hz", "input_shapes", "output_shapes", "max_frequency_hz"})
      if (node.Has(key))
        node.Required(key).Fail(std::string("not with a Nastran file (") + file->AsString() + "): " +
                                (std::string(key) == "max_frequency_hz"
                                     ? "choose the modes with modes: {max_hz: F}"
                                     : "its modes and shapes come from the file; name the DOFs with inputs and outputs"));
    return ParseNastranModal(node, file_path, units);
  }
  for (const char* key : kNastranModalKeys)
    if (node.Has(key))
      node.Required(key).Fail(std::string("'") + key + "' belongs to a modal path from a Nastran file (file: a .op2, "
                                                       ".pch or .op4); here the DOFs come from the shapes' names");
  if (file) {
    for (const char* key : {"modes", "frequencies_hz", "damping", "input_shapes", "output_shapes"})
      if (node.Has(key))
        node.Required(key).Fail("give 'file' (a MAT-file with f_hz, zeta, phi_in and phi_out) or '" +
                                std::string(key) + "', not both");
    model = AtNode(*file, [&] { return ReadModalMat(file_path); });
  } else {
    const Modes modes = ParseModes(node, base_dir);
    model.f_hz = modes.table.f_hz;
    model.zeta = modes.table.zeta;
    const ShapeTable in = ParseShapes(node, "input_shapes", modes, base_dir);
    const ShapeTable out = ParseShapes(node, "output_shapes", modes, base_dir);
    model.input_names = in.dofs;
    model.phi_in = in.values;
    model.output_names = out.dofs;
    model.phi_out = out.values;
  }
  if (auto q = node.Optional("output_quantity"))
    model.quantity = AtNode(*q, [&] { return ParseModalQuantity(q->AsString()); });
  bool static_residual = false;
  if (auto r = node.Optional("residual")) {
    const std::string word = r->AsString();
    if (word != "static" && word != "none") r->Fail("residual must be 'static' or 'none', got '" + word + "'");
    static_residual = word == "static";
    if (static_residual && !node.Has("max_frequency_hz"))
      r->Fail("residual: static adds the static compliance of the modes that max_frequency_hz leaves out; "
              "give max_frequency_hz");
  }
  if (auto m = node.Optional("max_frequency_hz")) {
    const double max_hz = m->AsPositive();
    const std::vector<double> all_hz = model.f_hz;
    const YamlNode at = static_residual ? node.Required("residual") : *m;
    model = AtNode(at, [&] { return model.Truncated(max_hz, static_residual); });
    if (model.modes() == 0) {
      double lowest = all_hz.front();
      for (double f : all_hz) lowest = std::min(lowest, f);
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

}  // namespace deb::load
