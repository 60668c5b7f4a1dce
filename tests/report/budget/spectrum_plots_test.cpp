#include "deb/report/budget/spectrum_plots.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "deb/budget/engine.h"
#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/report_writer.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("the RMS axis puts each label r at the variance r squared, thinned near zero") {
  // Variance axis up to 420 (RMS 20.5): step 5 -> labels 0, 10, 15, 20 at
  // 0, 100, 225, 400; 5 at 25 is within 8 % of the axis from 0 and gives way.
  CHECK(RmsTics(420.0) == "set y2tics nomirror ('0' 0, '10' 100, '15' 225, '20' 400)");
  // In units of 10^6: labels at r^2 / 1e6.
  CHECK(RmsTics(4.2e6, 1e6).find("'2000' 4") != std::string::npos);
  // Up to 1e4 (RMS 100): 20 would sit at 400 = 4 % of the axis, on the 0
  // in report.pdf's short CPS figures: it gives way, 40 at 16 % stays.
  const std::string tics = RmsTics(1e4);
  CHECK(tics.find("'20' 400") == std::string::npos);
  CHECK(tics.find("'40' 1600") != std::string::npos);
  CHECK(tics.find("'100' 10000") != std::string::npos);
  // The total gets its own tic; regular ones within 12 % of the axis give
  // way (15 at 225 is 6.7 % from 14.03 at 196.8: in report.pdf's short CPS
  // figures the two labels touched, as wafer_stage's 2.173 and 2; h0's
  // 1.897 and 2, 10 % apart, touched in a figure drawn at 2/3 height).
  CHECK(RmsTics(420.0, 1.0, {{14.03, "14.0"}}) == "set y2tics nomirror ('0' 0, '10' 100, '14.0' 196.8409, '20' 400)");
  CHECK(RmsTics(420.0, 1.0, {{19.9, "19.9"}}).find("'20' 400") == std::string::npos);
  // Total and requirement both marked; a requirement crowding the total gives way.
  CHECK(RmsTics(420.0, 1.0, {{14.03, "14.0"}, {20, "20"}}).find("'14.0' 196.8409, '20' 400") != std::string::npos);
  CHECK(RmsTics(420.0, 1.0, {{14.03, "14.0"}, {14.2, "14.2"}}).find("14.2") == std::string::npos);
}

TEST_CASE("the display range holds all but a thousandth of every contributor's variance, in whole decades") {
  const FrequencyGrid grid = FrequencyGrid::Log(1e-4, 1e8, 1201);
  OutputResult o;
  ContributorResult c;
  // A white PSD on 3..70 Hz: the CPS rises linearly between the band edges.
  for (double f : grid.f_hz()) c.psd.push_back(f >= 3 && f <= 70 ? 1.0 : 0.0);
  double sum = 0.0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (k) sum += 0.5 * (c.psd[k] + c.psd[k - 1]) * (grid.f_hz()[k] - grid.f_hz()[k - 1]);
    c.cps.push_back(sum);
  }
  c.variance = sum;
  o.contributors.push_back(c);
  const FrequencyRange r = DisplayRange(o, grid);
  CHECK(r.trimmed);
  CHECK(r.lo_hz == doctest::Approx(1.0));
  CHECK(r.hi_hz == doctest::Approx(100.0));
  CHECK(RangeCaption(r) == " Shown: 1–100 Hz; the CSV covers the whole grid.");
  // The note is a second line of the x label, so gnuplot makes room for it
  // below the tic labels instead of printing it over the frame (a label at screen coordinates).
  const std::string axis = FrequencyAxis(r, grid);
  CHECK(axis.find("set xlabel ('frequency [Hz]'.\"\\n\".'{/*0.9 grid: 10^{-4} to 10^{8} Hz; shown: the decades holding "
                  "all but 10^{-3} of every contributor''s variance}')") != std::string::npos);
  CHECK(axis.find("at screen") == std::string::npos);
  CHECK(FrequencyAxis(r, grid, "what is shown").find("shown: what is shown}") != std::string::npos);
  // A contributor spread over the whole grid keeps the whole grid.
  ContributorResult flat;
  flat.cps = {0.0};
  for (std::size_t k = 1; k < grid.size(); ++k) flat.cps.push_back(static_cast<double>(k));
  flat.variance = flat.cps.back();
  o.contributors.push_back(flat);
  CHECK_FALSE(DisplayRange(o, grid).trimmed);
  CHECK(RangeCaption(DisplayRange(o, grid)).empty());
  CHECK(FrequencyAxis(DisplayRange(o, grid), grid).find("set xlabel 'frequency [Hz]'\n") != std::string::npos);
}

