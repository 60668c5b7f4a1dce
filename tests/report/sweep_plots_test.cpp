#include "deb/report/sweep_plots.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/io/budget_yaml.h"
#include "tests/support/cli_harness.h"

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

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST_CASE("the key of a sweep plot names colours and dashes apart: contributors + total + blocks entries") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  spec.parameters = {{"a", {1, 2}, {}}, {"b", {10, 20, 30}, {}}};
  const auto plots = SweepPlots(spec, std::vector<BudgetResult>(6, Evaluate(budget)));
  const std::string& script = plots[0].script;
  const std::size_t contributors = budget.contributors.size();
  CHECK(Count(script, "keyentry") == contributors + 1 + 3);
  CHECK(Count(script, " notitle") == 3 * (contributors + 1));  // every curve
  CHECK(Count(script, "title 'b = 30'") == 1);
  // With one parameter every curve names itself and there is no keyentry.
  SweepSpec one;
  one.parameters = {{"a", {1, 2}, {}}};
  const std::string single = SweepPlots(one, std::vector<BudgetResult>(2, Evaluate(budget)))[0].script;
  CHECK(Count(single, "keyentry") == 0);
  CHECK(Count(single, " notitle") == 0);
}

}  // namespace deb::report
