#include "deb/load/nastran_modal_yaml.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/formats/nastran_modes.h"
#include "deb/formats/op4_file.h"
#include "deb/units/unit.h"

namespace deb::load {
using formats::NastranDof;
using formats::NastranModeFile;

const char* const kNastranModalKeys[7] = {"inputs",     "outputs",     "length_unit", "force_unit",
                                         "rigid_modes", "matrices", "rows"};

namespace {

struct Channels {
  std::vector<std::string> names;
  std::vector<NastranDof> dofs;
};

Channels ParseChannels(const YamlNode& node, const char* key) {
  const YamlNode list = node.Required(key);
  Channels c;
  std::vector<YamlNode> at;
  if (list.IsMap()) {
    for (const std::string& name : list.Keys()) {
      const YamlNode dof = list.Required(name);
      if (name.empty()) dof.Fail("empty channel name");
      c.names.push_back(name);
      at.push_back(dof);
    }
  } else if (list.IsSequence()) {
    at = list.Elements();
    for (const YamlNode& dof : at) c.names.push_back(dof.AsString());
  } else {
    list.Fail("expected a list of DOFs ([\"101:T3\", ...]) or a map of channel names to DOFs ({F_tip: \"101:T3\"})");
  }
  if (at.empty()) list.Fail("no DOFs: give at least one (GRID:COMPONENT, e.g. 101:T3)");
  if (at.size() > static_cast<std::size_t>(limits::kMaxChannels))
    list.Fail(std::to_string(at.size()) + " DOFs; at most " + std::to_string(limits::kMaxChannels) + " are allowed");
  for (std::size_t i = 0; i < at.size(); ++i) {
    const NastranDof dof = AtNode(at[i], [&] { return formats::ParseNastranDof(at[i].AsString()); });
    for (std::size_t j = 0; j < c.dofs.size(); ++j)
      if (c.dofs[j].grid == dof.grid && c.dofs[j].component == dof.component)
        at[i].Fail(formats::NastranDofText(dof) + " is given twice (also as '" + c.names[j] + "')");
    c.dofs.push_back(dof);
  }
  return c;
}

// The damping ratio of each kept mode (by its frequency).
std::vector<double> ParseDamping(const YamlNode& node, const std::vector<double>& f_hz) {
  const YamlNode d = node.Required("damping");
  const std::size_t n = f_hz.size();
  if (d.IsScalar()) return std::vector<double>(n, d.AsDouble());
  if (d.IsSequence()) {
    std::vector<double> z = d.AsDoubles();
    if (z.size() != n)
      d.Fail(std::to_string(z.size()) + " damping ratio(s) for the " + std::to_string(n) +
             " mode(s) kept; give one for all, one per mode kept, or {f_hz: [...], zeta: [...]}");
    return z;
  }
  if (!d.IsMap()) d.Fail("expected a damping ratio, a list of one per mode, or {f_hz: [...], zeta: [...]}");
  d.AllowOnly({"f_hz", "zeta"});
  const YamlNode fn = d.Required("f_hz"), zn = d.Required("zeta");
  const std::vector<double> f = fn.AsDoubles(), z = zn.AsDoubles();
  if (f.empty()) fn.Fail("no points: give at least one frequency");
  if (z.size() != f.size())
    zn.Fail(std::to_string(z.size()) + " damping ratio(s) for " + std::to_string(f.size()) + " frequencies");
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!std::isfinite(f[i]) || f[i] < 0.0) fn.Fail("f_hz " + NumberText(f[i]) + " must be finite and >= 0");
    if (i > 0 && f[i] <= f[i - 1])
      fn.Fail("frequencies must increase: " + NumberText(f[i]) + " after " + NumberText(f[i - 1]));
  }
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double x = f_hz[k];
    if (x <= f.front()) {
      out[k] = z.front();
    } else if (x >= f.back()) {
      out[k] = z.back();
    } else {
      const std::size_t i = static_cast<std::size_t>(std::upper_bound(f.begin(), f.end(), x) - f.begin());
      const double t = (x - f[i - 1]) / (f[i] - f[i - 1]);
      out[k] = z[i - 1] + t * (z[i] - z[i - 1]);
    }
  }
  return out;
}

