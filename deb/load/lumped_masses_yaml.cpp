#include "deb/load/lumped_masses_yaml.h"

#include <algorithm>
#include <tuple>

#include "deb/core/limits.h"
#include "deb/core/suggest.h"
#include "deb/models/lumped_masses.h"

namespace deb::load {
namespace {

// The index of mass `name` (LumpedMasses::kGround for "ground" where allowed).
int MassIndex(const YamlNode& at, const std::vector<std::string>& names, bool ground_allowed) {
  const std::string name = at.AsString();
  if (name == "ground") {
    if (!ground_allowed) at.Fail("'ground' cannot be named here: name a mass");
    return LumpedMasses::kGround;
  }
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::vector<std::string> all = names;
    if (ground_allowed) all.push_back("ground");
    std::string list;
    for (const std::string& n : all) list += (list.empty() ? "" : ", ") + n;
    at.Fail("no mass '" + name + "'" + DidYouMean(name, all) + " (the masses: " + list + ")");
  }
  return static_cast<int>(it - names.begin());
}

// `a` or `[a, b]`: (a, b), b = kGround when one name is given.
std::pair<int, int> Ends(const YamlNode& at, const std::vector<std::string>& names, bool ground_first,
                         const char* what) {
  if (!at.IsSequence()) return {MassIndex(at, names, ground_first), LumpedMasses::kGround};
  const std::vector<YamlNode> e = at.Elements();
  if (e.size() != 2) at.Fail(std::string(what) + ": give one mass or two, [a, b]");
  const int a = MassIndex(e[0], names, ground_first), b = MassIndex(e[1], names, true);
  if (a == b) e[1].Fail(std::string(what) + ": the same mass twice");
  return {a, b};
}

// The entry's name, added to `seen` (which must not hold it).
void Name(const YamlNode& entry, std::vector<std::string>& seen) {
  const YamlNode n = entry.Required("name");
  const std::string name = n.AsString();
  if (std::find(seen.begin(), seen.end(), name) != seen.end()) n.Fail("name '" + name + "' is used twice");
  seen.push_back(name);
}

}  // namespace

std::set<std::string> LumpedMassesKeys() { return {"masses", "couplings", "inputs", "outputs"}; }

LumpedMassesPath ParseLumpedMasses(const YamlNode& node) {
  LumpedMasses model;
  const YamlNode masses = node.Required("masses");
  if (!masses.IsMap()) masses.Fail("give the masses as a map, name: mass (e.g. {table: 400 kg})");
  const std::vector<std::string> names = masses.Keys();
  if (names.empty()) masses.Fail("give at least one mass");
  if (names.size() > static_cast<std::size_t>(limits::kMaxStates / 2))
    masses.Fail(std::to_string(names.size()) + " masses give " + std::to_string(2 * names.size()) +
                " states, more than the " + std::to_string(limits::kMaxStates) + " a path may have");
  for (const std::string& name : names) {
    const YamlNode m = masses.Required(name);
    if (name == "ground") m.Fail("'ground' is the moving reference, not a mass; name the mass otherwise");
    model.names.push_back(name);
    model.mass_kg.push_back(m.AsPositiveIn("kg"));
  }

  const YamlNode couplings = node.Required("couplings");
  for (const YamlNode& c : couplings.Elements()) {
    c.AllowOnly({"between", "k", "c"});
    LumpedMasses::Coupling j;
    if (!c.Required("between").IsSequence()) c.Required("between").Fail("between: name both ends, [a, b] (one may be ground)");
    std::tie(j.a, j.b) = Ends(c.Required("between"), names, true, "between");
    if (c.Has("k")) j.k_n_per_m = c.Required("k").AsNonNegativeIn("N/m");
    if (c.Has("c")) j.c_n_s_per_m = c.Required("c").AsNonNegativeIn("N.s/m");
    if (j.k_n_per_m == 0.0 && j.c_n_s_per_m == 0.0) c.Fail("a coupling needs k (N/m), c (N s/m) or both, not zero");
    model.couplings.push_back(j);
  }

  LumpedMassesPath p;
  std::vector<LumpedMasses::Input> inputs;
  for (const YamlNode& in : node.Required("inputs").Elements()) {
    in.AllowOnly({"name", "force", "ground"});
    Name(in, p.input_names);
    const bool force = in.Has("force"), ground = in.Has("ground");
    if (force == ground) in.Fail("give 'force: mass' (or [mass, reaction]) or 'ground: acceleration'");
    LumpedMasses::Input i;
    if (force) {
      std::tie(i.on, i.reaction) = Ends(in.Required("force"), names, false, "force");
      p.input_si_units.push_back("N");
    } else {
      const YamlNode g = in.Required("ground");
      if (g.AsString() != "acceleration")
        g.Fail("the ground moves by its acceleration ('ground: acceleration'; a velocity or displacement source "
               "is converted to it by its unit)");
      p.input_si_units.push_back("m/s^2");
    }
    inputs.push_back(i);
  }
  std::vector<LumpedMasses::Output> outputs;
  for (const YamlNode& out : node.Required("outputs").Elements()) {
    out.AllowOnly({"name", "displacement", "velocity"});
    Name(out, p.output_names);
    const bool displacement = out.Has("displacement"), velocity = out.Has("velocity");
    if (displacement == velocity) out.Fail("give 'displacement: mass' or 'velocity: mass' (or [mass, relative to])");
    LumpedMasses::Output o;
    o.velocity = velocity;
    std::tie(o.of, o.relative_to) = Ends(out.Required(velocity ? "velocity" : "displacement"), names, false,
                                         velocity ? "velocity" : "displacement");
    p.output_si_units.push_back(velocity ? "m/s" : "m");
    outputs.push_back(o);
  }
  if (inputs.empty()) node.Required("inputs").Fail("give at least one input");
  if (outputs.empty()) node.Required("outputs").Fail("give at least one output");
  p.system = AtNode(node, [&] { return model.Realise(inputs, outputs); });
  return p;
}

}  // namespace deb::load
