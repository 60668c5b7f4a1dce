// deb.Budget and the loaders behind deb.load (python/deb/_load.py decides
// whether its argument is a file, a text or a dict).
#include <pybind11/stl.h>

#include <utility>
#include <vector>

#include "deb/budget/budget_outline.h"
#include "deb/load/budget_yaml.h"
#include "python/src/bindings.h"

namespace deb::python {

std::vector<BudgetOverride> ToOverrides(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::vector<BudgetOverride> out;
  for (const auto& [key_path, value] : pairs) out.push_back(ParseBudgetOverride(key_path + "=" + value));
  return out;
}

namespace {

template <typename T>
std::vector<std::string> NamesOf(const std::vector<T>& items) {
  std::vector<std::string> names;
  for (const T& item : items) names.push_back(item.name);
  return names;
}

}  // namespace

void BindBudget(py::module_& m) {
  py::class_<LoadedBudget>(m, "Budget", "A loaded, validated budget (deb.load); evaluate it with deb.evaluate")
      .def_property_readonly("name", [](const LoadedBudget& b) { return b.budget->name; })
      .def_property_readonly("description", [](const LoadedBudget& b) { return b.budget->description; })
      .def_property_readonly(
          "file", [](const LoadedBudget& b) { return b.file.empty() ? py::object(py::none()) : py::str(b.file); },
          "The budget file, or None for a budget loaded from a text or a dict")
      .def_property_readonly(
          "text", [](const LoadedBudget& b) { return b.text ? py::object(py::str(*b.text)) : py::none(); },
          "The YAML text it was loaded from (a text or a dict), or None for a file")
      .def_property_readonly("sources", [](const LoadedBudget& b) { return NamesOf(b.budget->sources); })
      .def_property_readonly("paths", [](const LoadedBudget& b) { return NamesOf(b.budget->paths); })
      .def_property_readonly("contributors", [](const LoadedBudget& b) { return NamesOf(b.budget->contributors); })
      .def_property_readonly("outputs", [](const LoadedBudget& b) { return NamesOf(b.budget->outputs); })
      .def_property_readonly(
          "parameters",
          [](const LoadedBudget& b) {
            py::dict out;
            for (const ParameterOutline& p : OutlineOf(b.budget->parameters))
              out[py::str(p.name)] = py::make_tuple(p.value, p.unit);
            return out;
          },
          "{name: (value, unit)} of the budget's parameters")
      .def("__repr__", [](const LoadedBudget& b) {
        return "<deb.Budget '" + b.budget->name + "': " + std::to_string(b.budget->contributors.size()) +
               " contributors, " + std::to_string(b.budget->outputs.size()) + " outputs>";
      });

  m.def(
      "load_file",
      [](const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides) {
        const std::vector<BudgetOverride> o = ToOverrides(overrides);
        py::gil_scoped_release release;
        return LoadedBudget{std::make_shared<const Budget>(LoadBudgetFile(path, o)), path, std::nullopt};
      },
      py::arg("path"), py::arg("overrides"));
  m.def(
      "load_text",
      [](const std::string& text, const std::string& name, const std::string& base_dir,
         const std::vector<std::pair<std::string, std::string>>& overrides) {
        const std::vector<BudgetOverride> o = ToOverrides(overrides);
        py::gil_scoped_release release;
        return LoadedBudget{std::make_shared<const Budget>(LoadBudgetText(text, name, base_dir, o)), "", text};
      },
      py::arg("text"), py::arg("name"), py::arg("base_dir"), py::arg("overrides"));
}

}  // namespace deb::python
