#include "deb/load/design_bounds_yaml.h"

#include "deb/core/number_text.h"
#include "deb/load/distributions_yaml.h"
#include "deb/units/quantity.h"

namespace deb::load {

std::vector<DesignVariable> ParseDesignBounds(const YamlNode& root, const ParameterSet& parameters) {
  std::vector<DesignVariable> out;
  const auto section = root.Optional("parameters");
  if (!section) return out;
  for (const Parameter& p : parameters.parameters()) {
    const YamlNode entry = section->Required(p.definition.name);
    if (!entry.IsMap() || (!entry.Has("min") && !entry.Has("max"))) continue;
    if (entry.Has("min") != entry.Has("max"))
      entry.Fail(std::string("a design variable has both bounds: give ") + (entry.Has("min") ? "max" : "min") +
                 " as well");
    if (p.derived)
      entry.Required("min").Fail(p.definition.name + " is derived from other parameters ('" + p.definition.expression +
                                 "'): give the bounds to the parameters it is made of");
    DesignVariable v;
    v.name = p.definition.name;
    v.unit = p.unit;
    v.unit_si = p.unit.empty() ? 1.0 : AtNode(entry, [&] { return QuantityOf(1.0, p.unit).value; });
    v.nominal = p.value.value;
    v.min = ParameterValueOf(entry.Required("min"), p, v.unit_si, parameters, false);
    v.max = ParameterValueOf(entry.Required("max"), p, v.unit_si, parameters, false);
    const auto shown = [&](double si) { return NumberText(si / v.unit_si) + (v.unit.empty() ? "" : " " + v.unit); };
    if (!(v.min < v.max)) entry.Required("max").Fail("max " + shown(v.max) + " must be above min " + shown(v.min));
    if (v.nominal < v.min || v.nominal > v.max)
      entry.Required("value").Fail("the value " + shown(v.nominal) + " lies outside [min, max] = [" + shown(v.min) +
                                   ", " + shown(v.max) + "]");
    out.push_back(v);
  }
  return out;
}

}  // namespace deb::load
