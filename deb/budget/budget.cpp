#include "deb/budget/budget.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>

#include "deb/core/file_name.h"
#include "deb/budget/groups.h"
#include "deb/budget/output_covariance.h"
#include "deb/budget/path_composition.h"
#include "deb/core/at_key_path.h"
#include "deb/core/error.h"
#include "deb/core/suggest.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

std::string Indexed(const char* list, std::size_t i) {
  return std::string(list) + "[" + std::to_string(i) + "]";
}

template <typename T>
void RequireUniqueNames(const std::vector<T>& items, const char* list) {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name.empty()) throw InputError(Indexed(list, i) + ".name", "a name is required");
    for (char ch : items[i].name)
      if (!IsFileNameCharacter(ch))
        throw InputError(Indexed(list, i) + ".name", "name '" + items[i].name +
                                                         "' may contain only letters, digits, '_', '-' and '.'");
    if (items[i].name == "." || items[i].name == "..")
      throw InputError(Indexed(list, i) + ".name", "name '" + items[i].name + "' is not a name (it names a file)");
    if (!seen.insert(items[i].name).second)
      throw InputError(Indexed(list, i) + ".name",
                       "name '" + items[i].name + "' is used twice in " + list);
  }
}

// Re-throws an InputError without a key path under `key`.
template <typename F>
void AtKey(const std::string& key, F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    if (!e.key_path().empty()) throw;
    throw InputError(key, e.what());
  }
}

}  // namespace

GridSpec ExplicitGrid(const FrequencyGrid& grid) {
  GridSpec spec;
  spec.kind = GridKind::kExplicit;
  spec.f_hz = grid.f_hz();
  spec.panel_starts = grid.panel_starts();
  return spec;
}

InputError Budget::Locate(const InputError& e) const { return positions ? positions->Located(e) : e; }

namespace {

// The element of `items` named n; else an InputError at `list` naming the nearest.
template <typename T>
const T& Named(const std::vector<T>& items, const std::string& n, const char* list, const char* what) {
  std::vector<std::string> names;
  for (const T& item : items) {
    if (item.name == n) return item;
    names.push_back(item.name);
  }
  throw InputError(list, std::string("the budget has no ") + what + " named '" + n + "'" + DidYouMean(n, names));
}

}  // namespace

const Source& Budget::FindSource(const std::string& n) const { return Named(sources, n, "sources", "source"); }

const Path& Budget::FindPath(const std::string& n) const { return Named(paths, n, "paths", "path"); }

namespace {

// outputs[i]: its unit, requirements and weighting.
void ValidateOutput(const Budget& budget, std::size_t i) {
  const Output& o = budget.outputs[i];
  const std::string key = Indexed("outputs", i);
  AtKey(key + ".unit", [&] { ValidateUnit(o.unit); });
  if (o.rms_max && !(std::isfinite(*o.rms_max) && *o.rms_max > 0.0)) {
    std::ostringstream os;
    os << "rms_max must be finite and > 0, got " << *o.rms_max;
    throw InputError(key + ".rms_max", os.str());
  }
  for (std::size_t b = 0; b < o.band_requirements.size(); ++b) {
    const BandRequirement& r = o.band_requirements[b];
    if (!(r.lo_hz > 0.0 && r.hi_hz > r.lo_hz && std::isfinite(r.hi_hz) && std::isfinite(r.rms_max) &&
          r.rms_max > 0.0)) {
      std::ostringstream os;
      os << "band requirement [" << r.lo_hz << ", " << r.hi_hz << "] Hz, rms_max " << r.rms_max
         << ": need 0 < lo_hz < hi_hz and a finite rms_max > 0";
      throw InputError(key + ".band_requirements[" + std::to_string(b) + "]", os.str());
    }
  }
  if (o.weighting) {
    if (o.weighting->system.inputs() != 1 || o.weighting->system.outputs() != 1)
      throw InputError(key + ".weighting", "a weighting must be SISO (1 input, 1 output)");
    AtKey(key + ".weighting.unit", [&] { ValidateUnit(o.weighting->unit); });
  }
}

// contributors[i]: its source and path exist, and fit each other and every output.
void ValidateContributor(const Budget& budget, std::size_t i) {
  const Contributor& c = budget.contributors[i];
  const std::string key = Indexed("contributors", i);
  // "total" names the sum of all contributors in every table, CSV column and plot.
  if (c.name == "total")
    throw InputError(key + ".name", "contributor name 'total' is reserved for the sum of all contributors");
  if (!c.group.empty()) AtKeyPath(key + ".group", [&] { GroupSegments(c.group); });
  std::vector<std::string> source_names, path_names;
  for (const auto& s : budget.sources) source_names.push_back(s.name);
  for (const auto& p : budget.paths) path_names.push_back(p.name);
  if (std::find(source_names.begin(), source_names.end(), c.source) == source_names.end())
    throw InputError(key + ".source", "no source named '" + c.source + "'" + DidYouMean(c.source, source_names));
  if (std::find(path_names.begin(), path_names.end(), c.path) == path_names.end())
    throw InputError(key + ".path", "no path named '" + c.path + "'" + DidYouMean(c.path, path_names));
  const Source& s = budget.FindSource(c.source);
  const Path& full = budget.FindPath(c.path);
  std::optional<Path> selected;  // the inputs the contributor drives (`inputs:`)
  if (!c.inputs.empty())
    AtKeyPath(key + ".inputs", [&] { selected = SelectPathInputs(full, c.inputs); });
  std::optional<Path> combined;  // with a row per output that combines signals
  if (std::any_of(budget.outputs.begin(), budget.outputs.end(), [](const Output& o) { return !o.combination.empty(); }))
    combined = WithOutputCombinations(selected ? *selected : full, budget.outputs);
  const Path& p = combined ? *combined : selected ? *selected : full;
  if (s.channels() != p.system.inputs()) {
    std::ostringstream os;
    os << "source '" << s.name << "' has " << s.channels() << " channel(s) but ";
    if (selected)
      os << "'inputs' names " << p.system.inputs() << " input(s) of path '" << p.name << "'";
    else
      os << "path '" << p.name << "' has " << p.system.inputs() << " input(s)"
         << (s.channels() < p.system.inputs() ? " (name the inputs it drives: inputs: [...])" : "");
    throw InputError(selected ? key + ".inputs" : key, os.str());
  }
  for (std::size_t k = 0; k < p.input_units.size(); ++k) {
    AtKey(key, [&] {
      try {
        ConvertUnit(s.unit, p.input_units[k]);
      } catch (const InputError& e) {
        throw InputError("source '" + s.name + "' (unit " + s.unit + ") does not fit input '" +
                         p.input_names[k] + "' of path '" + p.name + "' (unit " +
                         p.input_units[k] + "): " + e.what());
      }
    });
  }
  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    const Output& out = budget.outputs[o];
    const int row = p.OutputIndex(out.signal);
    if (row < 0)
      throw InputError(Indexed("outputs", o) + ".signal",
                       "output '" + out.name + "' reads signal '" + out.signal + "'" +
                           DidYouMean(out.signal, p.output_names) + ", which path '" + p.name +
                           "' (contributor '" + c.name + "') does not have");
    const std::string from = out.weighting ? UnitProduct(p.output_units[row], out.weighting->unit)
                                           : p.output_units[row];
    AtKey(Indexed("outputs", o) + ".unit", [&] {
      try {
        ConvertUnit(from, out.unit);
      } catch (const InputError& e) {
        throw InputError("output '" + out.name + "' in " + out.unit + " cannot be formed from signal '" +
                         out.signal + "' of path '" + p.name + "' in " + from + ": " + e.what());
      }
    });
  }
}

}  // namespace

