#include "deb/load/budget_yaml.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>

#include "deb/core/file_name.h"
#include "deb/core/input_file.h"
#include "deb/load/budget_extends.h"
#include "deb/load/budget_overrides.h"
#include "deb/load/parameters_yaml.h"
#include "deb/load/budget_variant.h"
#include "deb/load/design_bounds_yaml.h"
#include "deb/load/distributions_yaml.h"
#include "deb/load/path_yaml.h"
#include "deb/load/source_yaml.h"
#include "deb/load/yaml_reader.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

using load::YamlNode;
using load::YamlReader;

GridSpec ParseGrid(const YamlNode& node) {
  node.AllowOnly({"type", "min_hz", "max_hz", "points", "points_per_decade", "points_per_resonance",
                  "resonance_flank_points_per_decade", "max_refined_zeta", "f_hz"});
  GridSpec g;
  if (auto t = node.Optional("type")) g.kind = load::AtNode(*t, [&] { return ParseGridKind(t->AsString()); });
  auto& o = g.auto_options;
  const auto min = node.Optional("min_hz"), max = node.Optional("max_hz");
  if (min) o.min_hz = min->AsPositive();
  if (max) o.max_hz = max->AsPositive();
  if (min.has_value() != max.has_value())
    node.Fail("give both min_hz and max_hz, or neither (the automatic grid then covers 0.1-1000 Hz within the measured "
               "data and every band)");
  g.range_given = min.has_value();
  if (g.kind == GridKind::kLog || g.kind == GridKind::kLinear) {
    if (!g.range_given) node.Fail("a " + ToString(g.kind) + " grid needs min_hz and max_hz");
    const YamlNode points = node.Required("points");
    g.points = points.AsInt();
    const std::string what = ToString(g.kind) + " grid";
    load::AtNode(points, [&] { FrequencyGrid::CheckPoints(g.points, what.c_str()); });
    load::AtNode(node, [&] { FrequencyGrid::CheckRange(o.min_hz, o.max_hz, what.c_str()); });
  } else if (node.Has("points")) {
    node.Required("points").Fail("'points' applies to log and linear grids only");
  }
  if (g.kind == GridKind::kExplicit) {
    const YamlNode f = node.Required("f_hz");
    g.f_hz = f.AsDoubles();
    load::AtNode(f, [&] { FrequencyGrid check(g.f_hz); });
  } else if (node.Has("f_hz")) {
    node.Required("f_hz").Fail("'f_hz' applies to explicit grids only");
  }
  if (auto v = node.Optional("points_per_decade")) o.points_per_decade = v->AsInt();
  if (auto v = node.Optional("points_per_resonance")) o.points_per_resonance = v->AsInt();
  if (auto v = node.Optional("resonance_flank_points_per_decade"))
    v->Fail("resonance_flank_points_per_decade is no longer used: the automatic grid widens its panels in "
            "proportion to the distance from each pole; points_per_resonance sets both");
  if (auto v = node.Optional("max_refined_zeta")) o.max_refined_zeta = v->AsDouble();
  if (g.kind == GridKind::kAuto && g.range_given) load::AtNode(node, [&] { o.Validate(); });
  else if (g.kind == GridKind::kAuto) {
    AutoGridOptions check = o;
    check.min_hz = 0.1;
    check.max_hz = 1000.0;
    load::AtNode(node, [&] { check.Validate(); });
  }
  return g;
}

