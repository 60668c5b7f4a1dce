#include "deb/report/figure/label_layout.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace deb::report {
namespace {

// The fraction of `axis` at which `v` lies; none without an explicit range.
std::optional<double> Fraction(const FigureAxis& axis, double v) {
  if (!axis.min || !axis.max || !(*axis.max > *axis.min)) return std::nullopt;
  if (axis.scale == AxisScale::kLog) {
    if (!(v > 0.0 && *axis.min > 0.0)) return std::nullopt;
    return std::log10(v / *axis.min) / std::log10(*axis.max / *axis.min);
  }
  return (v - *axis.min) / (*axis.max - *axis.min);
}

// Whether the segment a-b (plot fractions) meets box `b` (Liang-Barsky
// clipping of the segment to the box).
bool SegmentMeets(std::pair<double, double> a, std::pair<double, double> e, const LabelBox& box) {
  const double dx = e.first - a.first, dy = e.second - a.second;
  double lo = 0.0, hi = 1.0;
  const auto clip = [&](double p, double q) {  // p t <= q
    if (p == 0.0) return q >= 0.0;
    const double t = q / p;
    if (p < 0.0) lo = std::max(lo, t);
    else hi = std::min(hi, t);
    return lo <= hi;
  };
  return clip(-dx, a.first - box.x0) && clip(dx, box.x1 - a.first) && clip(-dy, a.second - box.y0) &&
         clip(dy, box.y1 - a.second);
}

// A character's width and a line's height in a panel with `share` of its
// figure's height (< 1: one of a stack).
double CharWidth(double share) { return share < 1.0 ? kStackedLabelCharWidth : kLabelCharWidth; }
double LineHeight(double share) { return (share < 1.0 ? kStackedLabelLineHeight : kLabelLineHeight) / share; }

}  // namespace

std::size_t ShownCharacters(const std::string& enhanced) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < enhanced.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(enhanced[i]);
    if ((c & 0xC0) == 0x80) continue;
    if (c == '\\' && i + 1 < enhanced.size()) {
      ++i;
    } else if (c == '{' || c == '}' || c == '^' || c == '_' || c == '/' || c == '*') {
      continue;
    }
    ++n;
  }
  return n;
}

std::optional<std::pair<double, double>> PlotFraction(const FigurePanel& panel, const FigureAnnotation& a) {
  const auto x = Fraction(panel.x, a.x0);
  const auto y = Fraction(a.on_y2 ? panel.y2 : panel.y, a.y0);
  if (!x || !y) return std::nullopt;
  return std::make_pair(*x, *y);
}

std::optional<LabelBox> LabelBoxOf(const FigurePanel& panel, const FigureAnnotation& a, double share) {
  const auto at = PlotFraction(panel, a);
  if (!at || a.label.empty()) return std::nullopt;
  const double line = LineHeight(share);
  const double width = static_cast<double>(ShownCharacters(a.label)) * CharWidth(share);
  const double gap = std::fabs(a.label_dx) * CharWidth(share);
  const double centre = at->second + a.label_dy * line;
  LabelBox b;
  b.x0 = a.label_left ? at->first - gap - width : at->first + gap;
  b.x1 = b.x0 + width;
  b.y0 = centre - 0.5 * line;
  b.y1 = centre + 0.5 * line;
  return b;
}