void Budget::Validate() const {
  if (name.empty()) throw InputError("name", "the budget needs a name");
  RequireUniqueNames(sources, "sources");
  RequireUniqueNames(paths, "paths");
  RequireUniqueNames(contributors, "contributors");
  RequireUniqueNames(outputs, "outputs");
  if (contributors.empty()) throw InputError("contributors", "at least one contributor is required");
  if (outputs.empty()) throw InputError("outputs", "at least one output is required");

  for (std::size_t i = 0; i < sources.size(); ++i) {
    const Source& s = sources[i];
    const std::string key = Indexed("sources", i);
    DEB_DEMAND(s.spectrum != nullptr);
    AtKey(key + ".unit", [&] { ValidateUnit(s.unit); });
    if (static_cast<int>(s.channel_names.size()) != s.channels())
      throw InputError(key + ".channels", "source '" + s.name + "' has " +
                                              std::to_string(s.channels()) + " channels but " +
                                              std::to_string(s.channel_names.size()) + " names");
  }
  for (std::size_t i = 0; i < paths.size(); ++i) {
    AtKey(Indexed("paths", i), [&] {
      paths[i].Validate();
      for (const auto& u : paths[i].input_units) ValidateUnit(u);
      for (const auto& u : paths[i].output_units) ValidateUnit(u);
    });
  }
  for (std::size_t i = 0; i < outputs.size(); ++i) ValidateOutput(*this, i);
  for (std::size_t i = 0; i < contributors.size(); ++i) ValidateContributor(*this, i);
  ValidateCovarianceRequest(*this);
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const Band& b = bands[i];
    if (!(std::isfinite(b.lo_hz) && std::isfinite(b.hi_hz) && b.lo_hz > 0.0 && b.hi_hz > b.lo_hz)) {
      std::ostringstream os;
      os << "band [" << b.lo_hz << ", " << b.hi_hz << "] Hz is empty or invalid; need 0 < lo_hz < hi_hz";
      throw InputError(Indexed("bands", i), os.str());
    }
  }
}

Path WithOutputCombinations(const Path& path, const std::vector<Output>& outputs) {
  Path p = path;
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    if (outputs[o].combination.empty()) continue;
    try {
      p = AddCombinedOutput(p, outputs[o].name, outputs[o].combination);
    } catch (const InputError& e) {
      const std::string key = Indexed("outputs", o) + ".combination" + e.key_path();
      throw InputError(key, "output '" + outputs[o].name + "' (path '" + path.name + "'): " + e.message());
    }
  }
  return p;
}

std::string ContributorPathKey(const Contributor& c) {
  if (c.inputs.empty()) return c.path;
  std::string key = c.path + "(";
  for (std::size_t i = 0; i < c.inputs.size(); ++i) key += (i ? ", " : "") + c.inputs[i];
  return key + ")";
}

}  // namespace deb