Output ParseOutput(const YamlNode& node, const std::string& base_dir) {
  node.AllowOnly({"name", "signal", "unit", "weighting", "metric", "rms_max", "band_requirements", "references",
                  "combination", "description"});
  Output o;
  o.name = node.Required("name").AsString();
  o.signal = node.Has("signal") ? node.Required("signal").AsString() : o.name;
  o.unit = node.Required("unit").AsString();
  if (auto w = node.Optional("weighting")) o.weighting = load::ParseWeighting(*w);
  if (auto m = node.Optional("metric")) {
    m->AllowOnly({"type", "window_s"});
    const YamlNode type = m->Required("type");
    OutputMetric metric;
    metric.type = load::AtNode(type, [&] { return ParseMetricType(type.AsString()); });
    metric.window_s = m->Required("window_s").AsPositive();
    o.metric = metric;
  }
  if (auto r = node.Optional("rms_max")) o.rms_max = r->AsPositive();
  if (auto list = node.Optional("band_requirements"))
    for (const auto& b : list->Elements()) {
      b.AllowOnly({"lo_hz", "hi_hz", "rms_max"});
      BandRequirement q{b.Required("lo_hz").AsPositive(), b.Required("hi_hz").AsPositive(),
                        b.Required("rms_max").AsPositive()};
      if (!(q.hi_hz > q.lo_hz)) {
        std::ostringstream os;
        os << "band [" << q.lo_hz << ", " << q.hi_hz << "] Hz is empty; need lo_hz < hi_hz";
        b.Fail(os.str());
      }
      o.band_requirements.push_back(q);
    }
  if (auto comb = node.Optional("combination")) {
    if (node.Has("signal"))
      node.Required("signal").Fail("give 'signal' or 'combination', not both: a combination is its own signal");
    if (!comb->IsMap()) comb->Fail("a combination is a map signal: weight, e.g. {x_dot: 1, beta_dot: -210 mm}");
    for (const std::string& signal : comb->Keys()) {
      const YamlNode w = comb->Required(signal);
      SignalTerm t;
      t.signal = signal;
      // "-210 mm": a number, then its unit; a plain number is dimensionless.
      const std::string text = w.AsString();
      const std::size_t space = text.find_first_of(" \t");
      const std::string number = text.substr(0, space);
      char* end = nullptr;
      t.weight = std::strtod(number.c_str(), &end);
      if (number.empty() || !end || *end != '\0' || !std::isfinite(t.weight))
        w.Fail("weight '" + text + "' is not a number with an optional unit, e.g. -210 mm");
      if (space != std::string::npos) t.unit = text.substr(text.find_first_not_of(" \t", space));
      load::AtNode(w, [&] { ValidateUnit(t.unit); });
      o.combination.push_back(t);
    }
    o.signal = o.name;
  }
  if (auto refs = node.Optional("references"))
    for (const auto& r : refs->Elements()) {
      Source ref = load::ParseSource(r, base_dir);
      if (ref.channels() != 1)
        r.Fail("a reference is one measured signal of the output: it has " + std::to_string(ref.channels()) +
               " channels (select one with columns: [...])");
      const YamlNode unit = r.Has("unit") ? r.Required("unit") : r;
      load::AtNode(unit, [&] { ConvertUnit(ref.unit, o.unit); });
      o.references.push_back(std::move(ref));
    }
  return o;
}

Contributor ParseContributor(const YamlNode& node) {
  node.AllowOnly({"name", "source", "path", "inputs", "group", "breakdown", "exact", "description"});
  Contributor c;
  c.name = node.Required("name").AsString();
  c.source = node.Required("source").AsString();
  c.path = node.Required("path").AsString();
  if (auto group = node.Optional("group")) c.group = group->AsString();
  if (auto breakdown = node.Optional("breakdown")) {
    if (breakdown->AsString() != "channels")
      breakdown->Fail("breakdown '" + breakdown->AsString() + "': the one breakdown is 'channels' (the part of each "
                      "source channel)");
    c.breakdown_channels = true;
  }
  if (auto inputs = node.Optional("inputs")) {
    c.inputs = inputs->AsStrings();
    if (c.inputs.empty()) inputs->Fail("name at least one input of the path, or leave 'inputs' out to drive them all");
  }
  if (auto e = node.Optional("exact")) c.exact = load::AtNode(*e, [&] { return ParseExactVariance(e->AsString()); });
  return c;
}

Band ParseBand(const YamlNode& node) {
  Band b;
  if (node.IsSequence()) {
    const auto v = node.AsDoubles();
    if (v.size() != 2) node.Fail("a band is [lo_hz, hi_hz], got " + std::to_string(v.size()) + " numbers");
    b = {v[0], v[1]};
  } else {
    node.AllowOnly({"lo_hz", "hi_hz"});
    b = {node.Required("lo_hz").AsDouble(), node.Required("hi_hz").AsDouble()};
  }
  if (!(b.lo_hz > 0.0 && b.hi_hz > b.lo_hz)) {
    std::ostringstream os;
    os << "band [" << b.lo_hz << ", " << b.hi_hz << "] Hz is empty or invalid; need 0 < lo_hz < hi_hz";
    node.Fail(os.str());
  }
  return b;
}