TEST_CASE("share order sorts contributors by variance, largest first, ties in budget order") {
  OutputResult o;
  for (double v : {1.0, 5.0, 1.0, 3.0}) {
    ContributorResult c;
    c.variance = v;
    o.contributors.push_back(c);
  }
  CHECK(ShareOrder(o) == std::vector<std::size_t>{1, 3, 0, 2});
}

TEST_CASE("the stacked CPS plot reads its own CSV, whose top layer sums to the total CPS") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  ReportOptions options;
  options.reverse_cps = true;
  const std::vector<Plot> plots = SpectrumPlots(result, 0, options);
  REQUIRE(plots.size() == 3);
  CHECK(plots[0].name == "z_velocity_cps");
  CHECK(plots[1].name == "z_velocity_reverse_cps");
  CHECK(plots[2].name == "z_velocity_psd");
  for (const Plot& p : plots) CHECK(p.script.find("'" + p.name + ".csv'") != std::string::npos);
  // The last data row of the CPS CSV: contributors add up to the total.
  const std::string& csv = plots[0].csv;
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  double f, a, b, total;
  REQUIRE(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf", &f, &a, &b, &total) == 4);
  CHECK(a + b == doctest::Approx(total).epsilon(1e-9));
  CHECK(total == doctest::Approx(result.outputs[0].variance).epsilon(1e-9));
  // The requirement is a limit line at rms_max^2 = 400 whose key says it passes.
  const PlotFigure& cps = plots[0].figure;
  REQUIRE(cps.panels.size() == 1);
  REQUIRE(cps.panels[0].annotations.size() == 1);  // a pass: no crossing to mark
  CHECK(cps.panels[0].annotations[0].kind == AnnotationKind::kHorizontalLine);
  CHECK(cps.panels[0].annotations[0].y0 == doctest::Approx(400.0));
  CHECK(cps.panels[0].annotations[0].key == "requirement: 20 (pass)");
  // The reverse CPS starts at the total variance.
  const std::string& rev = plots[1].csv;
  const std::size_t first_row = rev.find('\n', rev.find('\n') + 1) + 1;
  REQUIRE(std::sscanf(rev.c_str() + first_row, "%lf,%lf,%lf,%lf", &f, &a, &b, &total) == 4);
  CHECK(total == doctest::Approx(result.outputs[0].variance).epsilon(1e-9));
}