// The DOF of each row of an OP4 file's eigenvectors: a grid id stands for
// its 6 rows T1..R3, GRID:COMPONENT for one row.
std::vector<NastranDof> ParseRows(const YamlNode& node) {
  if (!node.Has("rows"))
    node.Fail("missing 'rows': the DOF of each row of the eigenvectors, in order, for an OP4 file does not name "
              "them: e.g. rows: [1, 2, 3] for the g-set of grids 1-3 (6 rows each)");
  const YamlNode rows = node.Required("rows");
  if (!rows.IsSequence() || rows.size() == 0)
    rows.Fail("expected a list of the eigenvector rows' DOFs, in order: a grid id for its 6 rows T1..R3 "
              "(e.g. [1, 2, 3]), GRID:COMPONENT for one row (\"7:T1\" for a scalar point)");
  std::vector<NastranDof> dofs;
  for (const YamlNode& item : rows.Elements()) {
    const std::string text = item.AsString();
    if (text.find(':') != std::string::npos) {
      dofs.push_back(AtNode(item, [&] { return formats::ParseNastranDof(text); }));
      continue;
    }
    long long grid = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), grid);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || grid <= 0)
      item.Fail("'" + text + "' is neither a grid id (a positive integer: its 6 rows T1..R3) nor a DOF "
                "GRID:COMPONENT (one row)");
    for (int c = 1; c <= 6; ++c) dofs.push_back({grid, c});
  }
  return dofs;
}

// The modes of the file at `path`: a Nastran result file (OP2, punch) or, with
// `matrices` and `rows`, the matrices of an OP4 file.
std::unique_ptr<NastranModeFile> OpenModes(const YamlNode& node, const std::string& path) {
  const YamlNode file_node = node.Required("file");
  const std::string name = std::filesystem::path(path).filename().string();
  if (!formats::LooksLikeOp4File(path)) {
    for (const char* key : {"matrices", "rows"})
      if (node.Has(key))
        node.Required(key).Fail(std::string("'") + key + "' names the matrices of an OP4 file, and " + name +
                                " is not one: an OP2 or punch file names its own tables and grids");
    return AtNode(file_node, [&] { return std::make_unique<NastranModeFile>(path); });
  }
  const auto matrices = node.Optional("matrices");
  if (!matrices)
    node.Fail("missing 'matrices': which matrices of the OP4 file " + name +
              " hold the modes, e.g. matrices: {phi: PHIG, lambda: LAMA} (and mass: MHH unless the modes are "
              "mass-normalised)");
  matrices->AllowOnly({"phi", "lambda", "mass"});
  formats::Op4ModeMatrices m;
  m.phi = matrices->Required("phi").AsString();
  m.lambda = matrices->Required("lambda").AsString();
  if (const auto mass = matrices->Optional("mass")) m.mass = mass->AsString();
  m.rows = ParseRows(node);
  const formats::Op4File file = AtNode(file_node, [&] { return formats::Op4File(path); });
  return AtNode(*matrices, [&] { return std::make_unique<NastranModeFile>(file, m); });
}

std::string RangeText(double lo, double hi) {
  return lo == hi ? SignificantText(lo) : SignificantText(lo) + " to " + SignificantText(hi);
}

}  // namespace

