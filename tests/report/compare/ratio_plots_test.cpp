// deb/report/compare/ratio_plots.h: B's PSD over A's, checked where the
// ratio is known exactly (a contributor whose PSD B holds four times over),
// and the interpolation onto A's frequencies against a power law, which
// straight lines over log f and log y draw exactly.
#include "deb/report/compare/ratio_plots.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("AtFrequency interpolates a power law exactly, and is NaN outside the frequencies") {
  std::vector<double> f, y;
  for (double x = 1.0; x <= 1000.0; x *= 10.0) {
    f.push_back(x);
    y.push_back(3.0 / (x * x));
  }
  for (double x : {1.0, 2.0, 31.6, 500.0, 1000.0})
    CHECK(AtFrequency(f, y, x) == doctest::Approx(3.0 / (x * x)).epsilon(1e-12));
  CHECK(std::isnan(AtFrequency(f, y, 0.5)));
  CHECK(std::isnan(AtFrequency(f, y, 1001.0)));
  // Through a zero: straight over log f (a PSD that ends).
  CHECK(AtFrequency({1.0, 100.0}, {0.0, 2.0}, 10.0) == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("a ratio plot gives B / A per shared contributor and in total; four times the PSD is 4 at every row") {
  const BudgetResult a = Evaluate(LoadBudgetFile(test::ExampleBudget()));
  REQUIRE(a.outputs[0].contributors.size() == 2);
  BudgetResult b = a;
  OutputResult& ob = b.outputs[0];
  for (double& v : ob.contributors[1].psd) v *= 4.0;
  ob.contributors[1].variance *= 4.0;
  for (std::size_t k = 0; k < ob.total_psd.size(); ++k)
    ob.total_psd[k] = ob.contributors[0].psd[k] + ob.contributors[1].psd[k];
  ob.variance = ob.contributors[0].variance + ob.contributors[1].variance;

  const std::vector<Plot> plots = RatioPlots("a", a, "b", b);
  REQUIRE(plots.size() == a.outputs.size());
  const Plot& p = plots[0];
  CHECK(p.name == FileStem(a.outputs[0].name) + "_ratio");
  std::istringstream in(p.csv);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  CHECK(line ==
        "frequency_hz," + a.outputs[0].contributors[0].name + "," + a.outputs[0].contributors[1].name + ",total");
  std::size_t rows = 0;
  const OutputResult& oa = a.outputs[0];
  while (std::getline(in, line)) {
    double f, r0, r1, rt;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &f, &r0, &r1, &rt) == 4);
    const std::vector<double>& grid = a.grid.f_hz();
    // The grid point the row prints with 10 digits: the nearest.
    auto k = static_cast<std::size_t>(std::lower_bound(grid.begin(), grid.end(), f * (1 - 1e-9)) - grid.begin());
    if (k + 1 < grid.size() && std::fabs(grid[k + 1] - f) < std::fabs(grid[k] - f)) ++k;
    if (oa.contributors[0].psd[k] > 0.0) CHECK(r0 == doctest::Approx(1.0).epsilon(1e-9));
    if (oa.contributors[1].psd[k] > 0.0) CHECK(r1 == doctest::Approx(4.0).epsilon(1e-9));
    CHECK(rt == doctest::Approx(ob.total_psd[k] / oa.total_psd[k]).epsilon(1e-9));
    ++rows;
  }
  CHECK(rows > 10);
  // The RMS ratio in the key: sqrt(4) = 2 for the scaled contributor; a log
  // axis, since the ratios reach 4.
  const FigureSeries* scaled = FindSeries(p.figure, oa.contributors[1].name);
  REQUIRE(scaled);
  CHECK(scaled->key.find(" 2.000") != std::string::npos);
  CHECK(p.figure.panels[0].y.scale == AxisScale::kLog);
  // The total thin over the contributors (a contributor that is all of it
  // shows on both sides), the line B = A behind them all.
  const FigureSeries* total = FindSeries(p.figure, "total");
  REQUIRE(total);
  CHECK(total->width * 2.0 <= scaled->width);
  REQUIRE(p.figure.panels[0].annotations.size() == 1);
  CHECK(p.figure.panels[0].annotations[0].behind);
  // A ratio of 1 everywhere is drawn on a linear axis around 1.
  CHECK(RatioPlots("a", a, "a", a)[0].figure.panels[0].y.scale == AxisScale::kLinear);
}

TEST_CASE("ratios within rounding of 1 (an output the change does not touch) get an axis of height, +-1e-3") {
  // Comparing the thesis with the same thesis with tolerances, whose tilt
  // velocity differs by rounding only, made gnuplot refuse "set yrange [1:1]".
  const BudgetResult a = Evaluate(LoadBudgetFile(test::ExampleBudget()));
  BudgetResult b = a;
  for (double& v : b.outputs[0].total_psd) v *= 1.0 + 1e-15;
  for (ContributorResult& c : b.outputs[0].contributors)
    for (double& v : c.psd) v *= 1.0 - 1e-15;
  const std::vector<Plot> plots = RatioPlots("a", a, "b", b);
  const FigurePanel& panel = plots[0].figure.panels[0];
  REQUIRE(panel.y.scale == AxisScale::kLinear);
  REQUIRE(panel.y.min.has_value());
  REQUIRE(panel.y.max.has_value());
  CHECK(*panel.y.min <= 1.0 - 1e-3);
  CHECK(*panel.y.max >= 1.0 + 1e-3);
}

}  // namespace deb::report
