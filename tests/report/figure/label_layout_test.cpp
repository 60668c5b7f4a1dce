// deb/report/figure/label_layout.h: a marker's label lies inside the axes
// and over no other label, or names the marker in the key. Checked on
// constructed panels, and on every figure of the shipped budgets with
// markers (the loops' margins, the CPS crossings).
#include "deb/report/figure/label_layout.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/loop_plots.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/report_options.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

FigurePanel LogPanel() {
  FigurePanel p;
  p.x.scale = AxisScale::kLog;
  p.x.min = 0.1;
  p.x.max = 1000.0;
  p.y.min = 0.0;
  p.y.max = 10.0;
  return p;
}

FigureAnnotation Marker(double x, double y, const std::string& label) {
  FigureAnnotation a;
  a.kind = AnnotationKind::kMarker;
  a.x0 = x;
  a.y0 = y;
  a.label = label;
  return a;
}

// Every labelled marker's box inside the axes, no two overlapping.
void CheckPlaced(const FigurePanel& p, double share = 1.0) {
  std::vector<LabelBox> boxes;
  for (const FigureAnnotation& a : p.annotations) {
    if (a.kind != AnnotationKind::kMarker || a.label.empty()) continue;
    const auto box = LabelBoxOf(p, a, share);
    if (!box) continue;
    CHECK_MESSAGE(box->Inside(), a.label);
    for (const LabelBox& b : boxes) CHECK_MESSAGE(!box->Overlaps(b), a.label);
    boxes.push_back(*box);
    for (const FigureAnnotation& other : p.annotations)  // over no other marker's point
      if (&other != &a && other.kind == AnnotationKind::kMarker)
        if (const auto at = PlotFraction(p, other))
          CHECK_MESSAGE(!(at->first > box->x0 && at->first < box->x1 && at->second > box->y0 && at->second < box->y1),
                        a.label);
  }
}

}  // namespace

TEST_CASE("labels go right of their point, left near the right edge, and apart from each other") {
  FigurePanel p = LogPanel();
  p.annotations = {Marker(1.0, 5.0, "PM 34.31° at 1 Hz"), Marker(900.0, 5.0, "GM 16.14 dB at 900 Hz"),
                   Marker(1.2, 5.0, "GM -15.61 dB at 1.2 Hz")};
  PlaceMarkerLabels(p);
  CHECK_FALSE(p.annotations[0].label_left);
  CHECK(p.annotations[0].label_dy == 1.0);
  CHECK(p.annotations[1].label_left);  // right of 900 Hz would leave the axes
  // The third would sit on the first: it goes below.
  CHECK(p.annotations[2].label_dy < 0.0);
  CheckPlaced(p);
  // No label lies over another marker's point.
  for (const FigureAnnotation& a : p.annotations)
    for (const FigureAnnotation& other : p.annotations) {
      if (&a == &other || a.label.empty()) continue;
      const auto box = LabelBoxOf(p, a);
      const auto at = PlotFraction(p, other);
      REQUIRE(box);
      REQUIRE(at);
      CHECK_FALSE((at->first > box->x0 && at->first < box->x1 && at->second > box->y0 && at->second < box->y1));
    }
}

TEST_CASE("a label is not struck through by a horizontal line: a requirement or a band's limit") {
  FigurePanel p = LogPanel();
  // A line one label-line above the point (where the label would go first),
  // as optical_table's band limit ran through its 50 Hz tone's label.
  const double line = kLabelLineHeight * 10.0;  // in y units of [0, 10]
  FigureAnnotation limit;
  limit.kind = AnnotationKind::kSegment;
  limit.x0 = 1.0;
  limit.x1 = 100.0;
  limit.y0 = limit.y1 = 5.0 + line;
  p.annotations.push_back(limit);
  p.annotations.push_back(Marker(10.0, 5.0, "tone 50 Hz: 0.3470 nm RMS"));
  PlaceMarkerLabels(p);
  const FigureAnnotation& m = p.annotations.back();
  REQUIRE_FALSE(m.label.empty());
  CHECK(m.label_dy == -1.0);  // below, where no line runs
  const LabelBox box = *LabelBoxOf(p, m);
  CHECK_FALSE((box.y0 < 0.5 + kLabelLineHeight && box.y1 > 0.5 + kLabelLineHeight));
  // The same without the line goes above.
  p.annotations.erase(p.annotations.begin());
  PlaceMarkerLabels(p);
  CHECK(p.annotations.back().label_dy == 1.0);
}

TEST_CASE("a label that fits nowhere names its marker in the key, and a panel without a key gets one") {
  FigurePanel p = LogPanel();
  p.key.placement = KeyPlacement::kNone;
  const std::string long_label(100, 'x');
  p.annotations = {Marker(10.0, 5.0, long_label)};
  PlaceMarkerLabels(p);
  // The key names it by a number placed beside the point, as a label is.
  CHECK(p.annotations[0].label == "(1)");
  CHECK(p.annotations[0].label_dy == 1.0);
  CHECK(p.annotations[0].key == "(1) " + long_label);
  CHECK(p.key.placement == KeyPlacement::kOutsideRight);
  // A second such marker is (2).
  p.annotations = {Marker(10.0, 5.0, long_label), Marker(100.0, 2.0, long_label)};
  PlaceMarkerLabels(p);
  CHECK(p.annotations[0].key == "(1) " + long_label);
  CHECK(p.annotations[1].key == "(2) " + long_label);
  // Escapes and markup do not count: "a\_b^{2}" shows 4 characters.
  FigureAnnotation a = Marker(1.0, 5.0, "a\\_b^{2}");
  const auto box = LabelBoxOf(LogPanel(), a);
  REQUIRE(box);
  CHECK(box->x1 - box->x0 == doctest::Approx(4 * kLabelCharWidth));
}

