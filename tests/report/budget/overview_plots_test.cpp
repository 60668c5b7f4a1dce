#include "deb/report/budget/overview_plots.h"

#include <doctest/doctest.h>

#include <sstream>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("the overview has a panel per output: horizontal bars largest first from the top, the total at the foot, the requirement and the verdict") {
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
      CHECK(panel.series[i].kind == SeriesKind::kHorizontalBars);
      CHECK(panel.y.tics[i].first == doctest::Approx(static_cast<double>(order.size() - i) + 1.3));
    }
    CHECK(panel.y.tics.back().first == doctest::Approx(1.0));  // the total, below the smallest
    // RMS tics on a nice step from 0, at most six of them (two panels to a row).
    REQUIRE(panel.x.tics.size() >= 3);
    CHECK(panel.x.tics.size() <= 6);
    CHECK(panel.x.tics[0].first == 0.0);
    CHECK(panel.x.tics.back().first <= *panel.x.max);
    CHECK(panel.series[order.size()].name == "total");
    CHECK(panel.series.back().kind == SeriesKind::kLabels);
    CHECK(panel.series.back().labels_beside_end);
    REQUIRE(out.rms_max);
    REQUIRE(panel.annotations.size() == 1);
    CHECK(panel.annotations[0].kind == AnnotationKind::kVerticalLine);
    CHECK(panel.annotations[0].x0 == *out.rms_max);
    CHECK(panel.title.find(out.pass() ? ": PASS" : ": FAIL") != std::string::npos);
    CHECK(panel.title_colour == (out.pass() ? "#202020" : kRequirementColour));
    CHECK(*panel.x.max > std::max(out.rms(), *out.rms_max));
  }
  // As tall in report.pdf as its two rows of twelve bars need, within 600 px.
  CHECK(plots[0].pdf_height_px == 600);
  // Each bar reads its own row of the CSV: the row id is unique.
  CHECK(fig.panels[0].series[0].where_column == 11);
  CHECK(fig.panels[0].series[0].where_value != fig.panels[0].series[1].where_value);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("an overview bar of a contributor the model leaves uncoupled, computed as rounding, reads 0") {
  // nizamoglu2015_h0: the floor reaches beta_velocity as 6.1e-13 µrad/s of 22.
  const BudgetResult result = Evaluate(LoadBudgetFile(test::ExampleBudget("nizamoglu2015_h0.yaml")));
  std::size_t beta = result.outputs.size();
  for (std::size_t o = 0; o < result.outputs.size(); ++o)
    if (result.outputs[o].name == "beta_velocity") beta = o;
  REQUIRE(beta < result.outputs.size());
  bool floor_seen = false;
  for (const ContributorResult& c : result.outputs[beta].contributors)
    if (c.name == "floor") {
      floor_seen = true;
      REQUIRE(c.variance > 0.0);  // rounding, not an exact zero
      CHECK(c.variance < 1e-24 * result.outputs[beta].variance);
    }
  REQUIRE(floor_seen);
  const std::string csv = OverviewFigures(result)[0].csv;
  CHECK(csv.find(",beta_velocity,urad/s,floor,0,") != std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the overview of one output spans the figure, as tall in report.pdf as its bars need") {
  // optical_table: one output, five contributors.
  const BudgetResult result = Evaluate(LoadBudgetFile(test::ExampleBudget("optical_table.yaml")));
  REQUIRE(result.outputs.size() == 1);
  const std::vector<Plot> plots = OverviewFigures(result);
  REQUIRE(plots.size() == 1);
  CHECK(plots[0].figure.columns == 1);
  const double bars = static_cast<double>(result.outputs[0].contributors.size() + 1);
  CHECK(plots[0].pdf_height_px == static_cast<int>(30.0 + 90.0 + 2.0 * 20.0 + std::max(80.0, 17.0 * (bars + 0.5))));
  CHECK(plots[0].pdf_height_px < 300);
  // nizamoglu2015_h0: seven outputs, three to a row, at most four RMS steps each.
  const BudgetResult h0 = Evaluate(LoadBudgetFile(test::ExampleBudget("nizamoglu2015_h0.yaml")));
  const std::vector<Plot> seven = OverviewFigures(h0);
  REQUIRE(seven.size() == 1);
  CHECK(seven[0].figure.columns == 3);
  REQUIRE(seven[0].figure.panels.size() == h0.outputs.size());
  for (std::size_t o = 0; o < h0.outputs.size(); ++o) {
    const FigurePanel& panel = seven[0].figure.panels[o];
    CHECK(panel.x.tics.size() <= 5);
    // Room for the values as shown: beta_velocity's floor, rounding, reads
    // "0", and its axis is not widened for "6.144e-13" (it reached 2.5x the
    // total; the widest shown text, "22.27", needs 1.84x).
    if (h0.outputs[o].name == "beta_velocity") CHECK(*panel.x.max < 2.0 * h0.outputs[o].rms());
  }
  // avis_case_study: six outputs, three to a row, RMS in the thousands: at
  // most two steps ("10002000" ran together), and a value that would reach
  // the requirement's line written past it.
  const BudgetResult avis = Evaluate(LoadBudgetFile(test::ExampleBudget("avis_case_study.yaml")));
  const std::vector<Plot> six = OverviewFigures(avis);
  REQUIRE(six.size() == 1);
  CHECK(six[0].figure.columns == 3);
  CHECK(six[0].figure.panels[0].x.tics.size() <= 3);
  std::size_t past_line = 0;
  std::istringstream csv(six[0].csv);
  std::string line;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("panel,", 0) == 0) continue;
    std::vector<std::string> f;
    std::string field;
    std::istringstream fields(line);
    while (std::getline(fields, field, ',')) f.push_back(field);
    REQUIRE(f.size() == 12);
    const double rms = std::stod(f[2]), label_at = std::stod(f[11]);
    if (f[8].empty()) {
      CHECK(label_at == rms);
      continue;
    }
    const double rms_max = std::stod(f[8]);
    CHECK(label_at >= rms);
    if (label_at > rms) {
      CHECK(label_at == rms_max);
      ++past_line;
    }
  }
  CHECK(past_line >= 3);  // the three displacement totals, 1759 to 1855 nm against 2000
}

}  // namespace deb::report
