#include "deb/report/figure/figure_script.h"

#include <sstream>

#include "deb/core/error.h"
#include "deb/report/figure/label_layout.h"
#include "deb/report/figure/plot.h"
#include "deb/report/figure/plot_style.h"

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
// The ends of a bracket (FigureAnnotation::bracket): arrow heads at 90°.
constexpr const char* kBracketEnds = " heads size screen 0.008,90 ";

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
  s << "set " << name << "label " << Label(a.label);
  // A PNG's SVG source measures the right axis' and the colour bar's
  // numbers narrower than they are: their label moves 1.5 characters out.
  if (name == "y2" || name == "cb") s << " offset (exists(" << Quote(kPngSourceVariable) << ") ? 1.5 : 0),0";
  s << "\n";
  const std::string rotate =
      a.tic_rotation_deg ? " rotate by " + std::to_string(a.tic_rotation_deg) + " right" : std::string(" norotate");
  if (!a.tics.empty()) {
    s << "set " << name << "tics nomirror" << rotate << (a.tics_added ? " add" : "") << " (";
    for (std::size_t i = 0; i < a.tics.size(); ++i)
      s << (i ? ", " : "") << Label(a.tics[i].second) << " " << CsvNumber(a.tics[i].first);
    s << ")\n";
  } else {
    s << "set " << name << "tics nomirror" << rotate << "\n";
  }
  if (name == "x" || name == "y") s << "set grid " << (a.grid ? "" : "no") << name << "tics\n";
}

// A point size as "1.2*deb_point": gnuplot's SVG terminal draws points
// about twice as large as its cairo terminals; a PNG's SVG source
// (kPngSourceVariable) scales them back (kPointScaleVariable).
std::string PointSize(const std::string& size) { return size + "*" + kPointScaleVariable; }

// A dash pattern "(10,5)" as "(10*deb_dash,5*deb_dash)": gnuplot's SVG
// terminal scales a pattern by the line width, which report.pdf's figures
// draw 1.75 times as wide on a canvas half as wide as a PNG's, so their
// dashes came out three times as long (and a key sample, shorter than one
// dash, looked solid); kDashScaleVariable shortens them there, and in a
// PNG's SVG source, whose lines are 1.2 px per unit. Other dash types
// ("solid") as they are.
std::string Dash(const std::string& dash) {
  if (dash.empty() || dash.front() != '(') return dash;
  std::string out = "(";
  std::string number;
  for (std::size_t i = 1; i < dash.size(); ++i) {
    const char c = dash[i];
    if (c == ',' || c == ')') {
      out += number + "*" + kDashScaleVariable + c;
      number.clear();
    } else if (c != ' ') {
      number += c;
    }
  }
  return out;
}

std::string LineStyle(const std::string& colour, const std::string& dash, double width) {
  return "linecolor rgb " + Quote(colour) + " dashtype " + Dash(dash) + " linewidth " + CsvNumber(width);
}

std::string KeyOf(const std::string& key) { return key.empty() ? "notitle" : "title " + Quote(key); }

std::string Compare(WhereTest test) {
  switch (test) {
    case WhereTest::kEqual: return " == ";
    case WhereTest::kLess: return " < ";
    case WhereTest::kAtLeast: return " >= ";
  }
  return " == ";
}