TEST_CASE("the variance axis of a large output is scaled by a power of ten named in its label") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = SpectrumPlots(result, 1, {});  // z_displacement, variance ~ 2.6e6 nm^2
  CHECK(plots[0].script.find("[10^{6} nm^{2}]") != std::string::npos);
  CHECK(plots[0].script.find("/1000000)") != std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a failing output's CPS figure names its fail factor, stacks the largest on top and marks the crossing") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const OutputResult& out = result.outputs[0];  // position: 2.114 nm against 1.5 nm
  REQUIRE_FALSE(out.pass());
  const std::vector<Plot> plots = SpectrumPlots(result, 0, {});
  const FigurePanel& cps = plots[0].figure.panels.at(0);
  CHECK(cps.title == "position: " + SigLabel(out.rms(), 4) + " nm RMS, FAIL " + SigLabel(out.rms() / 1.5, 4) +
                         "× over 1.5 nm");
  // Layers in key order: decreasing variance; each lies on all smaller ones. The budget is grouped: the
  // layers are its top level.
  const PlotLevel top = GroupLevel(out, result.grid, "");
  const OutputResult& items = top.out;
  const std::vector<std::size_t> order = ShareOrder(items);
  std::vector<const FigureSeries*> layers;
  for (const FigureSeries& s : cps.series)
    if (s.kind == SeriesKind::kFilled) layers.push_back(&s);
  REQUIRE(layers.size() == items.contributors.size());
  for (std::size_t i = 0; i < layers.size(); ++i) {
    CHECK(layers[i]->name == items.contributors[order[i]].name);
    CHECK(layers[i]->low_columns.size() == layers.size() - 1 - i);
    CHECK(layers[i]->y_columns.back() == 2 + order[i]);
    CHECK(layers[i]->colour == top.styles[order[i]].colour);
  }
  // The total is drawn last, reading the total column.
  CHECK(cps.series.back().name == "total");
  CHECK(cps.series.back().y_columns == std::vector<std::size_t>{2 + items.contributors.size()});
  // Headroom above the total.
  CHECK(*cps.y.max >= 1.1 * out.variance);
  // The limit line and a marker where the cumulative RMS reaches it, at the guidance's frequency.
  const std::optional<FailureGuidance> guide = GuideFailure(out, result.grid);
  REQUIRE(guide);
  REQUIRE(guide->overall->cps_crossing_hz);
  const auto marker = std::find_if(cps.annotations.begin(), cps.annotations.end(),
                                   [](const FigureAnnotation& a) { return a.kind == AnnotationKind::kMarker; });
  REQUIRE(marker != cps.annotations.end());
  CHECK(marker->x0 == doctest::Approx(*guide->overall->cps_crossing_hz));
  CHECK(marker->y0 == doctest::Approx(1.5 * 1.5));
  // Its text is in the key, not over the stacked layers.
  CHECK(marker->label.empty());
  CHECK(marker->key.rfind("RMS reaches 1.5 ", 0) == 0);
  CHECK(cps.annotations[0].key == "requirement: 1.5 (FAIL)");

  // The PSD: the top-level items largest first, the total last, each band requirement
  // a segment at the flat PSD that uses its whole allowance.
  const FigurePanel& psd = plots[1].figure.panels.at(0);
  for (std::size_t i = 0; i < order.size(); ++i) CHECK(psd.series[i].name == items.contributors[order[i]].name);
  CHECK(psd.series.back().name == "total");
  // The total, on top, is narrower than the contributors: one that dominates shows on both sides of it.
  CHECK(psd.series.back().width < psd.series.front().width);
  REQUIRE(psd.annotations.size() == 3);
  CHECK(psd.annotations[0].kind == AnnotationKind::kSegment);
  // A bracket, ends and key sample: a group's dashed curve in a similar red is not one.
  CHECK(psd.annotations[0].bracket);
  CHECK(psd.annotations[0].behind);  // a contributor at the limit's level stays visible over it
  CHECK(plots[1].script.find("heads size screen 0.008,90") != std::string::npos);
  CHECK(plots[1].script.find("keyentry with vectors heads size screen 0.008,90") != std::string::npos);
  CHECK(psd.annotations[0].y0 == doctest::Approx(0.8 * 0.8 / (10 - 0.1)));
  CHECK(psd.annotations[1].y0 == doctest::Approx(2.0 * 2.0 / (100 - 10)));
  CHECK(psd.annotations[0].key.find("(FAIL)") != std::string::npos);
  CHECK(plots[1].caption.find("whole allowance") != std::string::npos);
}

