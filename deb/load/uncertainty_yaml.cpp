#include "deb/load/uncertainty_yaml.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <mutex>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/load/budget_extends.h"
#include "deb/load/budget_overrides.h"
#include "deb/load/budget_variant.h"
#include "deb/load/distributions_yaml.h"
#include "deb/load/key_path.h"
#include "deb/load/parameters_yaml.h"

namespace deb {

namespace {

// Loads the budget at given values of its uncertain parameters: from a fresh
// parse of its text, each value written as text with its unit at the
// parameter's key path, loaded as any budget is.
class UncertaintyVariants {
 public:
  UncertaintyVariants(const std::string& text, std::shared_ptr<const KeyPositions> positions, std::string base_dir,
                      UncertaintySpec spec, std::vector<load::KeyPath> steps, std::string note)
      : document_(YAML::Load(text)), positions_(std::move(positions)), base_dir_(std::move(base_dir)),
        spec_(std::move(spec)), steps_(std::move(steps)), note_(std::move(note)) {
    // A sample is a point: its parameters' distributions (checked once, at
    // the nominal values) and correlations are not part of it.
    document_.remove("correlations");
    for (const UncertainParameter& p : spec_.parameters)
      if (YAML::Node entry = document_["parameters"][p.name]; entry.IsMap()) entry.remove("distribution");
  }

  // A copy of the parsed document (cheaper than parsing the text again),
  // the values written in as text with their units, loaded as any budget.
  Budget Variant(const std::vector<double>& values) const {
    DEB_DEMAND(values.size() == steps_.size());
    YAML::Node v;
    {
      // yaml-cpp does not promise that reading one node from several
      // threads is safe; the copy is a small part of a sample's cost.
      const std::lock_guard<std::mutex> lock(mutex_);
      v = YAML::Clone(document_);
    }
    std::string note = note_;
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      const UncertainParameter& p = spec_.parameters[k];
      const std::string text = NumberText(values[k] / p.unit_si) + (p.unit.empty() ? "" : " " + p.unit);
      const std::string why = load::SetTextAt(v, steps_[k], text);
      DEB_DEMAND(why.empty());
      note += (k ? ", " : " ") + p.name + " = " + text;
    }
    return LoadBudgetVariantNode(v, positions_, note, base_dir_);
  }

 private:
  YAML::Node document_;
  std::shared_ptr<const KeyPositions> positions_;
  std::string base_dir_;
  UncertaintySpec spec_;
  std::vector<load::KeyPath> steps_;
  std::string note_;
  mutable std::mutex mutex_;
};

}  // namespace

UncertaintyBudget LoadUncertaintyFile(const std::string& path, const std::vector<BudgetOverride>& overrides) {
  // The budget as --set changes it, checked whole (its distributions too).
  const Budget checked = LoadBudgetFile(path, overrides);
  const std::string text = load::OverriddenText(load::ReadBudgetFile(path).text(), overrides, path);
  const load::YamlReader reader = load::YamlReader::FromString(text, path);
  const load::YamlNode root = reader.Root();
  const std::shared_ptr<const ParameterSet> parameters =
      root.Has("parameters") ? load::ParseParameters(root.Required("parameters")) : std::make_shared<ParameterSet>();
  UncertaintyBudget out;
  out.name = checked.name;
  out.spec = load::ParseUncertainty(root, *parameters);
  if (out.spec.parameters.empty())
    root.Fail("no parameter has a distribution: give one, e.g. parameters: {k: {value: 5.2e4 N/m, distribution: "
              "{normal: {sigma: 5 %}}}}");
  const YAML::Node document = reader.LoadCopy();
  std::vector<load::KeyPath> steps;
  for (const UncertainParameter& p : out.spec.parameters)
    steps.push_back(load::ResolveParameterName(document, load::ParseKeyPath(p.name)));
  const std::string dir = std::filesystem::path(path).parent_path().string();
  std::string note = load::OverridesNote(overrides);
  note += (note.empty() ? "" : "; ") + std::string("uncertainty sample");
  const auto variants = std::make_shared<const UncertaintyVariants>(text, checked.positions, dir.empty() ? "." : dir,
                                                                    out.spec, steps, note);
  out.variant = [variants](const std::vector<double>& values) { return variants->Variant(values); };
  return out;
}

}  // namespace deb