TEST_CASE("every marker label of the shipped budgets' figures lies inside its axes and over no other") {
  std::size_t labels = 0;
  for (const char* name : {"wafer_stage.yaml", "guide/feedback_loop.yaml", "measured_stage.yaml"}) {
    CAPTURE(name);
    const BudgetResult result = Evaluate(LoadBudgetFile(test::ExampleBudget(name)));
    std::vector<Plot> plots = LoopPlots(result);
    for (std::size_t o = 0; o < result.outputs.size(); ++o)
      for (Plot& p : SpectrumPlots(result, o, ReportOptions{})) plots.push_back(std::move(p));
    for (const Plot& plot : plots) {
      double total = 0.0;
      for (const FigurePanel& panel : plot.figure.panels) total += panel.height;
      for (FigurePanel panel : plot.figure.panels) {
        const double share = plot.figure.panels.size() > 1 ? panel.height / total : 1.0;
        PlaceMarkerLabels(panel, share);
        CheckPlaced(panel, share);
        for (const FigureAnnotation& a : panel.annotations) labels += a.kind == AnnotationKind::kMarker;
      }
    }
  }
  CHECK(labels >= 6);  // wafer_stage: a phase margin, three gain margins, |S|'s peak, CPS crossings
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a marker's label keeps off the curves where a place beside its point allows") {
  // A curve rising through the point from bottom left to top right, as a
  // tone's marker on a rising PSD (measured_stage's 50 Hz label lay over
  // the curves): right-above and left-below meet it, so the label goes
  // left-above (the next place tried) or right-below, clear of it.
  FigurePanel p = LogPanel();
  std::vector<std::pair<double, double>> curve;
  for (double x = 0.1; x <= 1000.0; x *= 1.2) curve.push_back({x, 2.5 + 1.25 * std::log10(x)});  // 1.25 .. 6.25
  p.label_obstacles.push_back(curve);
  p.annotations.push_back(Marker(10.0, 3.75, "tone 10 Hz: 0.5 nm RMS"));
  PlaceMarkerLabels(p);
  const FigureAnnotation& a = p.annotations[0];
  REQUIRE_FALSE(a.label.empty());
  const LabelBox box = *LabelBoxOf(p, a);
  // Clear of the curve: at the box's left and right ends the curve is above
  // or below the whole box.
  const auto curve_at = [](double fx) { return (2.5 + 1.25 * (fx * 4.0 - 1.0)) / 10.0; };  // fraction of y at fraction x
  const bool above = curve_at(box.x0) > box.y1 && curve_at(box.x1) > box.y1;
  const bool below = curve_at(box.x0) < box.y0 && curve_at(box.x1) < box.y0;
  CHECK((above || below));
  CHECK(a.label_left == (a.label_dy > 0.0));  // left-above or right-below: the sides the curve leaves free
  CHECK(a.label_left);
  // Without the curve the first place is right and above, as before.
  FigurePanel q = LogPanel();
  q.annotations.push_back(Marker(10.0, 3.75, "tone 10 Hz: 0.5 nm RMS"));
  PlaceMarkerLabels(q);
  CHECK_FALSE(q.annotations[0].label_left);
  CHECK(q.annotations[0].label_dy == 1.0);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a label that cannot keep off the curves stays next to its point, never two lines away") {
  // Curves every 0.4 of the y axis (of 10) leave no place clear: the label
  // goes over one, a line from its point, where it reads as that marker's
  // (two lines up, wafer_stage's "GM 74.63 dB at 4153 Hz" sat by another
  // marker).
  FigurePanel p = LogPanel();
  for (double y = 0.2; y < 10.0; y += 0.4) p.label_obstacles.push_back({{0.1, y}, {1000.0, y}});
  p.annotations.push_back(Marker(10.0, 5.0, "GM 16.14 dB at 313.0 Hz"));
  PlaceMarkerLabels(p);
  const FigureAnnotation& a = p.annotations[0];
  REQUIRE_FALSE(a.label.empty());
  CHECK(std::fabs(a.label_dy) == 1.0);
  // Horizontal lines a line above and below the point (requirements) take
  // its adjacent places: the label goes into the key, not two lines away.
  FigurePanel q = LogPanel();
  for (double y = 0.2; y < 10.0; y += 0.4) q.label_obstacles.push_back({{0.1, y}, {1000.0, y}});
  for (const double y : {5.6, 4.4}) {
    FigureAnnotation line;
    line.kind = AnnotationKind::kHorizontalLine;
    line.y0 = y;
    q.annotations.push_back(line);
  }
  q.annotations.push_back(Marker(10.0, 5.0, "GM 74.63 dB at 4153 Hz"));
  PlaceMarkerLabels(q);
  const FigureAnnotation& b = q.annotations.back();
  CHECK(b.label.empty());
  CHECK(b.key == "GM 74.63 dB at 4153 Hz");
}

}  // namespace deb::report