TEST_CASE("a contributor that is zero on an output stays in the key as 0") {
  BudgetResult result;
  result.grid = FrequencyGrid::Log(1.0, 100.0, 21);
  OutputResult out;
  out.name = "x";
  out.unit = "nm";
  for (const char* name : {"a", "zero"}) {
    ContributorResult c;
    c.name = name;
    c.psd.assign(21, std::string(name) == "a" ? 1.0 : 0.0);
    c.cps.assign(21, 0.0);
    for (std::size_t k = 1; k < 21; ++k)
      c.cps[k] = c.cps[k - 1] + 0.5 * (c.psd[k] + c.psd[k - 1]) * (result.grid.f_hz()[k] - result.grid.f_hz()[k - 1]);
    c.variance = c.cps.back();
    out.contributors.push_back(c);
  }
  out.total_psd = out.contributors[0].psd;
  out.total_cps = out.contributors[0].cps;
  out.variance = out.contributors[0].variance;
  result.outputs.push_back(out);
  const std::vector<Plot> plots = SpectrumPlots(result, 0, {});
  const FigureSeries* zero = FindSeries(plots[0].figure, "zero");
  REQUIRE(zero != nullptr);
  CHECK(zero->key == "zero: 0 (0 %)");
  REQUIRE(FindSeries(plots[1].figure, "zero") != nullptr);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the captions state an output's weighting and metric") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  REQUIRE(result.outputs[1].metric);
  const std::vector<Plot> plots = SpectrumPlots(result, 1, {});
  CHECK(plots[0].caption.find(" Metric: " + result.outputs[1].metric->Describe()) != std::string::npos);
  CHECK(plots[1].caption.find(" Metric: ") != std::string::npos);
  // Without a weighting or metric, nothing is added.
  CHECK(SpectrumPlots(result, 0, {})[0].caption.find("Metric") == std::string::npos);
  const Budget thesis = LoadBudgetFile(test::ExampleBudget("nizamoglu2015_h210.yaml"));
  const BudgetResult thesis_result = Evaluate(thesis);
  for (std::size_t o = 0; o < thesis.outputs.size(); ++o) {
    if (!thesis.outputs[o].weighting) continue;
    CHECK(SpectrumPlots(thesis_result, o, {})[0].caption.find("The output is weighted by") !=
          std::string::npos);
    break;
  }
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("tones are triangles on the total at their frequencies, labelled with their RMS") {
  // measured_stage.yaml: mains hum at 50 Hz (0.2 mN) and 150 Hz (0.05 mN) through the loop.
  const Budget budget = LoadBudgetFile(test::ExampleBudget("measured_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = SpectrumPlots(result, 0, {});
  const auto psd = std::find_if(plots.begin(), plots.end(), [](const Plot& p) { return p.kind == PlotKind::kSpectrum; });
  REQUIRE(psd != plots.end());
  std::vector<FigureAnnotation> marks;
  for (const FigureAnnotation& a : psd->figure.panels.at(0).annotations)
    if (a.kind == AnnotationKind::kMarker && a.point_type == 9) marks.push_back(a);
  REQUIRE(marks.size() == 2);
  CHECK(marks[0].x0 == 50.0);  // the larger first
  CHECK(marks[1].x0 == 150.0);
  const OutputResult& out = result.outputs[0];
  std::size_t hum = 0;
  while (out.contributors[hum].name != "mains_hum") ++hum;
  CHECK(marks[0].label.find(SigLabel(std::sqrt(out.contributors[hum].tones[0].variance), 4)) != std::string::npos);
  CHECK(marks[0].colour == ContributorStyle(hum).colour);
  CHECK(psd->caption.find("Triangles mark tones") != std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a CPS axis fits the budget: a requirement far above is named at the top, one near is drawn as a line") {
  // optical_table: 0.9683 nm RMS against 2 nm, a limit 4.27x the variance (above kFarAbove = 3).
  const Budget budget = LoadBudgetFile(test::ExampleBudget("optical_table.yaml"));
  BudgetResult result = Evaluate(budget);
  const OutputResult& out = result.outputs.at(0);
  REQUIRE(out.rms_max);
  const auto cps_of = [&](const BudgetResult& r) {
    for (const Plot& p : SpectrumPlots(r, 0, {}))
      if (p.kind == PlotKind::kCps) return p;
    FAIL("no CPS plot");
    return Plot{};
  };
  const Plot far = cps_of(result);
  const FigurePanel& panel = far.figure.panels.at(0);
  REQUIRE(panel.y.max);
  // The axis: the total variance plus its headroom, not the limit's 4 nm^2.
  CHECK(*panel.y.max == doctest::Approx(1.12 * out.variance));
  bool named = false, line = false, entry = false;
  for (const FigureAnnotation& a : panel.annotations) {
    named |= a.kind == AnnotationKind::kText && a.label.find("requirement 2 nm RMS, above the axis") != std::string::npos;
    line |= a.kind == AnnotationKind::kHorizontalLine;
    entry |= a.kind == AnnotationKind::kKeyEntry && a.key.find("above the axis") != std::string::npos;
    // Text sits in the band above the headroom, which no data reaches (the total is at 1/1.12 of the axis).
    if (a.kind == AnnotationKind::kText) CHECK(a.y0 > 1.0 / 1.12 + 0.03);
  }
  CHECK(named);
  CHECK(entry);
  CHECK_FALSE(line);
  CHECK(far.caption.find("lies above the axis") != std::string::npos);
  // A limit twice the variance: the axis reaches it and the limit is a line.
  result.outputs[0].rms_max = std::sqrt(2.0 * out.variance);
  const Plot near = cps_of(result);
  CHECK(*near.figure.panels.at(0).y.max == doctest::Approx(1.12 * 2.0 * out.variance));
  bool near_line = false;
  for (const FigureAnnotation& a : near.figure.panels.at(0).annotations)
    near_line |= a.kind == AnnotationKind::kHorizontalLine;
  CHECK(near_line);
}

TEST_CASE("a contributor that is all of an output's PSD shows beside the total, a thin line drawn over it") {
  // single_axis_isolator's displacement is floor alone (100 %): its curve and the total coincide.
  const Budget budget = LoadBudgetFile(test::ExampleBudget("single_axis_isolator.yaml"));
  const BudgetResult result = Evaluate(budget);
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    const std::vector<Plot> plots = SpectrumPlots(result, o, {});
    const auto psd = std::find_if(plots.begin(), plots.end(), [](const Plot& p) { return p.kind == PlotKind::kSpectrum; });
    REQUIRE(psd != plots.end());
    const auto& series = psd->figure.panels.at(0).series;
    REQUIRE(series.size() >= 2);
    CHECK(series.back().name == "total");
    for (std::size_t k = 0; k + 1 < series.size(); ++k) {
      CAPTURE(series[k].name);
      // At least twice as wide: a band of the contributor's colour on each side of the total.
      CHECK(series[k].width >= 2.0 * series.back().width);
    }
  }
}

TEST_CASE("a measured reference is a grey dashed series on the PSD plot, NaN outside what it covers") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = SpectrumPlots(result, 0, {});
  const auto psd = std::find_if(plots.begin(), plots.end(), [](const Plot& p) { return p.kind == PlotKind::kSpectrum; });
  REQUIRE(psd != plots.end());
  const auto& series = psd->figure.panels.at(0).series;
  const auto ref = std::find_if(series.begin(), series.end(), [](const FigureSeries& s) { return s.name == "measured: measured"; });
  REQUIRE(ref != series.end());
  CHECK(ref->dash != "solid");
  CHECK(ref->y_columns == std::vector<std::size_t>{3 + GroupLevel(result.outputs[0], result.grid, "").out.contributors.size()});
  CHECK(series.back().name == "total");  // still drawn last
  // The first data row (0.1 Hz) lies below the measurement's 0.216 Hz: no point there.
  const std::string& csv = psd->csv;
  const std::size_t first = csv.find("\n0.1,");
  REQUIRE(first != std::string::npos);
  const std::string row = csv.substr(first + 1, csv.find('\n', first + 1) - first - 1);
  CHECK(row.substr(row.rfind(',') + 1) == "NaN");
  CHECK(psd->caption.find("measured reference") != std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("group CPS plots: one drill-down per group of two or more members, stacking its members") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = GroupCpsPlots(result, 0, 4);
  // environment, stage, stage/drive and metrology (facility has one member: no drill-down); the top level is the
  // output's main CPS plot.
  std::vector<std::string> names;
  for (const Plot& p : plots) names.push_back(p.name);
  CHECK(names == std::vector<std::string>{"position_cps_group_environment", "position_cps_group_stage",
                                          "position_cps_group_stage_drive", "position_cps_group_metrology"});
  // The data file is the plot's own.
  const Plot& stage = plots[1];
  CHECK(stage.script.find("position_cps_group_stage.csv") != std::string::npos);
  for (const FigureSeries& s : stage.figure.panels.at(0).series)
    if (!s.data.empty()) CHECK(s.data == "position_cps_group_stage.csv");
  CHECK(stage.caption.rfind("Group stage: ", 0) == 0);
  // The stage drill-down: cable_slab, y_crosstalk and drive/ (the subgroup summed), its total the stage's.
  CHECK(stage.csv.find("cable_slab") != std::string::npos);
  CHECK(stage.csv.find("drive/") != std::string::npos);
  CHECK(stage.csv.find("amplifier") == std::string::npos);
  double v = 0.0;
  for (const ContributorResult& c : result.outputs[0].contributors)
    if (c.group.rfind("stage", 0) == 0) v += c.variance;
  CHECK(stage.figure.panels.at(0).title.find(SigLabel(std::sqrt(v), 4)) != std::string::npos);
  // Without groups: none.
  const BudgetResult plain = Evaluate(LoadBudgetFile(test::ExampleBudget()));
  CHECK(GroupCpsPlots(plain, 0, 4).empty());
}

// The names of the stacked layers (CPS) or of the curves (PSD) of a figure, in the key's order.
std::vector<std::string> ItemNames(const Plot& p) {
  std::vector<std::string> names;
  for (const FigureSeries& s : p.figure.panels.at(0).series)
    if (s.name != "total" && s.name.rfind("edge below ", 0) != 0 && s.name.rfind("measured: ", 0) != 0)
      names.push_back(s.name);
  return names;
}

TEST_CASE("with groups the main CPS and PSD plots show the top level: each group summed exactly from its members") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  BudgetResult result = Evaluate(budget);
  // cooling_water out of its group (facility then has none): a contributor in no group stacks as itself.
  for (OutputResult& o : result.outputs)
    for (ContributorResult& c : o.contributors)
      if (c.name == "cooling_water") c.group.clear();
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    const OutputResult& out = result.outputs[o];
    const PlotLevel top = GroupLevel(out, result.grid, "");
    std::vector<std::string> names;
    for (const ContributorResult& c : top.out.contributors) names.push_back(c.name);
    CHECK(names == std::vector<std::string>{"cooling_water", "environment/", "stage/", "metrology/"});
    // The layers add up to the output's total CPS, at every frequency.
    for (std::size_t k = 0; k < out.total_cps.size(); ++k) {
      double sum = 0.0;
      for (const ContributorResult& c : top.out.contributors) sum += c.cps[k];
      REQUIRE(std::fabs(sum - out.total_cps[k]) <= 1e-12 * out.total_cps[k]);
    }
    double variance = 0.0;
    for (const ContributorResult& c : top.out.contributors) variance += c.variance;
    CHECK(std::fabs(variance - out.variance) <= 1e-12 * out.variance);
    // The figures stack (CPS) and draw (PSD) these items, largest first, and nothing else.
    const std::vector<Plot> plots = SpectrumPlots(result, o, {});
    REQUIRE(plots.size() >= 2);
    CHECK(plots[0].kind == PlotKind::kCps);
    CHECK(plots[1].kind == PlotKind::kSpectrum);
    std::vector<std::string> by_share;
    for (std::size_t i : ShareOrder(top.out)) by_share.push_back(top.out.contributors[i].name);
    CHECK(ItemNames(plots[0]) == by_share);
    CHECK(ItemNames(plots[1]) == by_share);
    CHECK(plots[0].caption.find("top-level groups") != std::string::npos);
    CHECK(plots[0].csv.find("floor") == std::string::npos);  // no contributor of a group on its own
    // The top level shows the output's range and keeps its requirement.
    CHECK(top.range.lo_hz == DisplayRange(out, result.grid).lo_hz);
    CHECK(top.range.hi_hz == DisplayRange(out, result.grid).hi_hz);
    CHECK(top.out.rms_max == out.rms_max);
  }
  // Without groups nothing changes: the contributors themselves.
  const BudgetResult plain = Evaluate(LoadBudgetFile(test::ExampleBudget()));
  const PlotLevel level = GroupLevel(plain.outputs[0], plain.grid, "");
  REQUIRE(level.out.contributors.size() == plain.outputs[0].contributors.size());
  for (std::size_t c = 0; c < level.out.contributors.size(); ++c) {
    CHECK(level.out.contributors[c].name == plain.outputs[0].contributors[c].name);
    CHECK(level.styles[c].colour == ContributorStyle(c).colour);
  }
  CHECK(SpectrumPlots(plain, 0, {})[0].caption.find(", contributors stacked by share") != std::string::npos);
}

TEST_CASE("a contributor and a group keep one colour in the main plots, every drill-down and colours.csv") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::size_t n = budget.contributors.size();
  const std::vector<GroupResult> groups = ComputeGroups(result.outputs[0]);
  // The colour each item must have: a contributor's by its budget index, a group's after the contributors.
  std::map<std::string, std::string> expected;
  for (std::size_t c = 0; c < n; ++c) expected[budget.contributors[c].name] = ContributorStyle(c).colour;
  for (std::size_t g = 0; g < groups.size(); ++g) expected[groups[g].name + "/"] = GroupStyle(n, g).colour;
  std::map<std::string, std::set<std::string>> seen;  // item -> its colours in every figure
  std::size_t drill_downs = 0;
  for (std::size_t o = 0; o < result.outputs.size(); ++o)
    for (const Plot& p : SpectrumPlots(result, o, {})) {
      drill_downs += p.name.find("_cps_group_") != std::string::npos;
      for (const FigureSeries& s : p.figure.panels.at(0).series)
        if (expected.count(s.name)) seen[s.name].insert(s.colour);
    }
  CHECK(drill_downs == 4 * result.outputs.size());
  for (const auto& item : seen) {
    INFO(item.first);  // not a structured binding: clang cannot capture one in INFO's lambda
    CHECK(item.second == std::set<std::string>{expected.at(item.first)});
  }
  // Every group somewhere, every contributor in a drill-down but cooling_water, facility's only member (shown as
  // facility/).
  CHECK(seen.size() + 1 == expected.size());
  CHECK(seen.count("cooling_water") == 0);
  // No two items share a colour.
  std::set<std::string> distinct;
  for (const auto& [name, colour] : expected) distinct.insert(colour);
  CHECK(distinct.size() == expected.size());
  // colours.csv lists the groups after the contributors, in these colours.
  const test::fs::path dir = test::TempDir("group_colours") / "report";
  ReportOptions options;
  options.plots = false;
  WriteReportDirectory(result, {}, options, dir.string());
  const std::string csv = test::ReadAll(dir / "plots" / "colours.csv");
  for (std::size_t g = 0; g < groups.size(); ++g)
    CHECK(csv.find("\n" + std::to_string(n + g) + "," + groups[g].path + "/," + GroupStyle(n, g).colour + ",") !=
          std::string::npos);
}

