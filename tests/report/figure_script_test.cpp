#include "deb/report/figure_script.h"

#include <doctest/doctest.h>

#include "deb/report/gnuplot_runner.h"
#include "deb/report/plot.h"

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

}  // namespace deb::report
