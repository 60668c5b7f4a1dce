// Internal: not part of the public API.
// One axis of a figure, as data: what it measures, how it is scaled and
// which range it shows. Labels are gnuplot enhanced text (user text already
// passed through Enhanced); the emitter (figure_script.h) quotes them.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace deb::report {

enum class AxisScale { kLinear, kLog };

struct FigureAxis {
  std::string label;  // enhanced text; a line break starts a second line
  AxisScale scale = AxisScale::kLinear;
  std::optional<double> min, max;  // none: gnuplot's autoscale
  std::string format;              // tic format, e.g. "%g", "10^{%L}"; empty: gnuplot's
  // Explicit tics (value, enhanced label); empty: gnuplot's.
  std::vector<std::pair<double, std::string>> tics;
  bool tics_added = false;  // the explicit tics come on top of gnuplot's, not instead
  bool shown = true;        // false: no tics, no label (the y2 axis of most plots)
  bool minor_grid = true;   // grid lines at the minor tics (off on very long log axes)
  bool grid = true;         // grid lines at the major tics (off for bar categories)
  int tic_rotation_deg = 0; // tic labels turned by this angle, anchored at their right end
};

}  // namespace deb::report
