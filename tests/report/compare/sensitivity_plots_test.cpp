#include "deb/report/compare/sensitivity_plots.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"

namespace deb::report {
namespace {

// Output y (variance 4) with contributors a and b; parameters k and m.
OutputResult Output() {
  OutputResult o;
  o.name = "y";
  o.unit = "nm";
  o.variance = 4.0;
  ContributorResult a, b;
  a.name = "a";
  a.variance = 3.0;
  b.name = "b";
  b.variance = 1.0;
  o.contributors = {a, b};
  return o;
}

// d var / d ln p per term: k moves a by +2 and b by -1 (total +1, elasticity 0.25);
// m moves b by -4 (total -4, elasticity -1).
std::vector<Sensitivity> All() {
  return {{"k", "y", "nm", "total", 4.0, 1.0, 0.25}, {"k", "y", "nm", "a", 3.0, 2.0, 2.0 / 3.0},
          {"k", "y", "nm", "b", 1.0, -1.0, -1.0},    {"m", "y", "nm", "total", 4.0, -4.0, -1.0},
          {"m", "y", "nm", "a", 3.0, 0.0, 0.0},      {"m", "y", "nm", "b", 1.0, -4.0, -4.0}};
}

}  // namespace

TEST_CASE("tornado bars: parameters by the magnitude of the total's elasticity, each with its contributors' shares") {
  const auto bars = TornadoBars(All(), Output());
  REQUIRE(bars.size() == 5);  // m: total, b (a moves 0: left out); k: total, a, b
  CHECK(bars[0].parameter == "m");
  CHECK(bars[0].contributor == "total");
  CHECK(bars[0].value == -1.0);
  CHECK(bars[1].contributor == "b");
  CHECK(bars[1].value == -1.0);  // -4 / 4
  CHECK(bars[2].parameter == "k");
  CHECK(bars[3].contributor == "a");
  CHECK(bars[3].contributor_index == 0);
  CHECK(bars[4].contributor == "b");
  // The shares of one parameter sum to the total's elasticity.
  CHECK(bars[3].value + bars[4].value == doctest::Approx(bars[2].value));
}

TEST_CASE("the tornado chart names every bar on the y axis, largest on top, and its data top to bottom") {
  BudgetResult nominal;
  nominal.outputs = {Output()};
  const auto plots = TornadoPlots(All(), nominal);
  REQUIRE(plots.size() == 1);
  const Plot& p = plots[0];
  CHECK(p.name == "y_tornado");
  CHECK(p.script == EmitFigure(p.figure));
  REQUIRE(p.figure.panels.size() == 1);
  const FigurePanel& panel = p.figure.panels[0];
  // The y axis names the bars top to bottom at n-1 .. 0: ordered by |elasticity| (m: -1 before k: 0.25).
  using Tic = std::pair<double, std::string>;
  CHECK(panel.y.tics == std::vector<Tic>{{4, "m: total"}, {3, "of which b"}, {2, "k: total"}, {1, "of which a"},
                                         {0, "of which b"}});
  REQUIRE(panel.y.min);
  CHECK(*panel.y.min < 0.0);
  CHECK(*panel.y.max > 4.0);
  // x symmetric about 0, the largest bar + 30 %.
  CHECK(*panel.x.min == doctest::Approx(-1.3));
  CHECK(*panel.x.max == doctest::Approx(1.3));
  // The total's bars black, then each contributor's in its report colour, each reading the rows of its colour index.
  REQUIRE(panel.series.size() == 4);
  CHECK(panel.series[0].kind == SeriesKind::kHorizontalBars);
  CHECK(panel.series[0].colour == kTotalColour);
  CHECK(panel.series[0].where_value == -1.0);
  const FigureSeries* b = FindSeries(p.figure, "b");
  REQUIRE(b);
  CHECK(b->colour == ContributorStyle(1).colour);
  CHECK(b->where_column == 5);
  CHECK(b->where_value == 1.0);
  CHECK(b->bar_height < panel.series[0].bar_height);
  CHECK(b->x_column == 2);  // the value
  CHECK(b->y_columns == std::vector<std::size_t>{1});  // the position
  CHECK(panel.series[3].kind == SeriesKind::kLabels);
  CHECK(panel.series[3].labels_beside_end);
  // The zero line.
  REQUIRE(panel.annotations.size() == 1);
  CHECK(panel.annotations[0].kind == AnnotationKind::kVerticalLine);
  CHECK(panel.annotations[0].x0 == 0.0);
  // The CSV row of a bar sits at its tic's position.
  // with its value labelled as the tables print numbers (SigLabel).
  CHECK(p.csv.find("\n4,-1,m,total,-1,-1.00\n") != std::string::npos);
  CHECK(p.csv.find("\n0,-0.25,k,b,1,-0.250\n") != std::string::npos);
  CHECK(SigLabel(-2.927e-5, 3).find("10^{-5}") != std::string::npos);  // not "-2.93e-05"
  CHECK(panel.series[3].label_column == 6);
  CHECK(panel.series[3].label_format.empty());
}

}  // namespace deb::report
