#include "deb/load/sweep_yaml.h"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/core/parallel.h"
#include "deb/core/suggest.h"
#include "deb/load/budget_extends.h"
#include "deb/load/budget_overrides.h"
#include "deb/load/budget_variant.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/key_path.h"
#include "deb/load/parameters_yaml.h"
#include "deb/load/yaml_reader.h"
#include "deb/units/quantity.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

using load::AtNode;
using load::KeyPath;
using load::ScaleNumbersAt;
using load::SetTextAt;
using load::YamlNode;
using load::YamlReader;

KeyPath ParseKeyPath(const YamlNode& node) {
  return AtNode(node, [&] { return load::ParseKeyPath(node.AsString()); });
}

std::string Assign(YAML::Node n, const KeyPath& steps, const SweepParameter& p, double v) {
  // A budget parameter receives its value as text, with its unit.
  const bool parameter = steps.size() >= 2 && steps[0].is_key && steps[0].key == "parameters";
  if (!p.texts.empty() || parameter) return SetTextAt(n, steps, p.Text(v));
  return ScaleNumbersAt(n, steps, [v](double) { return v; });
}

// A parameter's name on axes and in tables: one line of printable text.
std::string ParseLabel(const YamlNode& node) {
  const std::string label = node.AsString();
  if (const std::string why = ParameterLabelProblem(label); !why.empty()) node.Fail(why);
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
  return load::AtNode(r, [&] { return log ? LogRange(from, to, n) : LinearRange(from, to, n); });
}

// Loads the variants of one sweep file: its text, the parameters' parsed
// key paths and values. Reads only its own copies, so variants load on
// several threads at once; their errors are located in the user's file.
class VariantLoader {
 public:
  VariantLoader(std::string text, std::shared_ptr<const KeyPositions> positions, std::string base_dir,
                SweepSpec spec, std::vector<KeyPath> steps, std::string overrides_note)
      : text_(std::move(text)), positions_(std::move(positions)), base_dir_(std::move(base_dir)),
        spec_(std::move(spec)), steps_(std::move(steps)), rows_(spec_.Variants()),
        overrides_note_(std::move(overrides_note)) {}

  // The budget with nothing assigned and its study keys removed. Each
  // variant starts from a fresh parse of the text, not a YAML::Clone: a
  // clone loses the nodes' positions, which Reached tells aliases apart by.
  YAML::Node BaseCopy() const {
    YAML::Node copy = YAML::Load(text_);
    RemoveStudyKeys(copy);
    return copy;
  }

  Budget Variant(std::size_t i) const;

 private:
  std::string text_;
  std::shared_ptr<const KeyPositions> positions_;
  std::string base_dir_;
  SweepSpec spec_;
  std::vector<KeyPath> steps_;
  std::vector<std::vector<double>> rows_;
  std::string overrides_note_;  // "--set ...", or empty
};

Budget VariantLoader::Variant(std::size_t i) const {
  DEB_DEMAND(i < rows_.size());
  YAML::Node v = BaseCopy();
  for (std::size_t k = 0; k < steps_.size(); ++k) Assign(v, steps_[k], spec_.parameters[k], rows_[i][k]);
  YAML::Emitter emitter;
  emitter << v;
  std::ostringstream note;
  if (!overrides_note_.empty()) note << overrides_note_ << "; ";
  note << "sweep variant " << i + 1 << ":";
  for (std::size_t k = 0; k < steps_.size(); ++k)
    note << (k ? ", " : " ") << spec_.parameters[k].key_path << " = " << spec_.parameters[k].Text(rows_[i][k]);
  return LoadBudgetVariant(emitter.c_str(), positions_, note.str(), base_dir_);
}

