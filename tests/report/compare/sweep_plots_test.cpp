#include "deb/report/compare/sweep_plots.h"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/report_pdf.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/gnuplot_runner.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/cli_harness.h"
#include "tests/support/csv_blocks.h"

namespace deb::report {
namespace {

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The rows of CSV block `index` (after its comment and header lines where present), as numbers.
std::vector<std::vector<double>> Block(const std::string& csv, int index) {
  std::vector<std::vector<double>> rows;
  for (const auto& fields : test::CsvBlockRows(csv, index)) {
    std::vector<double> row;
    for (const std::string& f : fields) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("sweep plots hold one data block per combination of the other parameters, ordered by the first") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  spec.parameters = {{"a", {3, 1, 2}, {}, {}, {}, {}}, {"b", {10, 20}, {}, {}, {}, {}}};  // 6 variants, a unsorted
  std::vector<BudgetResult> results(6, Evaluate(budget));
  const auto plots = SweepPlots(spec, results);
  REQUIRE(plots.size() == 2 * budget.outputs.size());  // small multiples and a map per output
  CHECK(plots[0].name == FileStem(budget.outputs[0].name) + "_sweep");
  CHECK(plots[1].name == FileStem(budget.outputs[0].name) + "_map");
  const std::string& csv = plots[0].csv;
  CHECK(csv.find("# b = 10\n") != std::string::npos);
  CHECK(csv.find("\n\n\n# b = 20\n") != std::string::npos);
  // Rows of a block ascend in a.
  const auto first_block = Block(csv, 0);
  REQUIRE(first_block.size() == 3);
  CHECK(first_block[0][0] == 1.0);
  CHECK(first_block[1][0] == 2.0);
  CHECK(first_block[2][0] == 3.0);
  // Panel b draws block b.
  REQUIRE(plots[0].figure.panels.size() == 2);
  CHECK(FindSeries(plots[0].figure, "total", 1)->block == 1);
  // The total thin, drawn last, over contributors three times as wide: one that is all of it still shows.
  const FigurePanel& panel = plots[0].figure.panels[0];
  CHECK(panel.series.back().name == "total");
  for (std::size_t k = 0; k + 1 < panel.series.size(); ++k)
    CHECK(panel.series[k].width >= 3.0 * panel.series.back().width);
}

TEST_CASE("small multiples: one panel per value of the other parameters, one RMS axis, the key once") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  SweepParameter a{"paths[0].num[1]", {1, 2}, {}, {}, {}, {}}, b{"sources[1].spectrum.level", {10, 20, 30}, {}, {}, {}, {}};
  a.label = "stiffness";
  a.unit = "N/m";
  b.label = "noise";
  spec.parameters = {a, b};
  const auto plots = SweepPlots(spec, std::vector<BudgetResult>(6, Evaluate(budget)));
  const PlotFigure& figure = plots[0].figure;
  CHECK(plots[0].script == EmitFigure(figure));
  REQUIRE(figure.panels.size() == 3);
  CHECK(figure.columns == 3);
  CHECK(figure.panels[2].title == "noise = 30");
  // The unit in the figure's title as well (report.pdf has no room for the y label).
  CHECK(figure.title.find(": RMS [") != std::string::npos);
  CHECK(figure.title.find("] against stiffness") != std::string::npos);
  CHECK(figure.panels[0].x.label == "stiffness [N/m]");  // no key path on the axis
  // In a grid, the axis is named under each column's bottom panel only (its
  // name ran into the title of the panel below).
  SweepSpec grid = spec;
  grid.parameters[1].values = {10, 20, 30, 40};
  const PlotFigure two_by_two = SweepPlots(grid, std::vector<BudgetResult>(8, Evaluate(budget)))[0].figure;
  REQUIRE(two_by_two.columns == 2);
  REQUIRE(two_by_two.panels.size() == 4);
  CHECK(two_by_two.panels[0].x.label.empty());
  CHECK(two_by_two.panels[1].x.label.empty());
  CHECK(two_by_two.panels[2].x.label == "stiffness [N/m]");
  CHECK(two_by_two.panels[3].x.label == "stiffness [N/m]");
  CHECK(plots[0].script.find("paths[0]") == std::string::npos);
  // The key once, beside the panels; one RMS axis shared by every panel, labelled on the left.
  CHECK(figure.panels[0].key.placement == KeyPlacement::kBesideGrid);
  CHECK(figure.panels[1].key.placement == KeyPlacement::kNone);
  CHECK(figure.panels[2].key.placement == KeyPlacement::kNone);
  for (const FigurePanel& panel : figure.panels) {
    CHECK(panel.y.min == 0.0);
    CHECK(panel.y.max == figure.panels[0].y.max);
  }
  CHECK(!figure.panels[0].y.label.empty());
  CHECK(figure.panels[1].y.label.empty());
  // Contributors in their report colours, the total black and last; keys only in the first panel.
  const FigureSeries* total = FindSeries(figure, "total", 1);
  REQUIRE(total);
  CHECK(total->colour == kTotalColour);
  CHECK(total->key.empty());
  CHECK(FindSeries(figure, "total", 0)->key == "total");
  CHECK(figure.panels[1].series.back().name == "total");
  CHECK(figure.panels[1].series[0].colour == ContributorStyle(0).colour);
  // With one parameter: one panel, its key beside it.
  SweepSpec one;
  one.parameters = {a};
  const Plot single = SweepPlots(one, std::vector<BudgetResult>(2, Evaluate(budget)))[0];
  REQUIRE(single.figure.panels.size() == 1);
  CHECK(single.figure.panels[0].key.placement == KeyPlacement::kOutsideRight);
  CHECK(Count(single.script, "multiplot") == 0);
}

TEST_CASE("small multiples draw the requirement in every panel, in the key once") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  BudgetResult result = Evaluate(budget);
  result.outputs[0].rms_max = 2.5;
  SweepSpec spec;
  spec.parameters = {{"a", {1, 2}, {}, {}, {}, {}}, {"b", {10, 20}, {}, {}, {}, {}}};
  const PlotFigure figure = SweepPlots(spec, std::vector<BudgetResult>(4, result))[0].figure;
  REQUIRE(figure.panels.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    REQUIRE(figure.panels[i].annotations.size() == 1);
    CHECK(figure.panels[i].annotations[0].kind == AnnotationKind::kHorizontalLine);
    CHECK(figure.panels[i].annotations[0].y0 == 2.5);
    CHECK(figure.panels[i].annotations[0].colour == kRequirementColour);
  }
  CHECK(figure.panels[0].annotations[0].key == "requirement: 2.5");
  CHECK(figure.panels[1].annotations[0].key.empty());
  CHECK(*figure.panels[0].y.max >= 2.5);
}

TEST_CASE("the contour of a plane z = x + y at level 1 runs through the cells it crosses, on x + y = 1") {
  const std::vector<double> x = {0.0, 0.5, 2.0}, y = {0.0, 1.0};
  std::vector<std::vector<double>> z(3, std::vector<double>(2));
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 2; ++j) z[i][j] = x[i] + y[j];
  const auto segments = LevelSegments(x, y, z, 1.0);
  REQUIRE(segments.size() == 2);  // through cells [0, 0.5] and [0.5, 2]
  for (const ContourSegment& s : segments) {
    CHECK(s.x0 + s.y0 == doctest::Approx(1.0));
    CHECK(s.x1 + s.y1 == doctest::Approx(1.0));
  }
  CHECK(LevelSegments(x, y, z, 10.0).empty());  // every value below: no contour
}

