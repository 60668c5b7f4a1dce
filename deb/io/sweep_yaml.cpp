#include "deb/io/sweep_yaml.h"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/core/parallel.h"
#include "deb/core/suggest.h"
#include "deb/io/budget_yaml.h"
#include "deb/io/yaml_reader.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

using io::YamlNode;
using io::YamlReader;

// One step of a key path: a map key, or an index (-1: every element).
struct Step {
  std::string key;
  long index = 0;
  bool is_key = true;
};

// @throws via fail(why) for a malformed path.
template <typename Fail>
std::vector<Step> ParseKeyPath(const std::string& path, Fail&& fail_with) {
  std::vector<Step> steps;
  std::size_t i = 0;
  auto fail = [&](const std::string& why) {
    fail_with("key path '" + path + "': " + why + " (write e.g. paths[0].isolators[*].position[2])");
  };
  while (i < path.size()) {
    std::string key;
    while (i < path.size() && path[i] != '.' && path[i] != '[') key += path[i++];
    if (key.empty()) fail("empty key at character " + std::to_string(i + 1));
    steps.push_back({key, 0, true});
    while (i < path.size() && path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string::npos) fail("'[' without ']'");
      const std::string inside = path.substr(i + 1, close - i - 1);
      if (inside == "*") {
        steps.push_back({"", -1, false});
      } else {
        if (inside.empty() || inside.find_first_not_of("0123456789") != std::string::npos)
          fail("index '" + inside + "' is neither a number nor *");
        if (inside.size() > 9) fail("index " + inside + " is too large (at most 999999999)");
        steps.push_back({"", std::stol(inside), false});
      }
      i = close + 1;
    }
    if (i < path.size()) {
      if (path[i] != '.') fail("unexpected '" + std::string(1, path[i]) + "'");
      ++i;
      if (i == path.size()) fail("ends with '.'");
    }
  }
  if (steps.empty()) fail("empty");
  return steps;
}

std::vector<Step> ParseKeyPath(const YamlNode& node) {
  return ParseKeyPath(node.AsString(), [&](const std::string& why) { node.Fail(why); });
}

using Transform = std::function<double(double)>;

// The nodes a key path has reached. A YAML alias makes one node appear at
// several places: it is changed once (a scale applied twice would be wrong),
// and nested aliases cannot make a short file a walk of 10^9 nodes.
class Reached {
 public:
  // False if n was reached before. Counts every call against the limit.
  bool First(const YAML::Node& n) {
    if (++calls_ > limits::kMaxKeyPathVisits) throw Overflow();
    const YAML::Mark m = n.Mark();
    if (m.is_null()) return true;
    return seen_.insert({m.pos, m.line, m.column}).second;
  }
  struct Overflow {};
  static std::string Why() {
    return "the key path reaches more than " + std::to_string(limits::kMaxKeyPathVisits) +
           " values (nested YAML aliases?)";
  }

 private:
  std::size_t calls_ = 0;
  std::set<std::tuple<int, int, int>> seen_;
};

std::string Text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool IsNumber(const YAML::Node& n) {
  if (!n.IsScalar()) return false;
  double d;
  return YAML::convert<double>::decode(n, d);
}

// Why map n at `where` has no `key`: the keys it has, the nearest first.
std::string NoKey(const YAML::Node& n, const std::string& key, const std::string& where) {
  std::vector<std::string> keys;
  std::string list;
  for (const auto& kv : n) {
    keys.push_back(kv.first.Scalar());  // plain scalars: the reader's document check
    list += (list.empty() ? "" : ", ") + keys.back();
  }
  return (where.empty() ? std::string("the budget") : where) + " has no key '" + key + "'" + DidYouMean(key, keys) +
         " (it has: " + list + ")";
}

