#include "tools/model_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "deb/load/budget_yaml.h"
#include "tools/budget_overrides_option.h"

namespace deb::tools {

struct ModelCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
};

ModelCommand::ModelCommand() : options_(std::make_unique<Options>()) {}
ModelCommand::~ModelCommand() = default;

CLI::App* ModelCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* model = app.add_subcommand(
      "model", "Describe the physical models of a budget: natural frequencies, mode shapes, static pre-stress");
  model->add_option("budget", s.budget_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  AddOverridesOption(model, &s.overrides);
  return model;
}

int ModelCommand::Run() const {
  const Options& s = *options_;
  const Budget budget = LoadBudgetFile(s.budget_file, s.overrides);
  if (budget.models.empty()) {
    std::printf("budget %s has no physical model (no path of type isolation_system)\n", budget.name.c_str());
    return 0;
  }
  for (const auto& m : budget.models) std::printf("%s\n", m.report().c_str());
  std::printf("paths from the model(s):\n");
  for (const auto& p : budget.paths) {
    if (p.description.empty()) continue;
    std::printf("  %-28s %s\n", p.name.c_str(), p.description.c_str());
  }
  return 0;
}

}  // namespace deb::tools
