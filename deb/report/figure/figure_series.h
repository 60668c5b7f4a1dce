// Internal: not part of the public API.
// One curve, layer or set of bars of a figure, as data: which CSV columns it
// reads and how it is drawn. The columns are 1-based, as in the CSV beside
// the figure (plots/<name>.csv); y is the sum of `y_columns`, so a stacked
// layer is the columns below it plus its own.
// A CSV of several data blocks (separated by two blank lines, as gnuplot
// reads them) feeds several series: `block` picks one.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace deb::report {

enum class SeriesKind {
  kLine,    // a line through the points
  kFilled,  // the area between `low_columns` (or zero) and y
  kBars,    // a bar at each x, `bar_width` wide
  kPoints,  // markers only
  kSteps,   // a staircase
  kLabels,  // the text of `label_column` at each point (values over bars)
  kHorizontalBars,  // a bar from x = 0 to x at height y, `bar_height` thick (a tornado chart)
  kSegments,        // per row a straight line from (x, y) by (`dx_column`, `dy_column`), no heads (a contour)
  kHeatMap,         // `z_column` in the panel's palette over the (x, y) grid, interpolated; rows by scan lines
};

// Which rows a series draws: those whose `where_column` compares so with `where_value`.
enum class WhereTest { kEqual, kLess, kAtLeast };

struct FigureSeries {
  std::string name;  // plain text: the contributor, "total", a channel
  std::string key;   // enhanced text of its key entry; empty: not in the key
  SeriesKind kind = SeriesKind::kLine;
  std::string data;  // the CSV file, relative to plots/
  int block = -1;  // the CSV's data block, from 0; -1: the whole file
  std::size_t x_column = 1;
  double x_offset = 0.0;                 // added to x (bars side by side)
  std::vector<std::size_t> y_columns;    // summed
  std::vector<std::size_t> low_columns;  // kFilled: lower edge (summed); empty: 0
  double y_divisor = 1.0;                // y shown as value / y_divisor (an axis in units of 10^n)
  // Only the rows whose column `where_column` equals `where_value` (one
  // CSV behind several panels); 0: every row.
  std::size_t where_column = 0;
  double where_value = 0.0;
  WhereTest where_test = WhereTest::kEqual;
  std::size_t z_column = 0;   // kHeatMap: the value; in a panel with a heat map, every series' height
  std::size_t dx_column = 0, dy_column = 0;  // kSegments
  std::size_t label_column = 0;          // kLabels
  bool labels_upright = false;           // kLabels: turned by 90°, reading upwards from the point
  // kLabels: beside x, right of it where x >= 0 and left where x < 0 (the
  // ends of horizontal bars); else over the point. Boxed either way: a
  // line behind the labels (a requirement) stops at their text.
  bool labels_beside_end = false;
  std::string label_format;              // kLabels: printf format of the column's number; empty: its text

  std::string colour = "#000000";  // "#rrggbb"
  std::string dash = "solid";      // "solid" or gnuplot's "(a,b,...)"
  double width = 2.0;              // line width, in units of the terminal's
  int point_type = 0;              // markers on a line (or kPoints); 0: none
  double point_size = 0.0;         // of the markers; 0: 1.1 on a line, 1.2 as kPoints
  int marker_every = 1;            // one marker every n rows ...
  int marker_first = 0;            // ... from this row
  int fill_pattern = 0;            // hatch over the fill; 0: solid
  double fill_opacity = 1.0;       // kFilled: below 1 the fill is transparent and has no hatch
  std::string hatch_colour;        // of the hatch lines
  std::string edge_colour;         // outline of a fill or bar; empty: none
  double edge_width = 1.0;
  double bar_height = 0.5;         // kHorizontalBars, in y units
};

}  // namespace deb::report