// `map`: the panel is a heat map (splot seen from above), where every
// series has a height, its z_column.
void Clauses(const FigureSeries& s, bool log_y, bool map, std::vector<std::string>& out) {
  DEB_DEMAND(!s.y_columns.empty());
  DEB_DEMAND(!map || s.z_column > 0);
  const std::string div = s.y_divisor == 1.0 ? "" : "/" + CsvNumber(s.y_divisor);
  const std::string xs = s.x_offset == 0.0 ? std::to_string(s.x_column)
                                           : "(column(" + std::to_string(s.x_column) + ")+" + CsvNumber(s.x_offset) + ")";
  std::string y = "((" + Sum(s.y_columns) + ")" + div + ")";
  if (log_y) y = "(" + y + " > 0 ? " + y + " : NaN)";
  if (s.where_column)
    y = "(column(" + std::to_string(s.where_column) + ")" + Compare(s.where_test) + CsvNumber(s.where_value) + " ? " +
        y + " : NaN)";
  const std::string data =
      QuoteFile(s.data) + (s.block >= 0 ? " index " + std::to_string(s.block) : std::string()) + " using " + xs + ":";
  const std::string z = map ? ":" + std::to_string(s.z_column) : "";
  const std::string size = s.point_size > 0.0 ? CsvNumber(s.point_size) : "";
  if (map) {  // a heat map's panel: the map, markers on it and contour pieces
    switch (s.kind) {
      case SeriesKind::kHeatMap:
        out.push_back(data + y + z + " with pm3d " + KeyOf(s.key));
        return;
      case SeriesKind::kPoints:
        out.push_back(data + y + z + " with points pointtype " + std::to_string(s.point_type ? s.point_type : 7) +
                      " pointsize " + PointSize(size.empty() ? "1.2" : size) + " linewidth " + CsvNumber(s.width) +
                      " linecolor rgb " + Quote(s.colour) + " " + KeyOf(s.key));
        return;
      case SeriesKind::kSegments:
        out.push_back(data + y + z + ":" + std::to_string(s.dx_column) + ":" + std::to_string(s.dy_column) +
                      ":(0) with vectors nohead " + LineStyle(s.colour, s.dash, s.width) + " " + KeyOf(s.key));
        return;
      default:
        DEB_DEMAND(false);  // other kinds are not drawn on a heat map
    }
  }
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
      const std::string marker =
          "pointtype " + std::to_string(s.point_type) + " pointsize " + PointSize(size.empty() ? "1.1" : size);
      out.push_back(data + y + " with " + with + " " + line + " notitle");
      out.push_back(data + y + " every " + std::to_string(s.marker_every) + "::" + std::to_string(s.marker_first) +
                    " with points " + marker + " linewidth " + CsvNumber(s.width) + " linecolor rgb " +
                    Quote(s.colour) + " notitle");
      if (!s.key.empty()) out.push_back("keyentry with linespoints " + marker + " " + line + " " + KeyOf(s.key));
      return;
    }
    case SeriesKind::kLabels: {
      const std::string label =
          s.label_format.empty() ? std::to_string(s.label_column)
                                 : "(sprintf(" + Quote(s.label_format) + ", " + Col(s.label_column) + "))";
      if (s.labels_beside_end) {  // right of a bar's end at x >= 0, left of one at x < 0
        const std::string x = Col(s.x_column) + (s.x_offset == 0.0 ? "" : "+" + CsvNumber(s.x_offset));
        const std::string at = QuoteFile(s.data) + (s.block >= 0 ? " index " + std::to_string(s.block) : std::string()) +
                               " using (" + x;
        out.push_back(at + " >= 0 ? " + x + " : NaN):" + y + ":" + label +
                      " with labels left offset 0.6,0 boxed font ',10' textcolor rgb " + Quote(s.colour) + " notitle");
        out.push_back(at + " < 0 ? " + x + " : NaN):" + y + ":" + label +
                      " with labels right offset -0.6,0 boxed font ',10' textcolor rgb " + Quote(s.colour) + " notitle");
        return;
      }
      out.push_back(data + y + ":" + label +
                    " with labels " + (s.labels_upright ? "rotate by 90 left offset 0,0.5" : "offset 0,0.8") +
                    " boxed font ',9' textcolor rgb " + Quote(s.colour) + " notitle");
      return;
    }
    case SeriesKind::kPoints:
      out.push_back(data + y + " with points pointtype " + std::to_string(s.point_type ? s.point_type : 7) +
                    " pointsize " + PointSize(size.empty() ? "1.2" : size) + " linewidth " + CsvNumber(s.width) +
                    " linecolor rgb " + Quote(s.colour) + " " + KeyOf(s.key));
      return;
    case SeriesKind::kSegments:
      out.push_back(data + y + ":" + std::to_string(s.dx_column) + ":" + std::to_string(s.dy_column) +
                    " with vectors nohead " + LineStyle(s.colour, s.dash, s.width) + " " + KeyOf(s.key));
      return;
    case SeriesKind::kHeatMap:
      DEB_DEMAND(false);  // only with `map`, above
      return;
    case SeriesKind::kFilled:
    case SeriesKind::kBars:
    case SeriesKind::kHorizontalBars: {
      const bool horizontal = s.kind == SeriesKind::kHorizontalBars;
      const bool bars = s.kind == SeriesKind::kBars || horizontal;
      std::string low = "((" + Sum(s.low_columns) + ")" + div + ")";
      if (log_y) low = "(" + low + " > 0 ? " + low + " : NaN)";
      std::string source = bars ? data + y : data + low + ":" + y;
      if (horizontal) {  // a box centred on half the value, half the value wide (boxxyerror: x:y:dx:dy)
        const std::string x = Col(s.x_column) + (s.x_offset == 0.0 ? "" : "+" + CsvNumber(s.x_offset));
        source = QuoteFile(s.data) + (s.block >= 0 ? " index " + std::to_string(s.block) : std::string()) +
                 " using ((" + x + ") / 2):" + y + ":(abs(" + x + ") / 2):(" + CsvNumber(s.bar_height / 2.0) + ")";
      }
      const std::string with = horizontal ? "boxxyerror" : bars ? "boxes" : "filledcurves";
      if (!bars && s.fill_opacity < 1.0) {  // transparent: what lies under it shows through
        out.push_back(source + " with filledcurves fillcolor rgb " + Quote(s.colour) + " fillstyle transparent solid " +
                      CsvNumber(s.fill_opacity) + " noborder " + KeyOf(s.key));
        return;
      }
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

// The characters of a panel's longest key entry, as shown.
std::size_t LongestKeyEntry(const FigurePanel& p) {
  std::size_t longest = 0;
  for (const FigureSeries& fs : p.series) longest = std::max(longest, ShownCharacters(fs.key));
  for (const FigureAnnotation& a : p.annotations) longest = std::max(longest, ShownCharacters(a.key));
  return longest;
}

// What gnuplot's `set key width` adds to a key column: gnuplot estimates an
// entry's width as a fixed width per character, about a third more than
// DejaVu Sans takes on average, which below the plot (report.pdf) gives
// too few columns; the longest entry's excess, less a margin, is taken off.
int KeyWidthIncrement(const FigurePanel& p) { return -static_cast<int>(0.2 * static_cast<double>(LongestKeyEntry(p))); }

// What a key beside the plot adds to its column in a PNG's SVG source
// (kPngSourceVariable): the SVG terminal estimates an entry at about a fifth
// less than DejaVu Sans takes there, which would push the longest entries
// past the canvas' edge; three characters more keep a margin.
int KeyWidenedInSvg(const FigurePanel& p) {
  // A title longer than every entry widens the key by the difference:
  // gnuplot sizes the key by its entries alone.
  const std::size_t entries = LongestKeyEntry(p), title = ShownCharacters(p.key.title);
  const std::size_t longest = std::max(entries, title);
  return 3 + static_cast<int>(0.2 * static_cast<double>(longest)) + static_cast<int>(longest - entries);
}

// The key's placement, layout and title.
void Key(std::ostringstream& s, const FigurePanel& p, bool multiplot) {
  bool titled = false;  // the key's title set with its placement
  switch (p.key.placement) {
    case KeyPlacement::kNone: s << "unset key\n"; break;
    case KeyPlacement::kOutsideRight:
      // Beside the plot on the wide canvas of a PNG; below it, in up to three
      // columns, on report.pdf's narrow one (kPdfFigureVariable), where a key
      // beside it would leave the plot half the text width. (Panels of a
      // multiplot keep it beside them: their margins are fixed.)
      if (multiplot) {
        // The title from the key's left edge, as its entries: centred over
        // entries narrower than itself, it ran past the canvas' edge.
        s << "set key outside right top Left reverse width (exists(" << Quote(kPngSourceVariable) << ") ? "
          << KeyWidenedInSvg(p) << " : 0) title " << Label(p.key.title) << " left";
        titled = true;
        break;
      }
      // Below, the title goes a line down and the key is not opaque:
      // gnuplot sets it too close under a one-line axis label otherwise;
      // under a label with a note (a second line) it keeps a line's gap
      // without (the blank line left two lines empty there).
      s << "if (exists(" << Quote(kPdfFigureVariable) << ")) {\n  set key below horizontal Left reverse maxcols 3 "
        << "width " << KeyWidthIncrement(p) << " noopaque title ("
        << (p.x.label.find('\n') == std::string::npos ? "\"\\n\"." : "") << Label(p.key.title)
        << ")\n} else {\n  set key outside right top Left reverse width (exists(" << Quote(kPngSourceVariable)
        << ") ? " << KeyWidenedInSvg(p) << " : 0) title " << Label(p.key.title) << "\n}\nset key";
      titled = true;
      break;
    case KeyPlacement::kInsideTopRight: s << "set key inside right top Left reverse"; break;
    case KeyPlacement::kInsideTopLeft: s << "set key inside left top Left reverse"; break;
    case KeyPlacement::kBelow: s << "set key below Left reverse"; break;
    case KeyPlacement::kAbove: s << "set key outside top center horizontal Left reverse"; break;
    case KeyPlacement::kBesideGrid: s << "set key at screen 0.85,0.9 left top Left reverse"; break;
    case KeyPlacement::kBelowMap:
      // No title, not even an empty one: its blank line took the key below
      // the canvas' edge on report.pdf's 420 px canvas, and gnuplot then
      // left the whole key out.
      s << "set bmargin 6\nset key at screen 0.45,0.06 center center horizontal maxrows 1 Left reverse";
      titled = p.key.title.empty();
      if (!titled) {
        s << " title " << Label(p.key.title);
        titled = true;
      }
      break;
  }
  if (p.key.placement != KeyPlacement::kNone)
    s << (p.key.invert ? " invert" : " noinvert") << (titled ? "" : " title " + Label(p.key.title)) << "\n";
}

// `share`: of the figure's height, for a stacked panel (its labels' lines
// are taller in it).
void Panel(std::ostringstream& s, const FigurePanel& given, bool multiplot, bool last,
           double right_margin = kRightMargin, double share = 1.0) {
  FigurePanel p = given;
  PlaceMarkerLabels(p, share);
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
    s << "set lmargin " << kLeftMargin << "\nset rmargin " << right_margin << "\n";
    if (!last) s << "set format x ''\nunset xlabel\n";
    // The last panel's tics are labelled again (gnuplot's default format)
    // unless its axis has a format of its own.
    else if (p.x.format.empty()) s << "set format x '% h'\n";
  }
  Key(s, p, multiplot);
  if (!p.note.empty()) s << "set label 1 " << Quote(p.note) << " at graph 0.5,0.5 center front\n";

  // A heat map: a surface seen from above, in the palette, under the rest.
  bool map = false;
  for (const FigureSeries& fs : p.series) map = map || fs.kind == SeriesKind::kHeatMap;
  if (map) {
    DEB_DEMAND(!p.palette.empty());
    s << "set view map\nset pm3d at b interpolate 6,6\nunset grid\nset palette defined (";
    for (std::size_t i = 0; i < p.palette.size(); ++i) s << (i ? ", " : "") << i << " " << Quote(p.palette[i]);
    s << ")\n";
    Axis(s, p.colour_axis, "cb");
    // gnuplot's SVG terminal leaves a map's y label over its numbers.
    s << "set ylabel offset (exists(" << Quote(kPngSourceVariable) << ") ? -2 : 0),0\n";
  }

  std::vector<std::string> clauses;
  int tag = 10;  // labels and arrows of annotations
  for (const FigureAnnotation& a : p.annotations) {
    const std::string line = LineStyle(a.colour, a.dash, a.width);
    const std::string y = Coord(a.on_y2);
    const std::string layer = a.behind ? " nohead back " : " nohead front ";
    switch (a.kind) {
      case AnnotationKind::kHorizontalLine:
        s << "set arrow " << tag++ << " from graph 0, " << y << CsvNumber(a.y0) << " to graph 1, " << y
          << CsvNumber(a.y0) << layer << line << "\n";
        break;
      case AnnotationKind::kVerticalLine:
        s << "set arrow " << tag++ << " from first " << CsvNumber(a.x0) << ", graph 0 to first " << CsvNumber(a.x0)
          << ", graph 1" << layer << line << "\n";
        break;
      case AnnotationKind::kSegment:
        s << "set arrow " << tag++ << " from first " << CsvNumber(a.x0) << ", " << y << CsvNumber(a.y0)
          << " to first " << CsvNumber(a.x1) << ", " << y << CsvNumber(a.y1)
          << (a.bracket ? std::string(a.behind ? " back" : " front") + kBracketEnds : layer) << line << "\n";
        break;
      case AnnotationKind::kKeyEntry:
        if (a.fill_sample)
          clauses.push_back("keyentry with filledcurves fillcolor rgb " + Quote(a.colour) +
                            " fillstyle solid 0.6 noborder title " + Quote(a.key));
        else if (a.point_type > 0)
          clauses.push_back("keyentry with points pointtype " + std::to_string(a.point_type) + " pointsize " +
                            PointSize(CsvNumber(a.point_size)) + " linewidth " + CsvNumber(a.width) + " linecolor rgb " +
                            Quote(a.colour) + " title " + Quote(a.key));
        else
          clauses.push_back("keyentry with lines " + line + " title " + Quote(a.key));
        break;
      case AnnotationKind::kMarker:
        s << "set label " << tag++ << " " << Quote(a.label) << " at first " << CsvNumber(a.x0) << ", " << y
          << CsvNumber(a.y0) << (a.label_left ? " right" : "") << " point pointtype " << a.point_type
          << " pointsize " << PointSize(CsvNumber(a.point_size))
          << " linecolor rgb "
          << Quote(a.colour) << " offset " << CsvNumber(a.label_dx) << "," << CsvNumber(a.label_dy)
          << " textcolor rgb " << Quote(a.label_colour.empty() ? a.colour : a.label_colour) << " boxed front\n";
        break;
      case AnnotationKind::kLabel:
        s << "set label " << tag++ << " " << Quote(a.label) << " at first " << CsvNumber(a.x0) << ", " << y
          << CsvNumber(a.y0) << " left offset " << CsvNumber(a.label_dx) << "," << CsvNumber(a.label_dy)
          << " textcolor rgb " << Quote(a.colour) << " front\n";
        break;
      case AnnotationKind::kCircle:
        s << "set object " << tag++ << " circle at first " << CsvNumber(a.x0) << "," << CsvNumber(a.y0)
          << " size first " << CsvNumber(a.x1) << " fillstyle empty border linecolor rgb " << Quote(a.colour)
          << " linewidth " << CsvNumber(a.width) << " dashtype " << Dash(a.dash) << " front\n";
        break;
      case AnnotationKind::kText:
        s << "set label " << tag++ << " " << Quote(a.label) << " at graph " << CsvNumber(a.x0) << ", graph "
          << CsvNumber(a.y0) << " textcolor rgb " << Quote(a.colour) << " front\n";
        break;
    }
    if (!a.key.empty() && a.kind == AnnotationKind::kMarker)  // its label, moved into the key (label_layout.h)
      clauses.push_back("keyentry with points pointtype " + std::to_string(a.point_type) + " pointsize " +
                        PointSize(CsvNumber(a.point_size)) + " linecolor rgb " + Quote(a.colour) + " title " + Quote(a.key));
    if (!a.key.empty() && a.kind != AnnotationKind::kMarker && a.kind != AnnotationKind::kText &&
        a.kind != AnnotationKind::kLabel && a.kind != AnnotationKind::kKeyEntry)
      clauses.push_back(std::string("keyentry with ") + (a.bracket ? std::string("vectors") + kBracketEnds : "lines ") +
                        line + " title " + Quote(a.key));
  }
  std::vector<std::string> series;
  for (const FigureSeries& fs : p.series) Clauses(fs, p.y.scale == AxisScale::kLog, map, series);
  series.insert(series.end(), clauses.begin(), clauses.end());
  if (series.empty()) series.push_back("NaN notitle");
  s << (map ? "s" : "") << PlotList(series);
  if (multiplot && !last) s << "unset label\nunset arrow\nunset object\n";
}

}  // namespace

