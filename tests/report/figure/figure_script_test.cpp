#include "deb/report/figure/figure_script.h"

#include <cairo.h>
#include <doctest/doctest.h>

#include <cstdint>

#include "deb/report/figure/gnuplot_runner.h"
#include "deb/report/figure/plot.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/scratch_dir.h"

namespace deb::report {
namespace {

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

FigurePanel Panel(const std::string& key) {
  FigurePanel p;
  p.title = "t";
  p.y.scale = AxisScale::kLog;
  FigureSeries s;
  s.name = "s";
  s.key = key;
  s.data = "d.csv";
  s.y_columns = {2, 3};
  p.series.push_back(s);
  FigureAnnotation limit;
  limit.y0 = 4.0;
  limit.key = "limit";
  p.annotations.push_back(limit);
  return p;
}

}  // namespace

TEST_CASE("the emitter quotes user text, so that no backquote or macro of a name reaches gnuplot unquoted") {
  PlotFigure f;
  f.panels.push_back(Panel("it's `rm -rf` @x"));
  const std::string script = EmitFigure(f);
  CHECK(script.find("title 'it''s `rm -rf` @x'") != std::string::npos);
  CHECK(ScriptOffence(script).empty());
  // y sums its columns; a log axis drops the points <= 0.
  CHECK(script.find("'d.csv' using 1:(((column(2)+column(3))) > 0 ? ((column(2)+column(3))) : NaN)") !=
        std::string::npos);
  // The limit line is an arrow across the plot, and a key entry after the series.
  CHECK(script.find("set arrow 10 from graph 0, first 4 to graph 1, first 4 nohead") != std::string::npos);
  CHECK(script.find("keyentry with lines") > script.find("'d.csv'"));
  CHECK(Count(script, "\nplot ") == 1);
}

TEST_CASE("dash patterns are scaled by deb_dash: 0.4 in report.pdf's figures and a PNG's SVG, where gnuplot draws lines wider") {
  PlotFigure figure;
  FigurePanel p = Panel("s");
  p.series[0].dash = "(10,5)";
  p.annotations[0].dash = "(16,4,4,4)";
  figure.panels.push_back(p);
  const std::string script = EmitFigure(figure);
  CHECK(Count(script, "deb_dash = exists('deb_pdf_figure') || exists('deb_png') ? 0.4 : 1\n") == 1);
  CHECK(script.find("dashtype (10*deb_dash,5*deb_dash)") != std::string::npos);
  CHECK(script.find("dashtype (16*deb_dash,4*deb_dash,4*deb_dash,4*deb_dash)") != std::string::npos);
  CHECK(script.find("dashtype (10,5)") == std::string::npos);
  CHECK(script.find("dashtype solid") != std::string::npos);  // the grid's, as it is
}

TEST_CASE("stacked panels are one multiplot whose panels share their margins and the bottom panel's x axis") {
  PlotFigure f;
  f.title = "two";
  f.panels = {Panel("a"), Panel("b")};
  const std::string script = EmitFigure(f);
  CHECK(Count(script, "\nset multiplot") == 1);
  CHECK(Count(script, "unset multiplot") == 1);
  CHECK(Count(script, "\nplot ") == 2);
  CHECK(Count(script, "set lmargin 12\n") == 2);
  CHECK(Count(script, "set format x ''") == 1);  // only the top panel hides its x tic labels
  CHECK(ScriptOffence(script).empty());
}

TEST_CASE("a heat map panel is drawn from above (splot) in its palette, every series at its height") {
  FigurePanel p;
  p.palette = {"#fde725", "#440154"};
  p.colour_axis.label = "RMS";
  p.colour_axis.scale = AxisScale::kLog;
  FigureSeries map;
  map.name = "map";
  map.kind = SeriesKind::kHeatMap;
  map.data = "m.csv";
  map.block = 0;
  map.y_columns = {2};
  map.z_column = 3;
  FigureSeries contour = map;
  contour.kind = SeriesKind::kSegments;
  contour.block = 2;
  contour.dx_column = 4;
  contour.dy_column = 5;
  p.series = {map, contour};
  PlotFigure f;
  f.panels = {p};
  const std::string script = EmitFigure(f);
  CHECK(script.find("set view map\n") != std::string::npos);
  CHECK(script.find("set palette defined (0 '#fde725', 1 '#440154')") != std::string::npos);
  CHECK(script.find("set logscale cb 10") != std::string::npos);
  CHECK(script.find("\nsplot 'm.csv' index 0 using 1:((column(2))):3 with pm3d") != std::string::npos);
  CHECK(script.find("'m.csv' index 2 using 1:((column(2))):3:4:5:(0) with vectors nohead") != std::string::npos);
  CHECK(ScriptOffence(script).empty());
}

TEST_CASE("horizontal bars run from 0 to x; their values stand beside the ends; rows are picked by a test") {
  FigurePanel p;
  FigureSeries bars;
  bars.name = "bars";
  bars.kind = SeriesKind::kHorizontalBars;
  bars.data = "t.csv";
  bars.x_column = 2;
  bars.y_columns = {1};
  bars.bar_height = 0.5;
  bars.where_column = 5;
  bars.where_value = 3;
  bars.where_test = WhereTest::kAtLeast;
  FigureSeries values = bars;
  values.kind = SeriesKind::kLabels;
  values.label_column = 2;
  values.label_format = "%.3g";
  values.labels_beside_end = true;
  values.where_column = 0;
  p.series = {bars, values};
  PlotFigure f;
  f.panels = {p};
  const std::string script = EmitFigure(f);
  CHECK(script.find("'t.csv' using ((column(2)) / 2):(column(5) >= 3 ? ((column(1))) : NaN):(abs(column(2)) / 2):(0.25) "
                    "with boxxyerror") != std::string::npos);
  CHECK(script.find("using (column(2) >= 0 ? column(2) : NaN):((column(1))):(sprintf('%.3g', column(2))) with labels "
                    "left") != std::string::npos);
  CHECK(script.find("using (column(2) < 0 ? column(2) : NaN):((column(1))):(sprintf('%.3g', column(2))) with labels "
                    "right") != std::string::npos);
  CHECK(ScriptOffence(script).empty());
}

TEST_CASE("a key beside the plot stays inside a PNG: widened where gnuplot's SVG terminal measures text too narrow") {
  const test::ScratchDir dir("png_key");
  dir.Write("d.csv", "1,1,1\n10,2,2\n100,3,3\n");
  PlotFigure figure;
  FigurePanel p = Panel("measured 0.201–1925 Hz: 3.270 (12.34 %), 5678.90 (98.76 %)");
  p.key.placement = KeyPlacement::kOutsideRight;
  p.key.title = "RMS [nm] (share)";
  figure.panels.push_back(p);
  dir.Write("f.gp", EmitFigure(figure));
  const std::string png = dir.Path("f.png");
  // The PNG's last columns: the number of pixels drawn there (not white).
  const auto drawn_at_right_edge = [&](const std::string& terminal) {
    RunGnuplot(FindGnuplot(""), dir.Path(""), DrawCommands(terminal, GnuplotOutputFile(PlotFormat::kPng, "f.png"), "f.gp"),
               "f.png");
    FinishPlotFile(PlotFormat::kPng, png);
    cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
    REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
    REQUIRE(cairo_image_surface_get_width(s) == kPngWidthPx);
    const unsigned char* data = cairo_image_surface_get_data(s);
    const int stride = cairo_image_surface_get_stride(s);
    int edge = 0, key = 0;
    for (int y = 0; y < kPngHeightPx; ++y)
      for (int x = kPngWidthPx - 400; x < kPngWidthPx; ++x) {
        const std::uint32_t v = *reinterpret_cast<const std::uint32_t*>(data + y * stride + 4 * x) & 0xffffffu;
        if (v == 0xffffffu) continue;
        ++key;
        if (x >= kPngWidthPx - 4) ++edge;
      }
    cairo_surface_destroy(s);
    CHECK(key > 500);  // the key is drawn in the right part
    return edge;
  };
  CHECK(drawn_at_right_edge(TerminalCommand(PlotFormat::kPng)) == 0);
  // The same without the widening runs past the edge.
  CHECK(drawn_at_right_edge(TerminalCommand(PlotFormat::kPng) + "undefine " + kPngSourceVariable + "\n") > 0);
}

}  // namespace deb::report