// Replaces every number x the steps reach from n by t(x); `where` is the
// path so far. Returns an empty string or why the path does not reach a number.
std::string Apply(YAML::Node n, const std::vector<Step>& steps, std::size_t s, const Transform& t,
                  const std::string& where, Reached& reached) {
  if (!reached.First(n)) return "";
  if (s == steps.size()) {
    if (IsNumber(n)) {
      n = Text(t(n.as<double>()));
      return "";
    }
    if (n.IsSequence() && n.size() > 0) {
      for (std::size_t k = 0; k < n.size(); ++k)
        if (!IsNumber(n[k])) return where + " is a list that holds something other than numbers";
      for (std::size_t k = 0; k < n.size(); ++k)
        if (reached.First(n[k])) n[k] = Text(t(n[k].as<double>()));
      return "";
    }
    return where + " is not a number or a list of numbers";
  }
  const Step& step = steps[s];
  if (step.is_key) {
    if (!n.IsMap()) return where + " is not a map, so it has no key '" + step.key + "'";
    const YAML::Node& cn = n;
    if (!cn[step.key]) return NoKey(n, step.key, where);
    return Apply(n[step.key], steps, s + 1, t, where.empty() ? step.key : where + "." + step.key, reached);
  }
  if (!n.IsSequence()) return where + " is not a list, so it has no element [" + (step.index < 0 ? std::string("*") : std::to_string(step.index)) + "]";
  if (step.index >= 0) {
    if (static_cast<std::size_t>(step.index) >= n.size())
      return where + " has " + std::to_string(n.size()) + " element(s), so no [" + std::to_string(step.index) + "]";
    return Apply(n[static_cast<std::size_t>(step.index)], steps, s + 1, t, where + "[" + std::to_string(step.index) + "]",
                 reached);
  }
  if (n.size() == 0) return where + " is an empty list: [*] reaches nothing";
  for (std::size_t k = 0; k < n.size(); ++k) {
    const std::string why = Apply(n[k], steps, s + 1, t, where + "[" + std::to_string(k) + "]", reached);
    if (!why.empty()) return why;
  }
  return "";
}

// Writes a text at every scalar the steps reach (a textual parameter).
std::string ApplyText(YAML::Node n, const std::vector<Step>& steps, std::size_t s, const std::string& text,
                      const std::string& where, Reached& reached) {
  if (!reached.First(n)) return "";
  if (s == steps.size()) {
    if (!n.IsScalar()) return where + " is not a single value";
    n = text;
    return "";
  }
  const Step& step = steps[s];
  if (step.is_key) {
    const YAML::Node& cn = n;
    if (!n.IsMap()) return where + " is not a map, so it has no key '" + step.key + "'";
    if (!cn[step.key]) return NoKey(n, step.key, where);
    return ApplyText(n[step.key], steps, s + 1, text, where.empty() ? step.key : where + "." + step.key, reached);
  }
  if (!n.IsSequence()) return where + " is not a list";
  const std::size_t lo = step.index < 0 ? 0 : static_cast<std::size_t>(step.index);
  const std::size_t hi = step.index < 0 ? n.size() : lo + 1;
  if (hi > n.size() || lo >= hi) return where + " has " + std::to_string(n.size()) + " element(s)";
  for (std::size_t k = lo; k < hi; ++k) {
    const std::string why = ApplyText(n[k], steps, s + 1, text, where + "[" + std::to_string(k) + "]", reached);
    if (!why.empty()) return why;
  }
  return "";
}

std::string Assign(YAML::Node n, const std::vector<Step>& steps, const SweepParameter& p, double v) {
  Reached reached;
  try {
    if (!p.texts.empty()) return ApplyText(n, steps, 0, p.Text(v), "", reached);
    return Apply(n, steps, 0, [v](double) { return v; }, "", reached);
  } catch (const Reached::Overflow&) {
    return Reached::Why();
  }
}

// A parameter's name on axes and in tables: one line of printable text.
std::string ParseLabel(const YamlNode& node) {
  const std::string label = node.AsString();
  if (label.find_first_not_of(" \t") == std::string::npos)
    node.Fail("the label is empty; name the parameter, e.g. 'isolator height h'");
  if (label.size() > kMaxSweepLabelChars)
    node.Fail("the label has " + std::to_string(label.size()) + " characters, more than the " +
              std::to_string(kMaxSweepLabelChars) + " an axis can show");
  for (const char ch : label)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
      node.Fail("the label holds a control character (a line break?); write it on one line");
  return label;
}