void PlaceMarkerLabels(FigurePanel& panel, double share) {
  const double line = LineHeight(share), char_width = CharWidth(share);
  std::vector<LabelBox> placed;
  // Every marker's point, a character wide and half a line tall: a label
  // over another marker's point would read as that marker's.
  std::vector<LabelBox> points;
  for (const FigureAnnotation& a : panel.annotations)
    if (a.kind == AnnotationKind::kMarker)
      if (const auto at = PlotFraction(panel, a))
        points.push_back({at->first - 0.5 * char_width, at->first + 0.5 * char_width,
                          at->second - 0.25 * line, at->second + 0.25 * line});
  // Every horizontal line (a requirement, a band's limit), a third of a
  // line tall: a label across it is struck through.
  for (const FigureAnnotation& a : panel.annotations) {
    const bool across = a.kind == AnnotationKind::kHorizontalLine;
    if (!across && !(a.kind == AnnotationKind::kSegment && a.y0 == a.y1)) continue;
    const auto y = Fraction(a.on_y2 ? panel.y2 : panel.y, a.y0);
    const auto x0 = across ? std::optional<double>(0.0) : Fraction(panel.x, a.x0);
    const auto x1 = across ? std::optional<double>(1.0) : Fraction(panel.x, a.x1);
    if (y && x0 && x1)
      points.push_back({std::min(*x0, *x1), std::max(*x0, *x1), *y - line / 6.0, *y + line / 6.0});
  }
  // The curves in plot fractions, each cut where a point is off its axes.
  std::vector<std::vector<std::pair<double, double>>> curves;
  for (const auto& curve : panel.label_obstacles) {
    curves.emplace_back();
    for (const auto& [x, y] : curve) {
      const auto fx = Fraction(panel.x, x), fy = Fraction(panel.y, y);
      if (fx && fy) curves.back().push_back({*fx, *fy});
      else if (!curves.back().empty()) curves.emplace_back();
    }
  }
  // A curve is drawn wide (up to 4 px of report.pdf's 250 px tall plot) and
  // the box is an estimate: it keeps a third of a line and a character clear.
  const auto on_curve = [&](LabelBox b) {
    b.x0 -= char_width;
    b.x1 += char_width;
    b.y0 -= line / 3.0;
    b.y1 += line / 3.0;
    for (const auto& c : curves)
      for (std::size_t i = 0; i + 1 < c.size(); ++i)
        if (SegmentMeets(c[i], c[i + 1], b)) return true;
    return false;
  };
  // Tries the places beside a's point, above then below, right then left,
  // up to `farthest` lines away, and keeps the first inside the axes that
  // meets no label placed, no point or line, and with `off_curves` no curve.
  const auto place = [&](FigureAnnotation& a, bool off_curves, double farthest) {
    for (const double dy : {1.0, -1.0, 2.0, -2.0}) {
      if (std::fabs(dy) > farthest) break;
      for (const bool left : {false, true}) {
        a.label_left = left;
        a.label_dx = left ? -1.0 : 1.0;
        a.label_dy = dy;
        const LabelBox b = *LabelBoxOf(panel, a, share);
        bool free = b.Inside();
        for (const LabelBox& other : placed) free = free && !b.Overlaps(other);
        for (const LabelBox& point : points) free = free && !b.Overlaps(point);
        if (free && off_curves) free = !on_curve(b);
        if (free) {
          placed.push_back(b);
          return true;
        }
      }
    }
    return false;
  };
  int numbered = 0;
  for (FigureAnnotation& a : panel.annotations) {
    if (a.kind != AnnotationKind::kMarker || a.label.empty() || !PlotFraction(panel, a)) continue;
    // Off the curves where a place allows, up to two lines away (farther, a
    // label in a short panel read as the next marker's); else over a curve
    // but next to its point (two lines away and over a curve, wafer_stage's
    // "GM 74.63 dB at 4153 Hz" read as another marker's), else the key.
    const bool done = place(a, true, 2.0) || place(a, false, curves.empty() ? 2.0 : 1.0);
    if (!done) {  // nowhere beside its point: the key names it, by a number beside the point where one fits
      const std::string text = a.label;
      a.label = "(" + std::to_string(numbered + 1) + ")";
      if (place(a, true, 2.0) || place(a, false, 1.0)) {
        ++numbered;
        a.key = a.label + " " + text;
      } else {
        a.key = text;
        a.label.clear();
        a.label_left = false;
        a.label_dx = a.label_dy = 1.0;
      }
      if (panel.key.placement == KeyPlacement::kNone) panel.key.placement = KeyPlacement::kOutsideRight;
    }
  }
}

}  // namespace deb::report