TEST_CASE("the map's key below it is drawn in sweep.pdf's figure, not left out for want of room") {
  // An empty key title took the key below the 420 px canvas' edge, and
  // gnuplot then drew no key at all.
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  spec.parameters = {{"a", {1, 2}, {}, {}, {}, {}}, {"b", {10, 20}, {}, {}, {}, {}}};
  const std::vector<Plot> plots = SweepPlots(spec, std::vector<BudgetResult>(4, Evaluate(budget)));
  REQUIRE(plots.size() >= 2);
  const Plot& map = plots[1];
  REQUIRE(map.name.find("_map") != std::string::npos);
  namespace fs = std::filesystem;
  const fs::path dir = test::TempDir("sweep_map_key");
  fs::create_directories(dir / kPdfFigureDir);
  test::WriteFile(dir / (map.name + ".csv"), map.csv);
  test::WriteFile(dir / (map.name + ".gp"), map.script);
  RunGnuplot(FindGnuplot(""), dir.string(), PdfFigureCommands(map), map.name);
  const std::string svg = test::ReadAll(dir / kPdfFigureDir / (map.name + ".svg"));
  CHECK(svg.find("variants") != std::string::npos);
  CHECK(svg.find("best: ") != std::string::npos);
  CHECK(svg.find("requirement: ") != std::string::npos);
  // Where every variant meets the requirement, the caption says so (the key has no room).
  CHECK(map.caption.find("Every variant meets the requirement") != std::string::npos);
}