std::vector<double> ParseValues(const YamlNode& p, std::vector<std::string>* texts) {
  int given = 0;
  for (const char* k : {"values", "linear", "log"}) given += p.Has(k) ? 1 : 0;
  if (given != 1) p.Fail("give exactly one of values, linear, log");
  if (auto v = p.Optional("values")) {
    if (v->IsSequence() && v->size() == 0) v->Fail("the list of values is empty");
    const std::vector<std::string> words = v->AsStrings();
    bool numbers = true;
    for (const std::string& w : words) {
      char* end = nullptr;
      std::strtod(w.c_str(), &end);
      numbers &= !w.empty() && end && *end == '\0';
    }
    if (numbers) return v->AsDoubles();
    *texts = words;  // e.g. VC classes: the budget receives the words
    std::vector<double> index(words.size());
    for (std::size_t i = 0; i < words.size(); ++i) index[i] = static_cast<double>(i);
    return index;
  }
  const bool log = p.Has("log");
  const YamlNode r = p.Required(log ? "log" : "linear");
  r.AllowOnly({"from", "to", "count"});
  const double from = r.Required("from").AsDouble(), to = r.Required("to").AsDouble();
  const YamlNode count = r.Required("count");
  const int n = count.AsInt();
  if (n < 1) count.Fail("count " + std::to_string(n) + " gives an empty range; need count >= 1");
  if (static_cast<std::size_t>(n) > limits::kMaxSweepVariants)
    count.Fail("count " + std::to_string(n) + " is more than the " + std::to_string(limits::kMaxSweepVariants) +
               " variants a sweep may have");
  return io::AtNode(r, [&] { return log ? LogRange(from, to, n) : LinearRange(from, to, n); });
}

// Loads the variants of one sweep file: its text, the parameters' parsed
// key paths and values. Reads only its own copies, so variants load on
// several threads at once; their errors are located in the user's file.
class VariantLoader {
 public:
  VariantLoader(std::string text, std::shared_ptr<const KeyPositions> positions, std::string base_dir,
                SweepSpec spec, std::vector<std::vector<Step>> steps)
      : text_(std::move(text)), positions_(std::move(positions)), base_dir_(std::move(base_dir)),
        spec_(std::move(spec)), steps_(std::move(steps)), rows_(spec_.Variants()) {}

  // The budget with nothing assigned and its sweep section removed. Each
  // variant starts from a fresh parse of the text, not a YAML::Clone: a
  // clone loses the nodes' positions, which Reached tells aliases apart by.
  YAML::Node BaseCopy() const {
    YAML::Node copy = YAML::Load(text_);
    copy.remove("sweep");
    return copy;
  }

  Budget Variant(std::size_t i) const;

 private:
  std::string text_;
  std::shared_ptr<const KeyPositions> positions_;
  std::string base_dir_;
  SweepSpec spec_;
  std::vector<std::vector<Step>> steps_;
  std::vector<std::vector<double>> rows_;
};

Budget VariantLoader::Variant(std::size_t i) const {
  DEB_DEMAND(i < rows_.size());
  YAML::Node v = BaseCopy();
  for (std::size_t k = 0; k < steps_.size(); ++k) Assign(v, steps_[k], spec_.parameters[k], rows_[i][k]);
  YAML::Emitter emitter;
  emitter << v;
  std::ostringstream note;
  note << "sweep variant " << i + 1 << ":";
  for (std::size_t k = 0; k < steps_.size(); ++k)
    note << (k ? ", " : " ") << spec_.parameters[k].key_path << " = " << spec_.parameters[k].Text(rows_[i][k]);
  return LoadBudgetVariant(emitter.c_str(), positions_, note.str(), base_dir_);
}

