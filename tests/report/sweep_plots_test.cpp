#include "deb/report/sweep_plots.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/io/budget_yaml.h"
#include "report_test_support.h"

namespace deb::report {

TEST_CASE("sweep plots hold one data block per combination of the other parameters, ordered by the first") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  spec.parameters = {{"a", {3, 1, 2}, {}}, {"b", {10, 20}, {}}};  // 6 variants, a unsorted
  std::vector<BudgetResult> results(6, Evaluate(budget));
  const auto plots = SweepPlots(spec, results);
  REQUIRE(plots.size() == budget.outputs.size());
  const std::string& csv = plots[0].csv;
  CHECK(csv.find("# b = 10\n") != std::string::npos);
  CHECK(csv.find("\n\n\n# b = 20\n") != std::string::npos);
  // Rows of a block ascend in a.
  const auto block = csv.substr(csv.find("# b = 10\n"));
  const auto first = block.find("\n1,"), second = block.find("\n2,"), third = block.find("\n3,");
  CHECK(first < second);
  CHECK(second < third);
  CHECK(plots[0].script.find("index 1") != std::string::npos);
  CHECK(plots[0].script.find("b = 20") != std::string::npos);
}

}  // namespace deb::report
