#include "deb/report/compare/overlay_plots.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "deb/budget/comparison.h"
#include "deb/budget/engine.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"

#include "deb/load/budget_yaml.h"
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
  // Each block: comment, header, the points of the run's display range (and one either side).
  const FrequencyRange range = DisplayRange(a.outputs[0], a.grid);
  const std::vector<double>& f = a.grid.f_hz();
  const double lo = *(std::lower_bound(f.begin(), f.end(), range.lo_hz * (1 - 1e-12)) - (range.lo_hz > f.front()));
  const double hi = *std::lower_bound(f.begin(), f.end(), range.hi_hz * (1 - 1e-12));
  std::istringstream in(csv.substr(csv.find("# A\n"), split));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::size_t rows_a = 0;
  double first = 0.0, last = 0.0;
  while (std::getline(in, line) && !line.empty()) {
    const double x = std::stod(line.substr(0, line.find(',')));
    if (rows_a++ == 0) first = x;
    last = x;
  }
  CHECK(rows_a > 10);
  CHECK(first >= lo);
  CHECK(last <= hi);
  // A solid from block 0, B dashed from block 1, in the same colour per contributor; the totals black.
  const PlotFigure& cps = plots[1].figure;
  CHECK(plots[1].script == EmitFigure(cps));
  REQUIRE(cps.panels.size() == 1);
  const FigurePanel& panel = cps.panels[0];
  const FigureSeries* total_a = FindSeries(cps, "A: total");
  const FigureSeries* total_b = FindSeries(cps, "B: total");
  REQUIRE(total_a);
  REQUIRE(total_b);
  CHECK(total_a->block == 0);
  CHECK(total_b->block == 1);
  CHECK(total_a->dash == "solid");
  CHECK(total_b->dash == "(8,5)");
  // A wide and pale, B dashed over it in full colour: both show where they coincide.
  CHECK(total_a->colour == Tint(kTotalColour, 0.55));
  CHECK(total_b->colour == kTotalColour);
  CHECK(total_a->width > 2.0 * total_b->width);
  CHECK(total_a->y_columns == std::vector<std::size_t>{a.outputs[0].contributors.size() + 2});
  const FigureSeries* floor_b = FindSeries(cps, "B: " + a.outputs[0].contributors[0].name);
  REQUIRE(floor_b);
  CHECK(floor_b->colour == ContributorStyle(0).colour);
  const FigureSeries* floor_a = FindSeries(cps, "A: " + a.outputs[0].contributors[0].name);
  REQUIRE(floor_a);
  CHECK(floor_a->colour == Tint(ContributorStyle(0).colour, 0.55));
  CHECK(floor_a->width > 2.0 * floor_b->width);
  // Each side's total thinner than its contributors: one that is all of the total shows beside it.
  CHECK(total_a->width < floor_a->width);
  CHECK(total_b->width < floor_b->width);
  CHECK(&panel.series.back() == total_b);  // B drawn after A
  // The frequency axis clipped to the run's display range.
  REQUIRE(panel.x.min);
  CHECK(panel.x.scale == AxisScale::kLog);
  CHECK(*panel.x.min == doctest::Approx(range.lo_hz));
  CHECK(*panel.x.max == doctest::Approx(range.hi_hz));
  // CPS on a linear axis from 0 to just above the larger total (or requirement), as in deb run, in units of 10^e.
  const double y_max = std::max({a.outputs[0].variance, a.outputs[0].rms_max.value_or(0.0) *
                                                             a.outputs[0].rms_max.value_or(0.0)}) * 1.06;
  CHECK(panel.y.scale == AxisScale::kLinear);
  REQUIRE(panel.y.min);
  CHECK(*panel.y.min == 0.0);
  const double shown = *panel.y.max;
  CHECK(shown > 0.0);
  CHECK(std::fmod(std::log10(y_max / shown) + 100.0, 1.0) == doctest::Approx(0.0).epsilon(1e-6));  // y_max / 10^e
  CHECK(total_a->y_divisor == doctest::Approx(y_max / shown));
  CHECK(panel.y2.shown);
  // The requirement at its variance, and whether each side meets it.
  const double req = *a.outputs[0].rms_max;
  REQUIRE(panel.annotations.size() == 1);
  CHECK(panel.annotations[0].kind == AnnotationKind::kHorizontalLine);
  CHECK(panel.annotations[0].y0 * total_a->y_divisor == doctest::Approx(req * req));
  CHECK(panel.annotations[0].key == "requirement: " + Short(req) + " (A pass, B pass)");
  // PSD at most kOverlayPsdDecades deep, clipped to the same frequencies.
  const FigurePanel& psd = plots[0].figure.panels.at(0);
  CHECK(psd.y.scale == AxisScale::kLog);
  REQUIRE(psd.y.min);
  CHECK(std::log10(*psd.y.max / *psd.y.min) <= kOverlayPsdDecades + 1.0 + 1e-9);
  CHECK(*psd.x.min == *panel.x.min);
  CHECK(*psd.x.max == *panel.x.max);
  CHECK(psd.annotations.empty());
}

TEST_CASE("an overlay leaves out a contributor negligible in both results, and keeps one that appears") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  BudgetResult a = Evaluate(budget);
  a.outputs[0].contributors[1].variance = 1e-9 * a.outputs[0].variance;  // sensor_noise negligible
  REQUIRE(a.outputs[0].contributors[1].variance < kNegligibleShare * a.outputs[0].variance);
  CHECK(FindSeries(OverlayPlots("A", a, "B", a)[0].figure, "A: sensor_noise") == nullptr);
  CHECK(FindSeries(OverlayPlots("A", a, "B", a)[0].figure, "B: sensor_noise") == nullptr);
  BudgetResult b = a;
  b.outputs[0].contributors[1].variance = 0.5 * b.outputs[0].variance;  // appears in B: both sides drawn
  const PlotFigure figure = OverlayPlots("A", a, "B", b)[0].figure;
  const FigureSeries* sensor_a = FindSeries(figure, "A: sensor_noise");
  REQUIRE(sensor_a);
  CHECK(sensor_a->key.find("A: sensor\\_noise") == 0);  // the name as enhanced text
  CHECK(FindSeries(figure, "B: sensor_noise"));
  // Keys as the tables: 4 digits, and a part computed as rounding reads 0 (compare.pdf had "6.14·10⁻¹³" where
  // its table reads 0).
  const FigureSeries* total_b = FindSeries(figure, "B: total");
  REQUIRE(total_b);
  CHECK(total_b->key == "B: total " + SigLabel(b.outputs[0].rms(), 4));
  a.outputs[0].contributors[1].variance = 1e-30 * a.outputs[0].variance;
  const PlotFigure with_rounding = OverlayPlots("A", a, "B", b)[0].figure;
  const FigureSeries* rounded = FindSeries(with_rounding, "A: sensor_noise");
  REQUIRE(rounded);
  CHECK(rounded->key == "A: sensor\\_noise 0");
}

}  // namespace deb::report