TEST_CASE("the map of a two-parameter grid holds the grid by scan lines, the best variant and the requirement") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult base = Evaluate(budget);
  SweepSpec spec;
  spec.parameters = {{"a", {2, 1}, {}, {}, {}, {}}, {"b", {10, 20, 30}, {}, {}, {}, {}}};  // a unsorted
  std::vector<BudgetResult> results(6, base);
  // Total RMS of output 0 = a * b / 10 (variance scaled), requirement 3.5.
  const auto rows = spec.Variants();
  for (std::size_t i = 0; i < 6; ++i) {
    OutputResult& o = results[i].outputs[0];
    const double rms = rows[i][0] * rows[i][1] / 10.0;
    o.variance = rms * rms;
    o.rms_max = 3.5;
  }
  const auto plots = SweepPlots(spec, results);
  const Plot& map = plots[1];
  const auto grid = Block(map.csv, 0);
  REQUIRE(grid.size() == 6);
  CHECK(grid[0] == std::vector<double>{1, 10, 1});  // a ascending, b fastest
  CHECK(grid[5] == std::vector<double>{2, 30, 6});
  const auto best = Block(map.csv, 1);
  REQUIRE(best.size() == 1);
  CHECK(best[0] == std::vector<double>{1, 10, 1});
  const auto contour = Block(map.csv, 2);
  REQUIRE(contour.size() >= 1);
  for (const auto& s : contour) CHECK(s[2] == 3.5);
  // As a figure: the heat map of block 0, the requirement's contour from block 2, the best variant ringed
  // at its (a, b) from block 1, drawn last.
  CHECK(map.script == EmitFigure(map.figure));
  REQUIRE(map.figure.panels.size() == 1);
  const FigurePanel& panel = map.figure.panels[0];
  REQUIRE(panel.series.size() == 4);
  CHECK(panel.series[0].kind == SeriesKind::kHeatMap);
  CHECK(panel.series[0].block == 0);
  CHECK(panel.series[0].z_column == 3);
  CHECK(!panel.palette.empty());
  const FigureSeries* line = FindSeries(map.figure, "requirement");
  REQUIRE(line);
  CHECK(line->kind == SeriesKind::kSegments);
  CHECK(line->block == 2);
  CHECK(line->key == "requirement: 3.5");
  CHECK(line->colour == kRequirementColour);
  const FigureSeries& ring = panel.series.back();
  CHECK(ring.name == "best");
  CHECK(ring.block == 1);
  CHECK(ring.key == "best: 1.00");
  CHECK(ring.x_column == 1);
  CHECK(ring.y_columns == std::vector<std::size_t>{2});
  // The axes span the grid (ascending), the colours the RMS: log, as it spans a factor 6.
  CHECK(*panel.x.min == 1.0);
  CHECK(*panel.x.max == 2.0);
  CHECK(*panel.y.min == 10.0);
  CHECK(*panel.y.max == 30.0);
  CHECK(panel.colour_axis.scale == AxisScale::kLog);
  CHECK(panel.colour_axis.tics.front().first == 1.0);
  // Round ticks (1, 2, 5) and the highest RMS at the top end of the bar.
  CHECK(panel.colour_axis.tics[panel.colour_axis.tics.size() - 2].first == 5.0);
  CHECK(panel.colour_axis.tics.back().first == 6.0);
  // The key in a row below the map, never over it.
  CHECK(panel.key.placement == KeyPlacement::kBelowMap);
  // A variant zero but for rounding (4e-11 against up to 6): the colours span 3 decades below the
  // highest RMS, the bar is labelled in steps that stay apart, and the caption says what is clipped.
  std::vector<BudgetResult> zeroed = results;
  zeroed[0].outputs[0].variance = 4e-11 * 4e-11;
  const Plot clipped = SweepPlots(spec, zeroed)[1];
  const FigureAxis& bar = clipped.figure.panels.at(0).colour_axis;
  REQUIRE(bar.min);
  CHECK(*bar.min == doctest::Approx(6e-3));
  CHECK(bar.tics.size() <= 12);  // 3 decades of 1, 2, 5 and the ends
  for (const auto& [v, label] : bar.tics) CHECK(v >= *bar.min * 0.999);
  // No two labels closer than 8 % of the bar (a line of text in report.pdf's map).
  for (const FigureAxis* a : {&panel.colour_axis, &bar}) {
    const double span = std::log(a->tics.back().first / a->tics.front().first);
    for (std::size_t k = 1; k < a->tics.size(); ++k)
      CHECK(std::log(a->tics[k].first / a->tics[k - 1].first) >= 0.08 * span);
  }
  CHECK(clipped.caption.find("Colours span 3 decades") != std::string::npos);
  // Rounding (at most 1e-12 of the highest RMS: nizamoglu2015_sweep's beta_velocity at K_v = h = 0, 4.2e-11 of
  // 82) does not set the scale at all: the colours span the other variants, and the caption says so.
  zeroed[0].outputs[0].variance = 1e-13 * 1e-13;
  const Plot rounded = SweepPlots(spec, zeroed)[1];
  const FigureAxis& rounded_bar = rounded.figure.panels.at(0).colour_axis;
  REQUIRE(rounded_bar.min);
  double lowest_other = HUGE_VAL;
  for (std::size_t v = 1; v < zeroed.size(); ++v) lowest_other = std::min(lowest_other, zeroed[v].outputs[0].rms());
  CHECK(*rounded_bar.min == doctest::Approx(lowest_other));
  CHECK(rounded.caption.find("computed as rounding") != std::string::npos);
  CHECK(rounded.caption.find("Colours span 3 decades") == std::string::npos);
  // Zipped, or one parameter: no map.
  spec.mode = SweepMode::kZip;
  spec.parameters[1].values = {10, 20};
  CHECK(SweepPlots(spec, std::vector<BudgetResult>(2, base)).size() == base.outputs.size());
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("sweep.pdf sets two figures to a page: small multiples of up to four panels and the map at a run figure's height") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  spec.parameters = {{"paths[0].num[1]", {1, 2}, {}, {}, {}, {}}, {"sources[1].spectrum.level", {10, 20, 30}, {}, {}, {}, {}}};
  const auto plots = SweepPlots(spec, std::vector<BudgetResult>(6, Evaluate(budget)));
  REQUIRE(plots.size() >= 2);
  REQUIRE(plots[0].figure.panels.size() == 3);
  CHECK(plots[0].pdf_height_px == 420);
  CHECK(plots[1].name.find("_map") != std::string::npos);
  CHECK(plots[1].pdf_height_px == 420);
  const std::string terminal = PdfFigureTerminal(plots[0]);
  CHECK(terminal.find("size 662,420 ") != std::string::npos);
  CHECK(terminal.find(std::string(kPdfHeightVariable) + " = 420\n") != std::string::npos);
  // The grid's vertical room scales with the canvas: 600 / 420 on this one.
  CHECK(plots[0].script.find("deb_grid_v = exists('deb_pdf_height') ? 600.0 / deb_pdf_height : 1") !=
        std::string::npos);
  CHECK(plots[0].script.find("spacing 0.07,(0.13 * deb_grid_v)") != std::string::npos);
  // Five panels or more keep the overview's height.
  SweepSpec many;
  many.parameters = {{"paths[0].num[1]", {1, 2}, {}, {}, {}, {}},
                     {"sources[1].spectrum.level", {10, 20, 30, 40, 50}, {}, {}, {}, {}}};
  const auto tall = SweepPlots(many, std::vector<BudgetResult>(10, Evaluate(budget)));
  REQUIRE(tall[0].figure.panels.size() == 5);
  CHECK(tall[0].pdf_height_px == 0);
  CHECK(PdfFigureTerminal(tall[0]).find("size 662,600 ") != std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("small multiples put totals more than 5x apart on a log RMS axis") {
  // The nizamoglu2015 sweep's K_v = 0 (80-110 um/s) squeezed the 10-20 that
  // matter into the bottom seventh of a linear axis.
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  SweepSpec spec;
  spec.parameters = {{"paths[0].num[1]", {1, 2, 3}, {}, {}, {}, {}}};
  std::vector<BudgetResult> results(3, Evaluate(budget));
  const double rms = results[0].outputs[0].rms();
  REQUIRE(rms > 0.0);
  const auto linear = SweepPlots(spec, results);
  CHECK(linear[0].figure.panels[0].y.scale == AxisScale::kLinear);
  CHECK(*linear[0].figure.panels[0].y.min == 0.0);
  // One variant 8x the others: a log axis from the decade below half the
  // lowest total or contributor, down to 10^-3 of the top at most.
  results[0].outputs[0].variance *= 64.0;
  double smallest = rms;
  for (const ContributorResult& c : results[1].outputs[0].contributors)
    if (c.variance > 0.0) smallest = std::min(smallest, std::sqrt(c.variance));
  const double top = std::max(results[0].outputs[0].rms_max.value_or(0.0), 8.0 * rms);
  const double bottom = std::pow(10.0, std::floor(std::log10(std::max(smallest, 1e-3 * top) / 2.0)));
  const auto spread = SweepPlots(spec, results);
  const FigurePanel& panel = spread[0].figure.panels[0];
  CHECK(panel.y.scale == AxisScale::kLog);
  CHECK(*panel.y.min == doctest::Approx(bottom));
  CHECK(*panel.y.min <= smallest);  // every contributor shows
  CHECK(*panel.y.max >= 8.0 * rms);
  CHECK(spread[0].caption.find("log axis") != std::string::npos);
  // A variant computed as rounding (4e-11 of 82 in nizamoglu2015_sweep's beta_velocity) does not set the axis.
  results[1].outputs[0].variance = 1e-26 * results[0].outputs[0].variance;
  const auto rounded = SweepPlots(spec, results);
  CHECK(*rounded[0].figure.panels[0].y.min == doctest::Approx(bottom));
  CHECK(rounded[0].caption.find("computed as rounding") != std::string::npos);
}

}  // namespace deb::report
