#include "deb/report/overlay_plots.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/io/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("overlay plots give PSD and CPS per shared output, A and B as two data blocks of one CSV") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult a = Evaluate(budget);
  BudgetResult b = a;
  b.outputs.pop_back();  // an output only A has gets no overlay
  const auto plots = OverlayPlots("A", a, "B", b);
  REQUIRE(plots.size() == 2 * b.outputs.size());
  CHECK(plots[0].name == FileStem(b.outputs[0].name) + "_psd_overlay");
  CHECK(plots[1].name == FileStem(b.outputs[0].name) + "_cps_overlay");
  const std::string& csv = plots[1].csv;
  const auto split = csv.find("\n\n\n# B\n");
  REQUIRE(split != std::string::npos);
  // Each block: comment, header, one row per grid point.
  std::size_t rows_a = 0;
  for (std::size_t i = csv.find("# A\n"); i < split; i = csv.find('\n', i + 1)) ++rows_a;
  CHECK(rows_a == a.grid.size() + 2);
  CHECK(plots[1].script.find("index 0") != std::string::npos);
  CHECK(plots[1].script.find("index 1") != std::string::npos);
  CHECK(plots[1].script.find("dashtype (8,5)") != std::string::npos);
}

}  // namespace deb::report