TEST_CASE("a measured reference is drawn on the CPS plot: its cumulative variance over the range it covers") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const OutputResult& out = result.outputs[0];
  REQUIRE(out.references.size() == 1);
  const ReferenceResult& r = out.references[0];
  ReportOptions options;
  options.reverse_cps = true;
  const std::vector<Plot> plots = SpectrumPlots(result, 0, options);
  const Plot& cps = plots.at(0);
  REQUIRE(cps.kind == PlotKind::kCps);
  const auto& series = cps.figure.panels.at(0).series;
  const auto ref = std::find_if(series.begin(), series.end(), [](const FigureSeries& s) { return s.name == "measured: measured"; });
  REQUIRE(ref != series.end());
  CHECK(ref->dash == kReferenceDash);
  CHECK(ref->colour == kReferenceColour);
  CHECK(ref->kind == SeriesKind::kLine);
  CHECK(ref->key.find(SigLabel(std::sqrt(r.variance), 4)) != std::string::npos);  // its RMS in the key
  const std::size_t items = GroupLevel(out, result.grid, "").out.contributors.size();
  CHECK(ref->y_columns == std::vector<std::size_t>{3 + items});
  CHECK(series.back().name == "total");
  CHECK(cps.caption.find("measured reference") != std::string::npos);
  // Its column: NaN outside what it covers; inside, the reference's CPS, reaching its variance at the top.
  std::istringstream rows(cps.csv);
  std::string line;
  std::size_t inside = 0, outside = 0;
  double last = 0.0;
  while (std::getline(rows, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("frequency_hz", 0) == 0) continue;
    const double f_hz = std::stod(line.substr(0, line.find(',')));
    const std::string cell = line.substr(line.rfind(',') + 1);
    if (f_hz < r.covered_lo_hz || f_hz > r.covered_hi_hz) {
      CHECK(cell == "NaN");
      ++outside;
      continue;
    }
    ++inside;
    const std::size_t k = static_cast<std::size_t>(
        std::lower_bound(result.grid.f_hz().begin(), result.grid.f_hz().end(), f_hz * (1 - 1e-9)) -
        result.grid.f_hz().begin());
    CHECK(std::stod(cell) == doctest::Approx(r.cps[k]).epsilon(1e-9));
    last = std::stod(cell);
  }
  CHECK(inside > 10);
  CHECK(outside > 0);
  CHECK(last == doctest::Approx(r.variance).epsilon(1e-6));
  // The axis holds it (the measurement exceeds the budget here).
  CHECK(cps.figure.panels.at(0).y.max.value() * cps.figure.panels.at(0).series.back().y_divisor >= r.variance);
  // The reverse CPS does not draw it.
  const auto reverse = std::find_if(plots.begin(), plots.end(), [](const Plot& p) { return p.kind == PlotKind::kReverseCps; });
  REQUIRE(reverse != plots.end());
  CHECK(reverse->csv.find("measured") == std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a contributor broken down by channel gets a CPS whose channel layers add up to it") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("nizamoglu2015_h210.yaml"));
  const BudgetResult result = Evaluate(budget);
  const OutputResult& out = result.outputs[0];  // z_velocity
  std::size_t sensor = out.contributors.size();
  for (std::size_t c = 0; c < out.contributors.size(); ++c)
    if (!out.contributors[c].channels.empty()) sensor = c;
  REQUIRE(sensor < out.contributors.size());
  const ContributorResult& contributor = out.contributors[sensor];
  CHECK(contributor.cross_variance == 0.0);  // independent geophones
  const PlotLevel level = ChannelLevel(out, result.grid, sensor);
  // The layers are the channels the output sees; the others (the x and y
  // geophones on z, by symmetry) are named in the caption instead.
  std::size_t seen = 0;
  for (const ContributorResult::ChannelPart& part : contributor.channels)
    seen += RoundingZero(part.variance, contributor.variance) ? 0 : 1;
  REQUIRE(seen >= 2);
  REQUIRE(seen < contributor.channels.size());
  REQUIRE(level.out.contributors.size() == seen);
  CHECK(level.items.find(": nothing of this output, not drawn)") != std::string::npos);
  // The layers are the channels' parts, and sum to the contributor at every frequency.
  double worst = 0.0;
  for (std::size_t k = 0; k < result.grid.size(); ++k) {
    double sum = 0.0;
    for (const ContributorResult& layer : level.out.contributors) sum += layer.cps[k];
    worst = std::max(worst, std::abs(sum - contributor.cps[k]) / contributor.variance);
  }
  CHECK(worst < 1e-12);
  CHECK(level.out.variance == contributor.variance);
  CHECK_FALSE(level.out.rms_max.has_value());
  // One plot per output for this contributor, under its own file name.
  const std::vector<Plot> plots = ChannelCpsPlots(result, 0, 4);
  REQUIRE(plots.size() == 1);
  CHECK(plots[0].name == "z_velocity_cps_channels_" + contributor.name);
  CHECK(plots[0].script.find("'" + plots[0].name + ".csv'") != std::string::npos);
  CHECK(plots[0].caption.rfind("Contributor " + contributor.name + " by source channel", 0) == 0);
  // A budget without a breakdown has none.
  const Budget plain = LoadBudgetFile(test::ExampleBudget());
  CHECK(ChannelCpsPlots(Evaluate(plain), 0, 4).empty());
}

}  // namespace deb::report
