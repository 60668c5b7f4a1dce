#include "deb/load/path_yaml.h"

#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "deb/budget/path_composition.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/matrix_size_text.h"
#include "deb/core/number_text.h"
#include "deb/core/suggest.h"
#include "deb/load/block_yaml.h"
#include "deb/load/isolation_yaml.h"
#include "deb/load/lumped_masses_yaml.h"
#include "deb/formats/mat_file.h"
#include "deb/formats/op4_file.h"
#include "deb/load/modal_yaml.h"
#include "deb/load/uff_yaml.h"
#include "deb/formats/uff58_file.h"
#include "deb/systems/frf_csv.h"
#include "deb/systems/transfer_function.h"
#include "deb/units/unit.h"

namespace deb::load {
using formats::MatFile;
using formats::Op4File;
namespace {

const std::set<std::string> kCommonKeys = {"name", "description", "type", "inputs", "outputs",
                                           "input_unit", "input_units", "output_unit", "output_units"};

// A block built in SI units (from `si_in` to `si_out`) scaled to the
// path's input and output units: a mass_spring_damper is N to m, and a path
// from N to um needs 1e6 times its H. The units must be the same quantities.
StateSpace InPathUnits(const YamlNode& node, const Path& p, const std::string& si_in, const std::string& si_out) {
  const std::string type = node.Required("type").AsString();
  // The factor from the SI unit to the user's (output) or back (input).
  const auto scale = [&](const std::string& user, const std::string& si, const char* key, bool output) {
    const YamlNode at = node.Has(key) ? node.Required(key) : node;
    const UnitConversion c = AtNode(at, [&] { return output ? ConvertUnit(si, user) : ConvertUnit(user, si); });
    if (!c.IsPureScale())
      at.Fail("a " + type + " is " + si_in + " to " + si_out + ": '" + user + "' is not the same quantity as '" + si +
              "'");
    return c.scale;
  };
  const double factor =
      scale(p.output_units[0], si_out, "output_unit", true) * scale(p.input_units[0], si_in, "input_unit", false);
  const StateSpace& s = p.system;
  return StateSpace(s.A(), s.B(), s.C() * factor, s.D() * factor);
}

// The factors that scale a model in units `si_in[j]` to `si_out[i]`,
// channel by channel, to the path's units: H_path = diag(out) H diag(in).
// Each must be the same quantity.
struct ChannelScales {
  Eigen::VectorXd in, out;
};
ChannelScales ChannelScalesTo(const YamlNode& node, const Path& p, const std::vector<std::string>& si_in,
                              const std::vector<std::string>& si_out) {
  const auto scale = [&](const std::string& user, const std::string& si, const char* one, const char* many,
                         bool output, const std::string& channel) {
    const YamlNode at = node.Has(one) ? node.Required(one) : node.Has(many) ? node.Required(many) : node;
    const std::string what = std::string(output ? "output" : "input") + " '" + channel + "' is in " + si + ": '" +
                             user + "' is not the same quantity";
    std::optional<UnitConversion> c;
    try {
      c = output ? ConvertUnit(si, user) : ConvertUnit(user, si);
    } catch (const InputError& e) {
      at.Fail(what + " (" + e.message() + ")");
    }
    if (!c->IsPureScale()) at.Fail(what);
    return c->scale;
  };
  ChannelScales c{Eigen::VectorXd(p.system.inputs()), Eigen::VectorXd(p.system.outputs())};
  for (int j = 0; j < p.system.inputs(); ++j)
    c.in(j) = scale(p.input_units[j], si_in[j], "input_unit", "input_units", false, p.input_names[j]);
  for (int i = 0; i < p.system.outputs(); ++i)
    c.out(i) = scale(p.output_units[i], si_out[i], "output_unit", "output_units", true, p.output_names[i]);
  return c;
}

// A model built in SI units, channel by channel, scaled to the path's units
// (ChannelScalesTo).
StateSpace InChannelUnits(const YamlNode& node, const Path& p, const std::vector<std::string>& si_in,
                          const std::vector<std::string>& si_out) {
  const ChannelScales c = ChannelScalesTo(node, p, si_in, si_out);
  const StateSpace& s = p.system;
  return StateSpace(s.A(), s.B() * c.in.asDiagonal(), c.out.asDiagonal() * s.C(),
                    c.out.asDiagonal() * s.D() * c.in.asDiagonal());
}

std::set<std::string> With(std::set<std::string> keys, std::initializer_list<std::string> more) {
  keys.insert(more);
  return keys;
}

std::vector<std::string> Names(const YamlNode& node, const char* field, int count, const std::string& stem) {
  if (auto n = node.Optional(field)) {
    auto names = n->AsStrings();
    if (static_cast<int>(names.size()) != count)
      n->Fail(std::to_string(names.size()) + " name(s) given, the system has " + std::to_string(count));
    return names;
  }
  if (count == 1) return {stem};
  std::vector<std::string> names;
  for (int i = 1; i <= count; ++i) names.push_back(stem + std::to_string(i));
  return names;
}

std::vector<std::string> Units(const YamlNode& node, const std::string& single, const std::string& list, int count) {
  const auto one = node.Optional(single), many = node.Optional(list);
  if (one && many) many->Fail("give '" + single + "' or '" + list + "', not both");
  if (one) return std::vector<std::string>(count, one->AsString());
  if (many) {
    auto units = many->AsStrings();
    if (static_cast<int>(units.size()) != count)
      many->Fail(std::to_string(units.size()) + " unit(s) given, the system has " + std::to_string(count));
    return units;
  }
  node.Fail("missing '" + single + "' (one unit for all) or '" + list + "' (one per channel)");
}

// `file` relative to the budget's directory, unless absolute.
std::string Resolve(const std::string& base_dir, const std::string& file) {
  std::filesystem::path f(file);
  if (f.is_relative()) f = std::filesystem::path(base_dir) / f;
  return f.lexically_normal().string();
}

// The rule of limits::kMaxStates, for `states` states that `what` gives.
std::string TooManyStates(Eigen::Index states, const std::string& what) {
  if (states <= limits::kMaxStates) return "";
  return what + " " + std::to_string(states) + " states, more than the " + std::to_string(limits::kMaxStates) +
         " a state_space or transfer_function path may have (its analysis costs O(n^3) operations)";
}

// A state-space model from a file: a MAT-file (save plant.mat A B C D), or
// an OP4 file from Nastran. A, B, C and an optional D (zeros when absent);
// a MAT-file may add input_names / output_names.
struct StateSpaceFile {
  StateSpace system;
  std::vector<std::string> input_names, output_names;  // empty when the file has none
};

// The names of a MAT-file's variable `var`, one per channel, none repeated;
// {} if the file has no such variable.
std::vector<std::string> ChannelNames(const MatFile& f, const std::string& var, Eigen::Index count,
                                      const std::string& count_from) {
  if (!f.Has(var)) return {};
  std::vector<std::string> names = f.Names(var);
  if (static_cast<Eigen::Index>(names.size()) != count)
    throw InputError(f.path() + ": " + var + " holds " + std::to_string(names.size()) + " name(s) but " + count_from);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (!seen.insert(names[i]).second)
      throw InputError(f.path() + ": " + var + "{" + std::to_string(i + 1) + "} '" + names[i] + "' is given twice");
  return names;
}

// A, B, C and D of a file, by the names `matrices:` maps them to (D
// optional: zeros when not mapped), or else A, B, C and D (zeros when the
// file has no D). A mapped name's matrix is read located at its key; the
// shapes are checked with the file's names in the messages.
template <typename File>
StateSpace ReadStateMatrices(const File& f, const std::optional<YamlNode>& matrices) {
  const std::string& path = f.path();
  std::map<std::string, std::string> label;
  const auto read = [&](const char* key) -> Eigen::MatrixXd {
    if (!matrices) {
      label[key] = key;
      return f.Matrix(key);
    }
    const YamlNode name = matrices->Required(key);
    const std::string in_file = name.AsString();
    label[key] = in_file == key ? std::string(key) : std::string(key) + " ('" + Excerpt(in_file) + "')";
    return AtNode(name, [&] { return f.Matrix(in_file); });
  };
  if (matrices) matrices->AllowOnly({"A", "B", "C", "D"});
  const Eigen::MatrixXd a = read("A");
  const std::string n = std::to_string(a.rows());
  const std::string& la = label["A"];
  if (a.rows() != a.cols()) throw InputError(path + ": " + la + " is " + SizeText(a) + "; the state matrix A must be square");
  if (const std::string why = TooManyStates(a.rows(), la + " is " + SizeText(a) + ":"); !why.empty())
    throw InputError(path + ": " + why);
  const Eigen::MatrixXd b = read("B");
  const std::string& lb = label["B"];
  if (b.rows() != a.rows())
    throw InputError(path + ": " + lb + " is " + SizeText(b) + " but " + la + " is " + SizeText(a) + ": B needs " + n +
                     " rows");
  const Eigen::MatrixXd c = read("C");
  const std::string& lc = label["C"];
  if (c.cols() != a.rows())
    throw InputError(path + ": " + lc + " is " + SizeText(c) + " but " + la + " is " + SizeText(a) + ": C needs " + n +
                     " columns");
  if (b.cols() == 0) throw InputError(path + ": " + lb + " is " + SizeText(b) + ": the model needs at least one input");
  if (c.rows() == 0) throw InputError(path + ": " + lc + " is " + SizeText(c) + ": the model needs at least one output");
  const std::string at_most = "; at most " + std::to_string(limits::kMaxChannels) + " are allowed";
  if (b.cols() > limits::kMaxChannels)
    throw InputError(path + ": " + lb + " is " + SizeText(b) + ": " + std::to_string(b.cols()) + " inputs" + at_most);
  if (c.rows() > limits::kMaxChannels)
    throw InputError(path + ": " + lc + " is " + SizeText(c) + ": " + std::to_string(c.rows()) + " outputs" + at_most);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(c.rows(), b.cols());
  if (matrices ? matrices->Has("D") : f.Has("D")) {
    d = read("D");
    if (d.rows() != c.rows() || d.cols() != b.cols())
      throw InputError(path + ": " + label["D"] + " is " + SizeText(d) + " but " + lb + " is " + SizeText(b) +
                       " and " + lc + " is " + SizeText(c) + ": D needs to be " + std::to_string(c.rows()) + "x" +
                       std::to_string(b.cols()) + " (outputs x inputs)");
  }
  return StateSpace(a, b, c, d);
}

// An OP4 file by its content (whatever its name), else a MAT-file.
StateSpaceFile ReadStateSpaceFile(const std::string& path, const std::optional<YamlNode>& matrices) {
  if (formats::LooksLikeOp4File(path)) {
    const Op4File f(path);
    return {ReadStateMatrices(f, matrices), {}, {}};
  }
  const MatFile f(path);
  StateSpaceFile m{ReadStateMatrices(f, matrices), {}, {}};
  const Eigen::Index inputs = m.system.inputs(), outputs = m.system.outputs();
  m.input_names = ChannelNames(f, "input_names", inputs, "B has " + std::to_string(inputs) + " column(s) (inputs)");
  m.output_names = ChannelNames(f, "output_names", outputs, "C has " + std::to_string(outputs) + " row(s) (outputs)");
  return m;
}

TransferFunction ParseTf(const YamlNode& node) {
  const YamlNode den = node.Required("den");
  const std::vector<double> den_coefficients = den.AsDoubles();
  if (const std::string why = TooManyStates(static_cast<Eigen::Index>(den_coefficients.size()) - 1,
                                            "a denominator of this order gives");
      !why.empty())
    den.Fail(why);
  return AtNode(node, [&] { return TransferFunction(node.Required("num").AsDoubles(), den_coefficients); });
}

// `composed` under the name and description of `entry`.
Path Named(const Path& entry, Path composed) {
  composed.name = entry.name;
  composed.description = entry.description;
  return composed;
}

// Where a parsed path's channel names and units come from: the entry's
// inputs/outputs and units (a file's names as the default), the parts or
// data it was made of (inputs/outputs may rename them), or the type's own
// entries alone.
enum class ChannelSource { kEntry, kComposed, kOwn };

ChannelSource ParseTransferFunctionPath(const YamlNode& node, Path& p) {
  node.AllowOnly(With(kCommonKeys, {"num", "den", "matrix"}));
  if (auto m = node.Optional("matrix")) {
    std::vector<std::vector<TransferFunction>> rows;
    for (const auto& row : m->Elements()) {
      rows.emplace_back();
      for (const auto& e : row.Elements()) {
        e.AllowOnly({"num", "den"});
        rows.back().push_back(ParseTf(e));
      }
    }
    Eigen::Index states = 0;
    for (const auto& row : rows)
      for (const TransferFunction& tf : row) states += static_cast<Eigen::Index>(tf.den().size()) - 1;
    if (const std::string why = TooManyStates(states, "the denominators of this matrix give"); !why.empty())
      m->Fail(why);
    p.system = AtNode(*m, [&] { return ToStateSpace(rows); });
  } else {
    const TransferFunction tf = ParseTf(node);
    p.system = AtNode(node.Required("den"), [&] { return ToStateSpace(tf); });
  }
  return ChannelSource::kEntry;
}

// A MAT-file's channel names become the path's default names.
ChannelSource ParseStateSpacePath(const YamlNode& node, const std::string& base_dir, Path& p) {
  node.AllowOnly(With(kCommonKeys, {"A", "B", "C", "D", "file", "matrices"}));
  if (const auto file = node.Optional("file")) {
    for (const char* m : {"A", "B", "C", "D"})
      if (node.Has(m))
        node.Required(m).Fail("give 'file' (a MAT-file or an OP4 file with A, B, C and D) or the matrices inline, not both");
    const std::string path = Resolve(base_dir, file->AsString());
    StateSpaceFile m = AtNode(*file, [&] { return ReadStateSpaceFile(path, node.Optional("matrices")); });
    p.system = std::move(m.system);
    p.input_names = std::move(m.input_names);
    p.output_names = std::move(m.output_names);
    return ChannelSource::kEntry;
  }
  if (node.Has("matrices"))
    node.Required("matrices").Fail("'matrices' names the matrices of a 'file' (a MAT-file or an OP4 file); give 'file' too");
  const Eigen::MatrixXd a = node.Required("A").AsMatrix();
  if (const std::string why = TooManyStates(a.rows(), "A is " + SizeText(a) + ":"); !why.empty())
    node.Required("A").Fail(why);
  const Eigen::MatrixXd b = node.Required("B").AsMatrix(), c = node.Required("C").AsMatrix();
  const Eigen::MatrixXd d = node.Has("D") ? node.Required("D").AsMatrix() : Eigen::MatrixXd::Zero(c.rows(), b.cols());
  p.system = AtNode(node, [&] { return StateSpace(a, b, c, d); });
  return ChannelSource::kEntry;
}

// Names and units from the file: a table (deb/systems/frf_csv.h) or a
// universal file (deb/load/uff_yaml.h), told apart by its content.
ChannelSource ParseFrfPath(const YamlNode& node, const std::string& base_dir, Path& p) {
  const YamlNode file = node.Required("file");
  std::filesystem::path f(file.AsString());
  if (f.is_relative()) f = std::filesystem::path(base_dir) / f;
  if (formats::FileLooksLikeUff(f.lexically_normal().string())) {
    node.AllowOnly(With(kCommonKeys, {"file", "extrapolation", kUffPathKeys[0], kUffPathKeys[1]}));
    ParseUffFrfPath(node, f.lexically_normal().string(), p);
    return ChannelSource::kComposed;
  }
  for (const char* key : kUffPathKeys)
    if (node.Has(key))
      node.Required(key).Fail(std::string("'") + key + "' chooses datasets of a universal file (UFF 58); " +
                              f.lexically_normal().string() + " is a table: name its entries with outputs and inputs");
  node.AllowOnly(With(kCommonKeys, {"file", "extrapolation"}));
  const Extrapolation extrapolation =
      node.Has("extrapolation")
          ? AtNode(node.Required("extrapolation"), [&] { return ParseExtrapolation(node.Required("extrapolation").AsString()); })
          : Extrapolation::kError;
  const std::vector<std::string> outs = node.Has("outputs") ? node.Required("outputs").AsStrings() : std::vector<std::string>{};
  const std::vector<std::string> ins = node.Has("inputs") ? node.Required("inputs").AsStrings() : std::vector<std::string>{};
  FrfCsv frf = AtNode(file, [&] { return ReadFrfCsv(f.lexically_normal().string(), outs, ins, extrapolation); });
  p.input_names = frf.inputs;
  p.output_names = frf.outputs;
  p.system = StateSpace::Gain(Eigen::MatrixXd::Zero(frf.response.outputs(), frf.response.inputs()));
  p.measured = std::make_shared<const FrequencyModel>(std::move(frf.response));
  p.input_units = Units(node, "input_unit", "input_units", p.system.inputs());
  p.output_units = Units(node, "output_unit", "output_units", p.system.outputs());
  return ChannelSource::kComposed;
}

// Names from the mode shapes' DOFs (no inputs/outputs keys).
ChannelSource ParseModalPath(const YamlNode& node, const std::string& base_dir, Path& p) {
  std::set<std::string> keys = {"name", "description", "type", "input_unit", "input_units", "output_unit",
                                "output_units"};
  keys.insert(std::begin(kModalKeys), std::end(kModalKeys));
  node.AllowOnly(keys);
  ModalFileUnits file_units;
  ModalModel model = ParseModalModel(node, base_dir, file_units);
  AtNode(node, [&] { model.Validate(); });
  p.system = StateSpace::Gain(Eigen::MatrixXd::Zero(model.phi_out.rows(), model.phi_in.rows()));
  p.input_names = model.input_names;
  p.output_names = model.output_names;
  p.input_units = Units(node, "input_unit", "input_units", p.system.inputs());
  p.output_units = Units(node, "output_unit", "output_units", p.system.outputs());
  if (!file_units.inputs.empty()) {
    // Shapes in the file's units, scaled to the path's (output_unit names
    // the displacement's unit).
    const ChannelScales c = ChannelScalesTo(node, p, file_units.inputs, file_units.outputs);
    model.phi_in = c.in.asDiagonal() * model.phi_in;
    model.phi_out = c.out.asDiagonal() * model.phi_out;
    if (model.residual.size() > 0) model.residual = c.out.asDiagonal() * model.residual * c.in.asDiagonal();
  }
  p.modal = std::make_shared<const ModalModel>(model);
  const YamlNode unit_node = node.Required(node.Has("output_unit") ? "output_unit" : "output_units");
  for (std::string& u : p.output_units) u = AtNode(unit_node, [&] { return ModalOutputUnit(u, model.quantity); });
  // From a Nastran file, `inputs` and `outputs` name the DOFs and the channels.
  return file_units.inputs.empty() ? ChannelSource::kComposed : ChannelSource::kOwn;
}

ChannelSource ParseLumpedMassesPath(const YamlNode& node, Path& p) {
  std::set<std::string> keys = LumpedMassesKeys();
  keys.insert({"name", "description", "type", "input_unit", "input_units", "output_unit", "output_units"});
  node.AllowOnly(keys);
  LumpedMassesPath lumped = ParseLumpedMasses(node);
  p.system = std::move(lumped.system);
  p.input_names = std::move(lumped.input_names);
  p.output_names = std::move(lumped.output_names);
  p.input_units = Units(node, "input_unit", "input_units", p.system.inputs());
  p.output_units = Units(node, "output_unit", "output_units", p.system.outputs());
  p.system = InChannelUnits(node, p, lumped.input_si_units, lumped.output_si_units);
  return ChannelSource::kOwn;
}

// A delay or a sampled controller: its rational approximation, and its exact response.
ChannelSource ParseIrrationalPath(const YamlNode& node, const std::string& type, Path& p) {
  std::set<std::string> keys = IrrationalKeys(type);
  keys.insert(kCommonKeys.begin(), kCommonKeys.end());
  node.AllowOnly(keys);
  if (type == "discrete" && node.Has("den")) {
    const YamlNode den = node.Required("den");
    if (const std::string why =
            TooManyStates(static_cast<Eigen::Index>(den.AsDoubles().size()) - 1, "a denominator of this order gives");
        !why.empty())
      den.Fail(why);
  }
  IrrationalBlock block = ParseIrrationalBlock(node, type);
  p.system = block.approximation;
  p.measured = std::make_shared<const FrequencyModel>(std::move(block));
  return ChannelSource::kEntry;
}

ChannelSource ParseBlockPath(const YamlNode& node, const std::string& type, Path& p) {
  std::set<std::string> keys = BlockKeys(type);
  keys.insert(kCommonKeys.begin(), kCommonKeys.end());
  node.AllowOnly(keys);
  const TransferFunction tf = ParseBlock(node, type);
  p.system = AtNode(node, [&] { return ToStateSpace(tf); });
  return ChannelSource::kEntry;
}

// The entry's channel names and units, by where they come from.
void NameChannels(const YamlNode& node, const std::string& type, ChannelSource from, Path& p) {
  if (from == ChannelSource::kOwn) return;
  if (from == ChannelSource::kComposed) {
    if (node.Has("inputs")) p.input_names = Names(node, "inputs", p.system.inputs(), "u");
    if (node.Has("outputs")) p.output_names = Names(node, "outputs", p.system.outputs(), "y");
    return;
  }
  if (p.input_names.empty() || node.Has("inputs")) p.input_names = Names(node, "inputs", p.system.inputs(), "u");
  if (p.output_names.empty() || node.Has("outputs")) p.output_names = Names(node, "outputs", p.system.outputs(), "y");
  p.input_units = Units(node, "input_unit", "input_units", p.system.inputs());
  p.output_units = Units(node, "output_unit", "output_units", p.system.outputs());
  if (type == "mass_spring_damper") p.system = InPathUnits(node, p, "N", "m");
}

// `margins: {gain_db: G, phase_deg: P, modulus: M}` of a feedback path:
// gain and phase margins only for a loop of one channel.
MarginRequirement ParseMargins(const YamlNode& node, const FeedbackLoop& loop) {
  if (!node.IsMap()) node.Fail("expected {gain_db: G, phase_deg: P, modulus: M} (any of them)");
  node.AllowOnly({"gain_db", "phase_deg", "modulus"});
  MarginRequirement m;
  if (auto g = node.Optional("gain_db")) m.gain_db = g->AsPositive();
  if (auto p = node.Optional("phase_deg")) {
    m.phase_deg = p->AsPositive();
    if (*m.phase_deg >= 180.0) p->Fail("a phase margin is below 180 deg, got " + NumberText(*m.phase_deg));
  }
  if (auto q = node.Optional("modulus")) {
    m.modulus = q->AsPositive();
    if (*m.modulus > 1.0)
      q->Fail("a modulus margin min |1 + L| is at most 1 for a loop whose gain falls off, got " +
              NumberText(*m.modulus));
  }
  if (m.empty()) node.Fail("no margin: give gain_db, phase_deg or modulus");
  if ((m.gain_db || m.phase_deg) && loop.channels() != 1)
    node.Required(m.gain_db ? "gain_db" : "phase_deg")
        .Fail("gain and phase margins are those of a one-channel loop, and this one has " +
              std::to_string(loop.channels()) + " channels: give its modulus margin");
  return m;
}

}  // namespace

const Path& PathContext::Lookup(const YamlNode& name_node) const {
  const std::string name = name_node.AsString();
  const auto it = parsed_.find(name);
  if (it == parsed_.end()) {
    std::vector<std::string> before;
    for (const auto& [n, p] : parsed_) before.push_back(n);
    name_node.Fail("no path named '" + name + "'" + DidYouMean(name, before) + " is defined before this one");
  }
  return it->second;
}

// A path made of paths parsed before: series, parallel or feedback.
Path PathContext::Compose(const YamlNode& node, const std::string& type, const Path& entry) const {
  if (type == "feedback") {
    node.AllowOnly({"name", "description", "type", "inputs", "outputs", "plant", "controller", "sign", "margins"});
    const YamlNode plant = node.Required("plant"), controller = node.Required("controller");
    const PathPart g{&Lookup(plant), plant.key()}, k{&Lookup(controller), controller.key()};
    int sign = -1;
    if (auto s = node.Optional("sign")) {
      sign = s->AsInt();
      AtNode(*s, [&] { CheckFeedbackSign(sign); });
    }
    Path p = Named(entry, AtNodes(node, {plant, controller}, [&] { return FeedbackOfPaths(g, k, sign); }));
    if (auto margins = node.Optional("margins")) p.loops.back().required = ParseMargins(*margins, p.loops.back());
    return p;
  }
  node.AllowOnly({"name", "description", "type", "inputs", "outputs", "of"});
  const YamlNode of = node.Required("of");
  const std::vector<YamlNode> parts = of.Elements();
  std::vector<PathPart> looked_up;
  if (parts.size() >= 2)  // else the composition refuses the list before any name is looked up
    for (const YamlNode& part : parts) looked_up.push_back({&Lookup(part), part.key()});
  return Named(entry, AtNodes(of, parts, [&] {
    return type == "series" ? SeriesOfPaths(looked_up) : ParallelOfPaths(looked_up);
  }));
}

std::vector<Path> PathContext::Parse(const YamlNode& node) {
  if (node.Has("type") && node.Required("type").AsString() == "isolation_system") {
    IsolationPaths model = ParseIsolationSystem(node);
    models_.push_back({node.Required("name").AsString(), model.report});
    for (const Path& p : model.paths) {
      if (parsed_.count(p.name)) node.Required("name").Fail("path name '" + p.name + "' is used twice");
      parsed_.emplace(p.name, p);
    }
    return model.paths;
  }
  Path p;
  p.name = node.Required("name").AsString();
  if (auto d = node.Optional("description")) p.description = d->AsString();
  const YamlNode type_node = node.Required("type");
  const std::string type = type_node.AsString();
  ChannelSource from = ChannelSource::kEntry;
  if (type == "transfer_function") {
    from = ParseTransferFunctionPath(node, p);
  } else if (type == "state_space") {
    from = ParseStateSpacePath(node, base_dir_, p);
  } else if (type == "gain") {
    node.AllowOnly(With(kCommonKeys, {"gain"}));
    p.system = StateSpace::Gain(node.Required("gain").AsMatrix());
  } else if (type == "series" || type == "parallel" || type == "feedback") {
    p = Compose(node, type, p);
    from = ChannelSource::kComposed;
  } else if (type == "frf") {
    from = ParseFrfPath(node, base_dir_, p);
  } else if (type == "modal") {
    from = ParseModalPath(node, base_dir_, p);
  } else if (type == "lumped_masses") {
    from = ParseLumpedMassesPath(node, p);
  } else if (IsIrrationalType(type)) {
    from = ParseIrrationalPath(node, type, p);
  } else if (IsBlockType(type)) {
    from = ParseBlockPath(node, type, p);
  } else {
    type_node.Fail("unknown path type '" + type +
                   "'; allowed: transfer_function, state_space, gain, frf, modal, series, parallel, feedback, "
                   "isolation_system, lumped_masses, zpk, second_order, mass_spring_damper, pid, lead_lag, notch, "
                   "lowpass, highpass, integrator, delay, discrete");
  }
  NameChannels(node, type, from, p);
  AtNode(node, [&] { p.Validate(); });
  if (parsed_.count(p.name)) node.Required("name").Fail("name '" + p.name + "' is used twice in paths");
  parsed_.emplace(p.name, p);
  return {p};
}

Weighting ParseWeighting(const YamlNode& node) {
  node.AllowOnly({"num", "den", "unit", "description"});
  Weighting w;
  const TransferFunction tf = ParseTf(node);
  w.system = AtNode(node.Required("den"), [&] { return ToStateSpace(tf); });
  if (auto u = node.Optional("unit")) w.unit = u->AsString();
  AtNode(node, [&] { ValidateUnit(w.unit); });
  if (auto d = node.Optional("description")) w.description = d->AsString();
  return w;
}

}  // namespace deb::load