ModalModel ParseNastranModal(const YamlNode& node, const std::string& path, ModalFileUnits& units) {
  const YamlNode file_node = node.Required("file");
  const std::string name = std::filesystem::path(path).filename().string();
  const Channels inputs = ParseChannels(node, "inputs");
  const Channels outputs = ParseChannels(node, "outputs");
  const YamlNode length_node = node.Required("length_unit");
  const std::string length = length_node.AsString();
  AtNode(length_node, [&] { ValidateUnit(length); });
  if (!AtNode(length_node, [&] { return UnitsCommensurate(length, "m"); }))
    length_node.Fail("'" + length + "' is not a length unit");
  std::string force = "N";
  if (const auto f = node.Optional("force_unit")) {
    force = f->AsString();
    AtNode(*f, [&] { ValidateUnit(force); });
    if (!AtNode(*f, [&] { return UnitsCommensurate(force, "N"); })) f->Fail("'" + force + "' is not a force unit");
  }
  bool exclude_rigid = false;
  if (const auto r = node.Optional("rigid_modes")) {
    const std::string word = r->AsString();
    if (word != "keep" && word != "exclude") r->Fail("rigid_modes must be 'keep' or 'exclude', got '" + word + "'");
    exclude_rigid = word == "exclude";
  }
  bool static_residual = false;
  if (const auto r = node.Optional("residual")) {
    const std::string word = r->AsString();
    if (word != "static" && word != "none") r->Fail("residual must be 'static' or 'none', got '" + word + "'");
    static_residual = word == "static";
  }
  int count = -1;
  double max_hz = -1.0;
  std::optional<YamlNode> selection = node.Optional("modes");
  if (selection) {
    if (!selection->IsMap())
      selection->Fail("with a Nastran file, 'modes' chooses the modes: {max_hz: F} or {count: N}");
    selection->AllowOnly({"max_hz", "count"});
    if (selection->Has("max_hz") == selection->Has("count")) selection->Fail("give one of max_hz and count");
    if (const auto m = selection->Optional("max_hz")) max_hz = m->AsPositive();
    if (const auto c = selection->Optional("count")) {
      count = c->AsInt();
      if (count < 1) c->Fail("count must be at least 1, got " + std::to_string(count));
    }
  }
  if (static_residual && !selection)
    node.Required("residual").Fail("residual: static corrects for the modes that 'modes' leaves out; give modes: "
                                   "{max_hz: F} or {count: N}");

  const std::unique_ptr<NastranModeFile> opened = OpenModes(node, path);
  const NastranModeFile& file = *opened;
  const std::vector<formats::NastranMode>& all = file.modes();

  // Which of the file's modes are used, in order: rigid-body ones first
  // (unless excluded), then by the selection.
  std::vector<int> used;  // indices into `all`
  int rigid = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const formats::NastranMode& m = all[k];
    const bool is_rigid = m.f_hz < kRigidModeHz;
    if (!is_rigid && m.eigenvalue < 0.0)
      file_node.Fail(name + ": mode " + std::to_string(m.number) + " has a negative eigenvalue " +
                     NumberText(m.eigenvalue) + " at " + SignificantText(m.f_hz) +
                     " Hz: the model is unstable (a mechanism or a buckling load); fix it in the model");
    if (is_rigid) {
      ++rigid;
      if (exclude_rigid) continue;
    }
    used.push_back(static_cast<int>(k));
  }
  if (used.empty()) file_node.Fail(name + ": every mode of the file is a rigid-body mode, and rigid_modes: exclude");
  // The modes the selection keeps (and, with residual: static, every used
  // one, for the correction of the dropped).
  std::size_t kept = used.size();
  if (count > 0) {
    if (static_cast<std::size_t>(count) > used.size())
      selection->Required("count").Fail(
          "count " + std::to_string(count) + ", but " + name + " holds " + std::to_string(used.size()) + " mode(s)" +
          (exclude_rigid && rigid > 0 ? " besides its " + std::to_string(rigid) + " rigid-body mode(s)" : "") + " (" +
          SignificantText(all[static_cast<std::size_t>(used.front())].f_hz, 5) + "-" +
          SignificantText(all[static_cast<std::size_t>(used.back())].f_hz, 5) + " Hz)");
    kept = static_cast<std::size_t>(count);
  }
  if (max_hz > 0.0) {
    kept = 0;
    while (kept < used.size() && all[static_cast<std::size_t>(used[kept])].f_hz <= max_hz) ++kept;
    if (kept == 0)
      selection->Required("max_hz").Fail("no mode at or below " + NumberText(max_hz) + " Hz (the lowest is at " +
                                         SignificantText(all[static_cast<std::size_t>(used[0])].f_hz) + " Hz)");
  }
  if (kept > static_cast<std::size_t>(limits::kMaxModes))
    (selection ? *selection : file_node)
        .Fail(name + ": " + std::to_string(kept) + " modes kept; at most " + std::to_string(limits::kMaxModes) +
              " are allowed in a modal path: choose fewer with modes: {max_hz: F} or {count: N}");
  const std::size_t read = static_residual ? used.size() : kept;
  if (read > 2 * static_cast<std::size_t>(limits::kMaxModes))
    node.Required("residual").Fail(name + ": the static correction needs the " + std::to_string(read) +
                                   " modes of the file; at most " + std::to_string(2 * limits::kMaxModes) +
                                   " are read for it");
  const int last = read == 0 ? 0 : used[read - 1] + 1;  // shapes of the file's modes [0, last)
  // One pass over the eigenvectors for both sides: inputs, then outputs.
  std::vector<NastranDof> dofs = inputs.dofs;
  dofs.insert(dofs.end(), outputs.dofs.begin(), outputs.dofs.end());
  const Eigen::MatrixXd both = AtNode(file_node, [&] { return file.Shapes(dofs, last); });
  const auto n_in = static_cast<Eigen::Index>(inputs.dofs.size());
  const Eigen::MatrixXd in_all = both.topRows(n_in);
  const Eigen::MatrixXd out_all = both.bottomRows(both.rows() - n_in);

  ModalModel model;
  model.input_names = inputs.names;
  model.output_names = outputs.names;
  model.phi_in.resize(in_all.rows(), static_cast<Eigen::Index>(read));
  model.phi_out.resize(out_all.rows(), static_cast<Eigen::Index>(read));
  double gm_lo = INFINITY, gm_hi = 0.0;
  bool normalised = false;
  for (std::size_t j = 0; j < read; ++j) {
    const formats::NastranMode& m = all[static_cast<std::size_t>(used[j])];
    const bool is_rigid = m.f_hz < kRigidModeHz;
    model.f_hz.push_back(is_rigid ? 0.0 : m.f_hz);
    double scale = 1.0;
    if (std::isfinite(m.generalized_mass)) {
      scale = 1.0 / std::sqrt(m.generalized_mass);
      gm_lo = std::min(gm_lo, m.generalized_mass);
      gm_hi = std::max(gm_hi, m.generalized_mass);
      normalised = normalised || std::abs(m.generalized_mass - 1.0) > 1e-6;
    }
    model.phi_in.col(static_cast<Eigen::Index>(j)) = in_all.col(used[j]) * scale;
    model.phi_out.col(static_cast<Eigen::Index>(j)) = out_all.col(used[j]) * scale;
  }
  // The damping of the modes kept; the others are only corrected for
  // statically (residual: static) and dropped with their damping.
  model.zeta = ParseDamping(node, std::vector<double>(model.f_hz.begin(), model.f_hz.begin() + static_cast<long>(kept)));
  model.zeta.resize(read, 0.5);
  for (std::size_t j = 0; j < kept; ++j) {
    if (model.f_hz[j] == 0.0) model.zeta[j] = 0.0;  // a rigid-body mode has no damping
    const std::string p = ModeDampingProblem(model.f_hz[j], model.zeta[j]);
    if (!p.empty())
      node.Required("damping").Fail("mode " + std::to_string(all[static_cast<std::size_t>(used[j])].number) + " at " +
                                    SignificantText(model.f_hz[j]) + " Hz: damping " + NumberText(model.zeta[j]) +
                                    ": " + p);
  }
  if (auto q = node.Optional("output_quantity"))
    model.quantity = AtNode(*q, [&] { return ParseModalQuantity(q->AsString()); });

  model.notes.push_back("modes from " + name + " (" + file.format() + "; eigenvectors from " + file.shape_table() +
                        "): " + std::to_string(all.size()) + " in the file, " + SignificantText(all.front().f_hz, 5) +
                        "-" + SignificantText(all.back().f_hz, 5) + " Hz");
  if (normalised)
    model.notes.push_back("mass-normalised: each eigenvector divided by the square root of its generalised mass (" +
                          RangeText(gm_lo, gm_hi) + " in the model's units)");
  else if (gm_hi == 0.0)
    model.notes.push_back(std::string("the file holds no generalised masses") +
                          (node.Has("matrices") ? " (matrices: gives no mass)" : "") +
                          ": its eigenvectors are taken as mass-normalised");
  if (rigid > 0)
    model.notes.push_back(std::to_string(rigid) + " rigid-body mode(s) (below " + NumberText(kRigidModeHz) +
                          " Hz) " +
                          (exclude_rigid ? "excluded (rigid_modes: exclude)"
                                         : "kept as rigid modes at 0 Hz (force to displacement 1/(-w^2 m))"));
  if (kept < used.size())
    model.notes.push_back("kept " + std::to_string(kept) + " of " + std::to_string(used.size()) + " modes (" +
                          (count > 0 ? "count " + std::to_string(count) : "max_hz " + NumberText(max_hz)) + ")" +
                          (static_residual ? ", with the static correction of the " +
                                                 std::to_string(used.size() - kept) + " dropped"
                                           : ""));
  if (kept < read || static_residual)
    model = AtNode(node.Required("residual"), [&] { return model.FirstModes(static_cast<int>(kept), static_residual); });

  // The units the shapes are in, per DOF: mass-normalised shapes make H a
  // length (or rad) per force (or moment) in the model's units.
  const std::string moment = "(" + force + ")*(" + length + ")";
  for (const NastranDof& d : inputs.dofs) units.inputs.push_back(d.component <= 3 ? force : moment);
  for (const NastranDof& d : outputs.dofs) units.outputs.push_back(d.component <= 3 ? length : "rad");
  if (length != "m" || force != "N")
    model.notes.push_back("the model's units (" + length + ", " + force + ", rad) converted to the path's");
  return model;
}

}  // namespace deb::load