std::string EmitFigure(const PlotFigure& figure) {
  DEB_DEMAND(!figure.panels.empty());
  std::ostringstream s;
  s << "reset\n" << StylePreamble();
  // Dash patterns 0.4 times as long in report.pdf's figures and in a PNG's
  // SVG source (Dash).
  s << kDashScaleVariable << " = exists(" << Quote(kPdfFigureVariable) << ") || exists(" << Quote(kPngSourceVariable)
    << ") ? 0.4 : 1\n";
  // Points 0.75 times as large in a PNG's SVG source (PointSize).
  s << kPointScaleVariable << " = exists(" << Quote(kPngSourceVariable) << ") ? 0.75 : 1\n";
  // Marker labels sit on an opaque box: readable over a hatched layer.
  s << "set style textbox opaque margins 0.5,0.5 noborder\n";
  const std::size_t n = figure.panels.size();
  if (n == 1) {
    Panel(s, figure.panels[0], false, true);
    return s.str();
  }
  if (figure.columns > 1) {  // a grid of independent panels
    const std::size_t rows = (n + figure.columns - 1) / figure.columns;
    bool shared_key = false;
    for (const FigurePanel& p : figure.panels) shared_key = shared_key || p.key.placement == KeyPlacement::kBesideGrid;
    // The right sixth: the key. The vertical room for titles and labels is
    // fixed in px at a PDF canvas' 600 (deb_grid_v scales the fractions up
    // on a lower one); the PNG's 720 px keep the fractions.
    if (shared_key)
      s << "deb_grid_v = exists(" << Quote(kPdfHeightVariable) << ") ? 600.0 / " << kPdfHeightVariable << " : 1\n";
    s << "set multiplot layout " << rows << "," << figure.columns << " title " << Label(figure.title) << " font ',15'"
      << (shared_key ? " margins 0.07,0.83,(0.09 * deb_grid_v),(1 - 0.1 * deb_grid_v) spacing 0.07,(0.13 * deb_grid_v)"
                     : "")
      << "\n";
    if (shared_key) s << "set title font ',12'\n";  // small multiples: titles below the page's
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
  s << "set multiplot title " << Label(figure.title) << " font ',14'\n";
  double top = 1.0 - kTitle;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = (1.0 - kTitle) * figure.panels[i].height / total;
    s << "set size 1," << CsvNumber(h) << "\nset origin 0," << CsvNumber(top - h) << "\n";
    s << "set tmargin " << (i == 0 ? "1" : "0.5") << "\nset bmargin " << (i + 1 == n ? "5" : "0.5") << "\n";
    Panel(s, figure.panels[i], true, i + 1 == n, figure.key_margin > 0.0 ? figure.key_margin : kRightMargin,
          figure.panels[i].height / total);
    top -= h;
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace deb::report