Budget Load(YamlReader reader, const std::string& base_dir) {
  const YamlNode root = reader.Root();
  // sweep: read by deb sweep (deb/load/sweep_yaml.h); a run evaluates the budget as written.
  // correlations and the parameters' distributions and bounds: read by deb
  // uncertainty and deb optimise (deb/load/distributions_yaml.h,
  // design_bounds_yaml.h), checked here; a run uses the values.
  root.AllowOnly({"name", "description", "parameters", "correlations", "grid", "sources", "paths", "contributors",
                  "outputs", "bands", "covariance", "sweep"});
  if (auto parameters = root.Optional("parameters")) reader.SetParameters(load::ParseParameters(*parameters));
  const std::size_t uncertain = load::ParseUncertainty(root, reader.parameters()).parameters.size();
  load::ParseDesignBounds(root, reader.parameters());
  Budget b;
  b.uncertain_parameters = uncertain;
  b.parameters = reader.parameters().parameters();
  b.source_file = reader.name();
  b.positions = reader.positions();
  b.name = root.Required("name").AsString();
  for (char ch : b.name)
    if (!IsFileNameCharacter(ch))
      root.Required("name").Fail("budget name '" + Excerpt(b.name) +
                                 "' may contain only letters, digits, '_', '-' and '.' (it names the report directory)");
  if (b.name == "." || b.name == "..")
    root.Required("name").Fail("budget name '" + Excerpt(b.name) + "' is not a name: it names the report directory");
  if (auto d = root.Optional("description")) b.description = d->AsString();
  b.has_sweep = root.Optional("sweep").has_value();
  if (auto g = root.Optional("grid")) b.grid = ParseGrid(*g);
  load::PathContext paths(base_dir);
  for (const auto& n : root.Required("sources").Elements()) b.sources.push_back(load::ParseSource(n, base_dir));
  for (const auto& n : root.Required("paths").Elements())
    for (Path& p : paths.Parse(n)) b.paths.push_back(std::move(p));
  b.models = paths.models();
  for (const auto& n : root.Required("contributors").Elements()) b.contributors.push_back(ParseContributor(n));
  for (const auto& n : root.Required("outputs").Elements()) b.outputs.push_back(ParseOutput(n, base_dir));
  if (auto bands = root.Optional("bands"))
    for (const auto& n : bands->Elements()) b.bands.push_back(ParseBand(n));
  if (auto covariance = root.Optional("covariance")) {
    if (!covariance->IsSequence())
      covariance->Fail("covariance lists the names of 2 or more outputs, e.g. covariance: [x, y]");
    for (const auto& n : covariance->Elements()) b.covariance.push_back(n.AsString());
  }
  try {
    b.Validate();
  } catch (const InputError& e) {
    if (!e.located()) throw InputError(InputLocation{reader.name(), 0, 0, ""}, e.message());
    throw b.Locate(e);
  }
  return b;
}

}  // namespace

Budget LoadBudgetFile(const std::string& path) {
  const YamlReader reader = load::ReadBudgetFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return Load(reader, dir.empty() ? "." : dir);
}

Budget LoadBudgetFile(const std::string& path, const std::vector<BudgetOverride>& overrides) {
  if (overrides.empty()) return LoadBudgetFile(path);
  const YamlReader reader = load::ReadBudgetFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return LoadBudgetVariant(load::OverriddenText(reader.text(), overrides, reader.name()), reader.positions(),
                           load::OverridesNote(overrides), dir.empty() ? "." : dir);
}

namespace {

// A variant read by `reader`: its errors located by the original's positions.
Budget LoadVariant(const YamlReader& reader, const std::shared_ptr<const KeyPositions>& original,
                   const std::string& note, const std::string& base_dir) {
  try {
    Budget b = Load(reader, base_dir);
    b.positions = original;
    return b;
  } catch (const InputError& e) {
    // Located in the written-out copy, whose positions mean nothing to the user.
    if (e.key_path().empty()) throw;
    throw original->Located(InputError(e.key_path(), e.message()), note);
  }
}

}  // namespace

void RemoveStudyKeys(YAML::Node& root) {
  if (!root.IsMap()) return;
  for (const char* key : {"sweep", "correlations"}) root.remove(key);
  if (YAML::Node parameters = root["parameters"]; parameters.IsMap())
    for (auto entry : parameters)
      if (entry.second.IsMap())
        for (const char* key : {"distribution", "min", "max"}) entry.second.remove(key);
}

Budget LoadBudgetVariant(const std::string& text, const std::shared_ptr<const KeyPositions>& original,
                         const std::string& note, const std::string& base_dir) {
  return LoadVariant(YamlReader::FromString(text, original->file() + " (" + note + ")"), original, note, base_dir);
}

Budget LoadBudgetVariantNode(const YAML::Node& root, const std::shared_ptr<const KeyPositions>& original,
                             const std::string& note, const std::string& base_dir) {
  return LoadVariant(YamlReader::FromChecked(root, original->file() + " (" + note + ")"), original, note, base_dir);
}

Budget LoadBudgetText(const std::string& text, const std::string& name, const std::string& base_dir) {
  return Load(YamlReader::FromString(text, name), base_dir);
}

Budget LoadBudgetText(const std::string& text, const std::string& name, const std::string& base_dir,
                      const std::vector<BudgetOverride>& overrides) {
  if (overrides.empty()) return LoadBudgetText(text, name, base_dir);
  // Parsed first, so that the overrides meet a valid document and their
  // errors are located in the text as given.
  const YamlReader reader = YamlReader::FromString(text, name);
  return LoadBudgetVariant(load::OverriddenText(reader.text(), overrides, reader.name()), reader.positions(),
                           load::OverridesNote(overrides), base_dir);
}

}  // namespace deb