SweepBudget Load(const YamlReader& reader, const std::string& base_dir, const std::vector<BudgetOverride>& overrides) {
  const YamlNode root = reader.Root();
  for (const BudgetOverride& o : overrides)
    if (o.key_path == "sweep" || o.key_path.rfind("sweep.", 0) == 0 || o.key_path.rfind("sweep[", 0) == 0)
      throw InputError(reader.name() + ": --set " + o.key_path + "=" + o.value +
                       ": --set changes the budget, not its sweep section; edit the sweep in the file");
  const YamlNode sweep = root.Required("sweep");
  sweep.AllowOnly({"mode", "parameters"});
  SweepBudget out;
  out.text = load::OverriddenText(reader.text(), overrides, reader.name());
  if (auto m = sweep.Optional("mode")) out.spec.mode = load::AtNode(*m, [&] { return ParseSweepMode(m->AsString()); });
  const YamlNode params = sweep.Required("parameters");
  std::vector<KeyPath> steps;
  std::vector<YamlNode> path_nodes;
  // The budget's parameters, by name: a sweep of one gives each value its
  // unit (the sweep's unit:, or the one the parameter is written in).
  const std::shared_ptr<const ParameterSet> budget_parameters =
      root.Has("parameters") ? load::ParseParameters(root.Required("parameters")) : std::make_shared<ParameterSet>();
  const YAML::Node document = reader.LoadCopy();
  for (const YamlNode& p : params.Elements()) {
    p.AllowOnly({"path", "label", "unit", "values", "linear", "log"});
    const YamlNode path = p.Required("path");
    const KeyPath written = ParseKeyPath(path);
    steps.push_back(load::ResolveParameterName(document, written));
    path_nodes.push_back(path);
    SweepParameter param;
    param.key_path = path.AsString();
    if (auto label = p.Optional("label")) param.label = ParseLabel(*label);
    if (auto unit = p.Optional("unit")) {
      param.unit = unit->AsString();
      load::AtNode(*unit, [&] { ValidateUnit(param.unit); });
    }
    param.values = ParseValues(p, &param.texts);
    if (steps.back().size() != written.size() && param.texts.empty()) {
      for (const Parameter& known : budget_parameters->parameters())
        if (known.definition.name == written[0].key) param.value_unit = param.unit.empty() ? known.unit : param.unit;
      if (param.unit.empty()) param.unit = param.value_unit;
    }
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
  const auto loader = std::make_shared<const VariantLoader>(load::OverriddenText(reader.text(), overrides, reader.name()),
                                                            reader.positions(), base_dir, out.spec, steps,
                                                            load::OverridesNote(overrides));
  // Check every path once (with its first value) before any variant loads,
  // on one copy: the assignments change values, never what a path reaches.
  YAML::Node probe = loader->BaseCopy();
  for (std::size_t k = 0; k < steps.size(); ++k) {
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

SweepBudget LoadSweepFile(const std::string& path, const std::vector<BudgetOverride>& overrides) {
  const YamlReader reader = load::ReadBudgetFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return Load(reader, dir.empty() ? "." : dir, overrides);
}

std::vector<double> ParameterValues(const std::string& path, const std::string& key_path,
                                    const std::vector<BudgetOverride>& overrides) {
  const YamlReader reader = load::ReadBudgetFile(path);
  YAML::Node raw = reader.LoadCopy();
  load::ApplyOverrides(raw, overrides, reader.name());
  const KeyPath steps = load::ResolveParameterName(raw, load::ParseKeyPath(key_path));
  if (raw.IsMap()) raw.remove("sweep");
  std::vector<double> values;
  std::vector<std::string> expressions;
  const std::string why = load::MultiplyValuesAt(raw, steps, 1.0, &values, &expressions);
  if (!why.empty()) throw InputError("key path '" + key_path + "' does not reach a number in " + path + ": " + why);
  if (std::none_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) return values;
  // Expressions: their values under the budget's parameters. A parameter
  // itself in the unit of its number if it is one ("5.2e4 N/m": 5.2e4), an
  // expression elsewhere (gains: Kv) as the budget reads it, in SI base units.
  const YamlReader copy = YamlReader::FromString(load::OverriddenText(reader.text(), overrides, reader.name()), path);
  if (!copy.Root().Has("parameters")) return values;
  const std::shared_ptr<const ParameterSet> set = load::ParseParameters(copy.Root().Required("parameters"));
  if (values.size() == 1 && steps.size() >= 2 && steps[0].key == "parameters") {
    for (const Parameter& p : set->parameters())
      if (p.definition.name == steps[1].key) values[0] = p.unit.empty() ? p.value.value : ValueIn(p.value, p.unit);
    return values;
  }
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::isnan(values[i]) && !expressions[i].empty()) values[i] = set->EvaluateText(expressions[i]).value;
  return values;
}

Budget LoadBudgetWithScaledParameter(const std::string& path, const std::string& key_path, double factor,
                                     const std::vector<BudgetOverride>& overrides) {
  const YamlReader reader = load::ReadBudgetFile(path);
  YAML::Node raw = reader.LoadCopy();
  load::ApplyOverrides(raw, overrides, reader.name());
  const KeyPath steps = load::ResolveParameterName(raw, load::ParseKeyPath(key_path));
  RemoveStudyKeys(raw);
  const std::string why = load::MultiplyValuesAt(raw, steps, factor);
  if (!why.empty()) throw InputError("key path '" + key_path + "' does not reach a number in " + path + ": " + why);
  YAML::Emitter emitter;
  emitter << raw;
  std::ostringstream note;
  if (!overrides.empty()) note << load::OverridesNote(overrides) << "; ";
  note << key_path << " x " << factor;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return LoadBudgetVariant(emitter.c_str(), reader.positions(), note.str(), dir.empty() ? "." : dir);
}

SweepBudget LoadSweepText(const std::string& text, const std::string& name, const std::string& base_dir,
                          const std::vector<BudgetOverride>& overrides) {
  return Load(YamlReader::FromString(text, name), base_dir, overrides);
}

std::vector<Budget> LoadSweepVariants(const SweepBudget& sweep, int threads) {
  std::vector<Budget> variants(sweep.variant_count);
  ParallelForEach(variants.size(), [&](std::size_t i) { variants[i] = sweep.variant(i); }, threads);
  return variants;
}

}  // namespace deb
