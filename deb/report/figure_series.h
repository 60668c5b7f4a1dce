// Internal: not part of the public API.
// One curve, layer or set of bars of a figure, as data: which CSV columns it
// reads and how it is drawn. The columns are 1-based, as in the CSV beside
// the figure (plots/<name>.csv); y is the sum of `y_columns`, so a stacked
// layer is the columns below it plus its own.
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
};

struct FigureSeries {
  std::string name;  // plain text: the contributor, "total", a channel
  std::string key;   // enhanced text of its key entry; empty: not in the key
  SeriesKind kind = SeriesKind::kLine;
  std::string data;  // the CSV file, relative to plots/
  std::size_t x_column = 1;
  double x_offset = 0.0;                 // added to x (bars side by side)
  std::vector<std::size_t> y_columns;    // summed
  std::vector<std::size_t> low_columns;  // kFilled: lower edge (summed); empty: 0
  double y_divisor = 1.0;                // y shown as value / y_divisor (an axis in units of 10^n)
  // Only the rows whose column `where_column` equals `where_value` (one
  // CSV behind several panels); 0: every row.
  std::size_t where_column = 0;
  double where_value = 0.0;
  std::size_t label_column = 0;          // kLabels
  bool labels_upright = false;           // kLabels: turned by 90°, reading upwards from the point

  std::string colour = "#000000";  // "#rrggbb"
  std::string dash = "solid";      // "solid" or gnuplot's "(a,b,...)"
  double width = 2.0;              // line width, in units of the terminal's
  int point_type = 0;              // markers on a line (or kPoints); 0: none
  int marker_every = 1;            // one marker every n rows ...
  int marker_first = 0;            // ... from this row
  int fill_pattern = 0;            // hatch over the fill; 0: solid
  std::string hatch_colour;        // of the hatch lines
  std::string edge_colour;         // outline of a fill or bar; empty: none
  double edge_width = 1.0;
};

}  // namespace deb::report
