#include "deb/load/parameters_yaml.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace deb::load {

std::shared_ptr<const ParameterSet> ParseParameters(const YamlNode& node) {
  std::vector<ParameterDefinition> definitions;
  std::vector<YamlNode> values;
  std::vector<std::optional<YamlNode>> units;
  for (const std::string& name : node.Keys()) {
    const YamlNode entry = node.Required(name);
    ParameterDefinition d;
    d.name = name;
    d.key_path = entry.key();
    if (entry.IsMap()) {
      // distribution: distributions_yaml.h; min, max: design_bounds_yaml.h
      entry.AllowOnly({"value", "description", "unit", "distribution", "min", "max"});
      values.push_back(entry.Required("value"));
      if (auto text = entry.Optional("description")) d.description = text->AsString();
      units.push_back(entry.Optional("unit"));
      if (units.back()) d.unit = units.back()->AsString();
    } else {
      values.push_back(entry);
      units.emplace_back();
    }
    if (!values.back().IsScalar()) values.back().Fail("a parameter's value is a number with its unit or an expression");
    d.expression = values.back().AsString();
    definitions.push_back(std::move(d));
  }
  try {
    return std::make_shared<const ParameterSet>(ParameterSet::Evaluate(definitions));
  } catch (const InputError& e) {
    for (std::size_t i = 0; i < definitions.size(); ++i) {
      if (units[i] && e.key_path() == definitions[i].key_path + ".unit") units[i]->Fail(e.message());
      if (e.key_path() != definitions[i].key_path) continue;
      if (const auto* expression = dynamic_cast<const ExpressionError*>(&e))
        values[i].FailInText(expression->column_in_text(), e.message());
      values[i].Fail(e.message());
    }
    throw;
  }
}

}  // namespace deb::load
