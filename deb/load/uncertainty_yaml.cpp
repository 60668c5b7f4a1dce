#include "deb/load/uncertainty_yaml.h"

#include "deb/load/distributions_yaml.h"
#include "deb/load/parameter_variants.h"

namespace deb {

UncertaintyBudget LoadUncertaintyFile(const std::string& path, const std::vector<BudgetOverride>& overrides) {
  const load::StudyBudget budget = load::ReadStudyBudget(path, overrides);
  const load::YamlNode root = budget.reader->Root();
  UncertaintyBudget out;
  out.name = budget.checked.name;
  out.text = budget.text;
  out.spec = load::ParseUncertainty(root, *budget.parameters);
  if (out.spec.parameters.empty())
    root.Fail("no parameter has a distribution: give one, e.g. parameters: {k: {value: 5.2e4 N/m, distribution: "
              "{normal: {sigma: 5 %}}}}");
  std::vector<load::VariedParameter> varied;
  for (const UncertainParameter& p : out.spec.parameters) varied.push_back({p.name, p.unit, p.unit_si});
  out.variant = load::ParameterVariants(budget, path, overrides, varied, "uncertainty sample");
  return out;
}

}  // namespace deb
