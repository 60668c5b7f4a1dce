#include "deb/report/budget/band_plots.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/spectrum_plots.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("the bands figure draws each band requirement as a limit segment behind its own group and marks failures") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const OutputResult& out = result.outputs[0];  // position: decades 0.1..1e4 Hz; requirements 0.1-10 (fails), 10-100, 100-1e4
  REQUIRE(out.band_requirements.size() == 3);
  const Plot p = BandsPlot(result, 0);
  const FigurePanel& panel = p.figure.panels.at(0);
  // Five decade bands, then a group for each requirement range that is not a band (0.1-10, 100-1e4 Hz).
  REQUIRE(panel.x.tics.size() == out.bands.size() + 2);
  CHECK(panel.x.tics[out.bands.size()].second == "requirement\n0.1–10");
  // The unit once on the axis; seven groups: the labels turned so that they do not run together.
  CHECK(panel.x.label == "frequency band [Hz]");
  CHECK(panel.x.tic_rotation_deg == 30);
  std::vector<const FigureAnnotation*> limits;
  for (const FigureAnnotation& a : panel.annotations)
    if (a.kind == AnnotationKind::kSegment) limits.push_back(&a);
  REQUIRE(limits.size() == 3);
  for (const FigureAnnotation* l : limits) CHECK(l->bracket);
  // 10-100 Hz is a band: its segment spans that group (x = 3), at 2 nm.
  CHECK(limits[0]->x0 < 3.0);
  CHECK(limits[0]->x1 > 3.0);
  CHECK(limits[0]->x1 - limits[0]->x0 < 1.0);
  CHECK(limits[0]->y0 == doctest::Approx(2.0));
  // 0.1-10 Hz gets group 6, at 0.8 nm.
  CHECK(limits[1]->x0 < 6.0);
  CHECK(limits[1]->x1 > 6.0);
  CHECK(limits[1]->y0 == doctest::Approx(0.8));
  // Behind the bars: a bar that passes its limit covers it.
  for (const FigureAnnotation* a : limits) CHECK(a->behind);
  // The failing group's total is in the failing_total column; passing ones hold 0 there.
  std::istringstream lines(p.csv);
  std::string line;
  std::getline(lines, line);
  std::getline(lines, line);
  CHECK(line.rfind("group,lo_hz,hi_hz,total,failing_total,", 0) == 0);
  std::vector<double> failing;
  while (std::getline(lines, line)) {
    int group;
    double lo, hi, total, fail;
    REQUIRE(std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%lf", &group, &lo, &hi, &total, &fail) == 5);
    failing.push_back(fail);
    if (group == 6) {
      CHECK(total == doctest::Approx(out.band_requirements[0].rms()).epsilon(1e-9));
      CHECK(fail == total);
    }
  }
  CHECK(std::count_if(failing.begin(), failing.end(), [](double v) { return v > 0.0; }) == 1);
  const FigureSeries* outline = FindSeries(p.figure, "failing total");
  REQUIRE(outline != nullptr);
  CHECK(outline->y_columns == std::vector<std::size_t>{5});
  // Eleven contributors would be bars a few pixels wide: the bars are the
  // top-level groups, as the stacked CPS shows them, largest first, after the
  // total (and the failing total's outline).
  const PlotLevel top = GroupLevel(out, result.grid, "");
  REQUIRE(top.out.contributors.size() == 4);
  const std::vector<std::size_t> order = ShareOrder(top.out);
  CHECK(panel.series[0].name == "total");
  REQUIRE(panel.series.size() == 2 + 4);
  CHECK(panel.series[2].name == top.out.contributors[order[0]].name);
  CHECK(panel.series.back().name == top.out.contributors[order.back()].name);
  CHECK(p.caption.find("top-level group") != std::string::npos);
  // A FAIL label names the band's RMS.
  CHECK(std::any_of(panel.annotations.begin(), panel.annotations.end(), [](const FigureAnnotation& a) {
    return a.kind == AnnotationKind::kLabel && a.label.find("FAIL") != std::string::npos;
  }));
}

TEST_CASE("a band's bars are the groups past eight contributors, or the seven largest and the rest in one bar") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  BudgetResult result = Evaluate(budget);
  const OutputResult& out = result.outputs[0];
  // Each row's bars hold every contributor once: their variances add up to
  // the band's total (the contributors are uncorrelated), to rounding.
  const auto bars_add_up = [](const Plot& p, std::size_t bars) {
    std::istringstream lines(p.csv);
    std::string line;
    std::getline(lines, line);
    std::getline(lines, line);
    int rows = 0;
    while (std::getline(lines, line)) {
      std::vector<double> v;
      std::istringstream fields(line);
      for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
      REQUIRE(v.size() == 5 + bars);
      double sum = 0.0;
      for (std::size_t i = 5; i < v.size(); ++i) sum += v[i] * v[i];
      CHECK(std::sqrt(sum) == doctest::Approx(v[3]).epsilon(1e-9));
      ++rows;
    }
    return rows;
  };
  CHECK(bars_add_up(BandsPlot(result, 0), 4) == 7);
  // Without groups: the seven largest contributors, then "the other 4".
  for (ContributorResult& c : result.outputs[0].contributors) c.group.clear();
  const Plot p = BandsPlot(result, 0);
  const FigurePanel& panel = p.figure.panels.at(0);
  REQUIRE(panel.series.size() == 2 + 8);
  const std::vector<std::size_t> order = ShareOrder(out);
  CHECK(panel.series[2].name == out.contributors[order[0]].name);
  CHECK(panel.series[8].name == out.contributors[order[6]].name);
  CHECK(panel.series[9].name == "the other 4");
  CHECK(p.caption.find("the 7 largest, then the rest in one bar") != std::string::npos);
  CHECK(bars_add_up(p, 8) == 7);
}

}  // namespace deb::report
