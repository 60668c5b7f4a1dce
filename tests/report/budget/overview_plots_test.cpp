#include "deb/report/budget/overview_plots.h"

#include <doctest/doctest.h>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("the overview has a panel per output: bars largest first, the total last, the requirement and the verdict") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = OverviewFigures(result);
  REQUIRE(plots.size() == 1);
  const PlotFigure& fig = plots[0].figure;
  REQUIRE(fig.panels.size() == result.outputs.size());
  CHECK(fig.columns == 2);
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    const OutputResult& out = result.outputs[o];
    const FigurePanel& panel = fig.panels[o];
    const std::vector<std::size_t> order = ShareOrder(out);
    REQUIRE(panel.series.size() == out.contributors.size() + 2);  // bars, total, values
    for (std::size_t i = 0; i < order.size(); ++i) {
      CHECK(panel.series[i].name == out.contributors[order[i]].name);
      CHECK(panel.series[i].colour == ContributorStyle(order[i]).colour);
      CHECK(panel.x.tics[i].first == doctest::Approx(i + 1.0));
    }
    CHECK(panel.series[order.size()].name == "total");
    CHECK(panel.series.back().kind == SeriesKind::kLabels);
    REQUIRE(out.rms_max);
    REQUIRE(panel.annotations.size() == 1);
    CHECK(panel.annotations[0].y0 == *out.rms_max);
    CHECK(panel.title.find(out.pass() ? ": PASS" : ": FAIL") != std::string::npos);
    CHECK(panel.title_colour == (out.pass() ? "#202020" : kRequirementColour));
    CHECK(*panel.y.max > std::max(out.rms(), *out.rms_max));
  }
  // Each bar reads its own row of the CSV: the row id is unique.
  CHECK(fig.panels[0].series[0].where_column == 11);
  CHECK(fig.panels[0].series[0].where_value != fig.panels[0].series[1].where_value);
}

}  // namespace deb::report