SweepBudget Load(const YamlReader& reader, const std::string& base_dir) {
  const YamlNode root = reader.Root();
  const YamlNode sweep = root.Required("sweep");
  sweep.AllowOnly({"mode", "parameters"});
  SweepBudget out;
  if (auto m = sweep.Optional("mode")) out.spec.mode = io::AtNode(*m, [&] { return ParseSweepMode(m->AsString()); });
  const YamlNode params = sweep.Required("parameters");
  std::vector<std::vector<Step>> steps;
  std::vector<YamlNode> path_nodes;
  for (const YamlNode& p : params.Elements()) {
    p.AllowOnly({"path", "label", "unit", "values", "linear", "log"});
    const YamlNode path = p.Required("path");
    steps.push_back(ParseKeyPath(path));
    path_nodes.push_back(path);
    SweepParameter param;
    param.key_path = path.AsString();
    if (auto label = p.Optional("label")) param.label = ParseLabel(*label);
    if (auto unit = p.Optional("unit")) {
      param.unit = unit->AsString();
      io::AtNode(*unit, [&] { ValidateUnit(param.unit); });
    }
    param.values = ParseValues(p, &param.texts);
    out.spec.parameters.push_back(param);
  }
  if (out.spec.parameters.empty()) params.Fail("no parameters to sweep");
  if (out.spec.mode == SweepMode::kZip)
    for (std::size_t k = 1; k < out.spec.parameters.size(); ++k)
      if (out.spec.parameters[k].values.size() != out.spec.parameters[0].values.size())
        params.Elements()[k].Fail("zipped parameters need equally many values: " +
                                  std::to_string(out.spec.parameters[k].values.size()) + " here, " +
                                  std::to_string(out.spec.parameters[0].values.size()) + " for the first");
  if (out.spec.mode != SweepMode::kZip) {
    double variants = 1.0;
    for (const SweepParameter& p : out.spec.parameters) variants *= static_cast<double>(p.values.size());
    if (variants > static_cast<double>(limits::kMaxSweepVariants))
      params.Fail("the grid of these parameters has " + NumberText(variants) + " variants, more than the " +
                  std::to_string(limits::kMaxSweepVariants) + " a sweep may have; sweep fewer values");
  }
  const auto loader = std::make_shared<const VariantLoader>(reader.text(), reader.positions(), base_dir, out.spec, steps);
  // Check every path once (with its first value) before any variant loads.
  for (std::size_t k = 0; k < steps.size(); ++k) {
    YAML::Node probe = loader->BaseCopy();
    const std::string why = Assign(probe, steps[k], out.spec.parameters[k], out.spec.parameters[k].values[0]);
    if (!why.empty())
      path_nodes[k].Fail("key path '" + out.spec.parameters[k].key_path + "' does not reach " +
                         (out.spec.parameters[k].texts.empty() ? "a number: " : "a value: ") + why);
  }
  out.variant_count = out.spec.Variants().size();
  out.variant = [loader](std::size_t i) { return loader->Variant(i); };
  if (root.Has("name")) out.name = root.Required("name").AsString();  // each variant checks it
  return out;
}

}  // namespace

SweepBudget LoadSweepFile(const std::string& path) {
  const YamlReader reader = YamlReader::FromFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return Load(reader, dir.empty() ? "." : dir);
}

std::vector<double> ParameterValues(const std::string& path, const std::string& key_path) {
  const YamlReader reader = YamlReader::FromFile(path);
  YAML::Node raw = reader.LoadCopy();
  const auto steps = ParseKeyPath(key_path, [](const std::string& why) -> void { throw InputError(why); });
  if (raw.IsMap()) raw.remove("sweep");
  Reached reached;
  std::vector<double> values;
  std::string why;
  try {
    why = Apply(raw, steps, 0, [&values](double x) { values.push_back(x); return x; }, "", reached);
  } catch (const Reached::Overflow&) {
    why = Reached::Why();
  }
  if (!why.empty()) throw InputError("key path '" + key_path + "' does not reach a number in " + path + ": " + why);
  return values;
}

Budget LoadBudgetWithScaledParameter(const std::string& path, const std::string& key_path, double factor) {
  const YamlReader reader = YamlReader::FromFile(path);
  YAML::Node raw = reader.LoadCopy();
  const auto steps = ParseKeyPath(key_path, [](const std::string& why) -> void { throw InputError(why); });
  if (raw.IsMap()) raw.remove("sweep");
  Reached reached;
  std::string why;
  try {
    why = Apply(raw, steps, 0, [factor](double x) { return x * factor; }, "", reached);
  } catch (const Reached::Overflow&) {
    why = Reached::Why();
  }
  if (!why.empty()) throw InputError("key path '" + key_path + "' does not reach a number in " + path + ": " + why);
  YAML::Emitter emitter;
  emitter << raw;
  std::ostringstream note;
  note << key_path << " x " << factor;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return LoadBudgetVariant(emitter.c_str(), reader.positions(), note.str(), dir.empty() ? "." : dir);
}

SweepBudget LoadSweepText(const std::string& text, const std::string& name, const std::string& base_dir) {
  return Load(YamlReader::FromString(text, name), base_dir);
}

std::vector<Budget> LoadSweepVariants(const SweepBudget& sweep, int threads) {
  std::vector<Budget> variants(sweep.variant_count);
  ParallelForEach(variants.size(), [&](std::size_t i) { variants[i] = sweep.variant(i); }, threads);
  return variants;
}

}  // namespace deb
