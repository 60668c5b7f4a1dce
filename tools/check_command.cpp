#include "tools/check_command.h"

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/budget_description.h"
#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/sweep_yaml.h"
#include "tools/budget_overrides_option.h"

namespace deb::tools {

struct CheckCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
};

CheckCommand::CheckCommand() : options_(std::make_unique<Options>()) {}
CheckCommand::~CheckCommand() = default;

CLI::App* CheckCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* check = app.add_subcommand("check", "Validate a budget and describe it, without computing");
  check->add_option("budget", s.budget_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  AddOverridesOption(check, &s.overrides);
  return check;
}

int CheckCommand::Run() const {
  const Options& s = *options_;
  const Budget budget = LoadBudgetFile(s.budget_file, s.overrides);
  // Everything run checks of its input before computing: what check accepts, run accepts.
  const EvaluationPlan plan = PlanEvaluation(budget);
  // Every sweep variant is loaded and validated, as deb sweep would before computing.
  std::optional<SweepBudget> sweep;
  if (budget.has_sweep) {
    sweep = LoadSweepFile(s.budget_file, s.overrides);
    LoadSweepVariants(*sweep);
  }
  std::fputs(DescribeBudget(budget, plan).c_str(), stdout);
  std::fflush(stdout);  // the warnings after the description, also when both go to one file
  for (const auto& w : plan.warnings) std::fprintf(stderr, "deb: warning: %s\n", w.c_str());
  if (sweep) std::fputs(DescribeSweep(sweep->spec, sweep->variant_count).c_str(), stdout);
  return 0;
}

}  // namespace deb::tools
