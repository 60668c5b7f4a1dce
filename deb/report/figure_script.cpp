#include "deb/report/figure_script.h"

#include <sstream>

#include "deb/core/error.h"
#include "deb/report/plot.h"
#include "deb/report/plot_style.h"

namespace deb::report {

const FigureSeries* FindSeries(const PlotFigure& figure, const std::string& name, std::size_t panel) {
  if (panel >= figure.panels.size()) return nullptr;
  for (const FigureSeries& s : figure.panels[panel].series)
    if (s.name == name) return &s;
  return nullptr;
}

namespace {

// Left and right margins of every panel of a multiplot, in characters, so
// that their x axes line up whatever their tic labels are.
constexpr double kLeftMargin = 12.0, kRightMargin = 34.0;

std::string Label(const std::string& text) {
  return text.find('\n') == std::string::npos ? Quote(text) : QuoteLines(text);
}

std::string Col(std::size_t c) { return "column(" + std::to_string(c) + ")"; }

std::string Sum(const std::vector<std::size_t>& columns) {
  std::string s;
  for (std::size_t c : columns) s += (s.empty() ? "" : "+") + Col(c);
  return s.empty() ? "0" : s;
}

void Axis(std::ostringstream& s, const FigureAxis& a, const std::string& name) {
  if (!a.shown) {
    s << "unset " << name << "tics\nunset " << name << "label\n";
    return;
  }
  if (a.scale == AxisScale::kLog) s << "set logscale " << name << " 10\n";
  else s << "unset logscale " << name << "\n";
  if (!a.format.empty()) s << "set format " << name << " " << Quote(a.format) << "\n";
  if (a.min || a.max)
    s << "set " << name << "range [" << (a.min ? CsvNumber(*a.min) : "*") << ":" << (a.max ? CsvNumber(*a.max) : "*")
      << "]\n";
  s << "set " << name << "label " << Label(a.label) << "\n";
  const std::string rotate =
      a.tic_rotation_deg ? " rotate by " + std::to_string(a.tic_rotation_deg) + " right" : std::string(" norotate");
  if (!a.tics.empty()) {
    s << "set " << name << "tics nomirror" << rotate << " (";
    for (std::size_t i = 0; i < a.tics.size(); ++i)
      s << (i ? ", " : "") << Label(a.tics[i].second) << " " << CsvNumber(a.tics[i].first);
    s << ")\n";
  } else {
    s << "set " << name << "tics nomirror" << rotate << "\n";
  }
  if (name == "x" || name == "y") s << "set grid " << (a.grid ? "" : "no") << name << "tics\n";
}

std::string LineStyle(const std::string& colour, const std::string& dash, double width) {
  return "linecolor rgb " + Quote(colour) + " dashtype " + dash + " linewidth " + CsvNumber(width);
}

std::string KeyOf(const std::string& key) { return key.empty() ? "notitle" : "title " + Quote(key); }

void Clauses(const FigureSeries& s, bool log_y, std::vector<std::string>& out) {
  DEB_DEMAND(!s.y_columns.empty());
  const std::string div = s.y_divisor == 1.0 ? "" : "/" + CsvNumber(s.y_divisor);
  const std::string xs = s.x_offset == 0.0 ? std::to_string(s.x_column)
                                           : "(column(" + std::to_string(s.x_column) + ")+" + CsvNumber(s.x_offset) + ")";
  std::string y = "((" + Sum(s.y_columns) + ")" + div + ")";
  if (log_y) y = "(" + y + " > 0 ? " + y + " : NaN)";
  if (s.where_column)
    y = "(column(" + std::to_string(s.where_column) + ") == " + CsvNumber(s.where_value) + " ? " + y + " : NaN)";
  const std::string data = Quote(s.data) + " using " + xs + ":";
  switch (s.kind) {
    case SeriesKind::kLine:
    case SeriesKind::kSteps: {
      const std::string with = s.kind == SeriesKind::kLine ? "lines" : "steps";
      const std::string line = LineStyle(s.colour, s.dash, s.width);
      if (!s.point_type) {
        out.push_back(data + y + " with " + with + " " + line + " " + KeyOf(s.key));
        return;
      }
      // Markers at every n-th row, staggered between curves; the key shows
      // line and marker together.
      const std::string marker = "pointtype " + std::to_string(s.point_type) + " pointsize 1.1";
      out.push_back(data + y + " with " + with + " " + line + " notitle");
      out.push_back(data + y + " every " + std::to_string(s.marker_every) + "::" + std::to_string(s.marker_first) +
                    " with points " + marker + " linewidth " + CsvNumber(s.width) + " linecolor rgb " +
                    Quote(s.colour) + " notitle");
      if (!s.key.empty()) out.push_back("keyentry with linespoints " + marker + " " + line + " " + KeyOf(s.key));
      return;
    }
    case SeriesKind::kLabels:
      out.push_back(data + y + ":" + std::to_string(s.label_column) +
                    " with labels " + (s.labels_upright ? "rotate by 90 left offset 0,0.5" : "offset 0,0.8") +
                    " boxed font ',9' textcolor rgb " + Quote(s.colour) + " notitle");
      return;
    case SeriesKind::kPoints:
      out.push_back(data + y + " with points pointtype " + std::to_string(s.point_type ? s.point_type : 7) +
                    " pointsize 1.2 linecolor rgb " + Quote(s.colour) + " " + KeyOf(s.key));
      return;
    case SeriesKind::kFilled:
    case SeriesKind::kBars: {
      const bool bars = s.kind == SeriesKind::kBars;
      const std::string source =
          bars ? data + y : data + "((" + Sum(s.low_columns) + ")" + div + "):" + y;
      const std::string with = bars ? "boxes" : "filledcurves";
      const std::string border = s.edge_colour.empty() ? " noborder"
                                                       : " border linecolor rgb " + Quote(s.edge_colour);
      const std::string solid = source + " with " + with + " fillstyle solid 1.0" + border + " fillcolor rgb " +
                                Quote(s.colour) + (bars && !s.edge_colour.empty() ? " linewidth " + CsvNumber(s.edge_width) : "");
      if (!s.fill_pattern) {
        out.push_back(solid + " " + KeyOf(s.key));
        return;
      }
      // The hatch's border in the fill colour gives its key sample (a hatch
      // on the key's white) the colour of the layer.
      out.push_back(solid + " notitle");
      out.push_back(source + " with " + with + " fillstyle transparent pattern " + std::to_string(s.fill_pattern) +
                    " border linecolor rgb " + Quote(s.colour) + " fillcolor rgb " + Quote(s.hatch_colour) + " " +
                    KeyOf(s.key));
      if (bars && !s.edge_colour.empty())  // the bar keeps its edge
        out.push_back(source + " with " + with + " fillstyle empty border linecolor rgb " + Quote(s.edge_colour) +
                      " linecolor rgb " + Quote(s.edge_colour) + " notitle");
      return;
    }
  }
}

std::string Coord(bool y2) { return y2 ? "second " : "first "; }

void Panel(std::ostringstream& s, const FigurePanel& p, bool multiplot, bool last) {
  s << "set title " << Label(p.title);
  if (!p.title_colour.empty()) s << " textcolor rgb " << Quote(p.title_colour);
  s << "\n";
  Axis(s, p.x, "x");
  if (!p.x.minor_grid) s << "set grid nomxtics\n";
  Axis(s, p.y, "y");
  if (p.y2.shown) Axis(s, p.y2, "y2");
  else s << "unset y2tics\nunset y2label\n";
  if (p.equal_axes) s << "set size ratio -1\n";
  if (p.bar_width > 0.0) s << "set boxwidth " << CsvNumber(p.bar_width) << " absolute\n";
  if (multiplot) {
    s << "set lmargin " << kLeftMargin << "\nset rmargin " << kRightMargin << "\n";
    if (!last) s << "set format x ''\nunset xlabel\n";
  }
  switch (p.key.placement) {
    case KeyPlacement::kNone: s << "unset key\n"; break;
    case KeyPlacement::kOutsideRight: s << "set key outside right top Left reverse"; break;
    case KeyPlacement::kInsideTopRight: s << "set key inside right top Left reverse"; break;
    case KeyPlacement::kInsideTopLeft: s << "set key inside left top Left reverse"; break;
    case KeyPlacement::kBelow: s << "set key below Left reverse"; break;
  }
  if (p.key.placement != KeyPlacement::kNone)
    s << (p.key.invert ? " invert" : " noinvert") << " title " << Quote(p.key.title) << "\n";
  if (!p.note.empty()) s << "set label 1 " << Quote(p.note) << " at graph 0.5,0.5 center front\n";

  std::vector<std::string> clauses;
  int tag = 10;  // labels and arrows of annotations
  for (const FigureAnnotation& a : p.annotations) {
    const std::string line = LineStyle(a.colour, a.dash, a.width);
    const std::string y = Coord(a.on_y2);
    switch (a.kind) {
      case AnnotationKind::kHorizontalLine:
        s << "set arrow " << tag++ << " from graph 0, " << y << CsvNumber(a.y0) << " to graph 1, " << y
          << CsvNumber(a.y0) << " nohead front " << line << "\n";
        break;
      case AnnotationKind::kVerticalLine:
        s << "set arrow " << tag++ << " from first " << CsvNumber(a.x0) << ", graph 0 to first " << CsvNumber(a.x0)
          << ", graph 1 nohead front " << line << "\n";
        break;
      case AnnotationKind::kSegment:
        s << "set arrow " << tag++ << " from first " << CsvNumber(a.x0) << ", " << y << CsvNumber(a.y0)
          << " to first " << CsvNumber(a.x1) << ", " << y << CsvNumber(a.y1) << " nohead front " << line << "\n";
        break;
      case AnnotationKind::kMarker:
        s << "set label " << tag++ << " " << Quote(a.label) << " at first " << CsvNumber(a.x0) << ", " << y
          << CsvNumber(a.y0) << " point pointtype " << a.point_type << " pointsize 1.6 linecolor rgb "
          << Quote(a.colour) << " offset " << CsvNumber(a.label_dx) << "," << CsvNumber(a.label_dy)
          << " textcolor rgb " << Quote(a.colour) << " boxed front\n";
        break;
      case AnnotationKind::kLabel:
        s << "set label " << tag++ << " " << Quote(a.label) << " at first " << CsvNumber(a.x0) << ", " << y
          << CsvNumber(a.y0) << " left offset " << CsvNumber(a.label_dx) << "," << CsvNumber(a.label_dy)
          << " textcolor rgb " << Quote(a.colour) << " front\n";
        break;
      case AnnotationKind::kCircle:
        s << "set object " << tag++ << " circle at first " << CsvNumber(a.x0) << "," << CsvNumber(a.y0)
          << " size first " << CsvNumber(a.x1) << " fillstyle empty border linecolor rgb " << Quote(a.colour)
          << " linewidth " << CsvNumber(a.width) << " dashtype " << a.dash << " front\n";
        break;
      case AnnotationKind::kText:
        s << "set label " << tag++ << " " << Quote(a.label) << " at graph " << CsvNumber(a.x0) << ", graph "
          << CsvNumber(a.y0) << " textcolor rgb " << Quote(a.colour) << " front\n";
        break;
    }
    if (!a.key.empty() && a.kind != AnnotationKind::kMarker && a.kind != AnnotationKind::kText &&
        a.kind != AnnotationKind::kLabel)
      clauses.push_back("keyentry with lines " + line + " title " + Quote(a.key));
  }
  std::vector<std::string> series;
  for (const FigureSeries& fs : p.series) Clauses(fs, p.y.scale == AxisScale::kLog, series);
  series.insert(series.end(), clauses.begin(), clauses.end());
  if (series.empty()) series.push_back("NaN notitle");
  s << PlotList(series);
  if (multiplot && !last) s << "unset label\nunset arrow\nunset object\n";
}

}  // namespace

std::string EmitFigure(const PlotFigure& figure) {
  DEB_DEMAND(!figure.panels.empty());
  std::ostringstream s;
  s << "reset\n" << StylePreamble();
  // Marker labels sit on an opaque box: readable over a hatched layer.
  s << "set style textbox opaque margins 0.5,0.5 noborder\n";
  const std::size_t n = figure.panels.size();
  if (n == 1) {
    Panel(s, figure.panels[0], false, true);
    return s.str();
  }
  if (figure.columns > 1) {  // a grid of independent panels
    const std::size_t rows = (n + figure.columns - 1) / figure.columns;
    s << "set multiplot layout " << rows << "," << figure.columns << " title " << Quote(figure.title)
      << " font ',15'\n";
    for (std::size_t i = 0; i < n; ++i) {
      Panel(s, figure.panels[i], false, true);
      s << "unset label\nunset arrow\nunset object\n";
    }
    s << "unset multiplot\n";
    return s.str();
  }
  double total = 0.0;
  for (const FigurePanel& p : figure.panels) total += p.height;
  // Panels stacked from the top, below a title line of 6 % of the page.
  constexpr double kTitle = 0.06;
  s << "set multiplot title " << Quote(figure.title) << " font ',14'\n";
  double top = 1.0 - kTitle;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = (1.0 - kTitle) * figure.panels[i].height / total;
    s << "set size 1," << CsvNumber(h) << "\nset origin 0," << CsvNumber(top - h) << "\n";
    s << "set tmargin " << (i == 0 ? "1" : "0.5") << "\nset bmargin " << (i + 1 == n ? "5" : "0.5") << "\n";
    Panel(s, figure.panels[i], true, i + 1 == n);
    top -= h;
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace deb::report
