// Internal: not part of the public API.
// The one place that writes gnuplot for the budget report's figures. The
// script holds no terminal or output file (plot.h): it starts with `reset`
// and the report's style (plot_style.h), then draws every panel; several
// panels are a multiplot whose panels share left and right margins, so that
// their frequency axes line up. Every text of the PlotFigure goes through Quote.
#pragma once

#include <string>

#include "deb/report/figure/plot_figure.h"

namespace deb::report {

// @pre every series has at least one y column and the figure one panel (DEB_DEMAND).
std::string EmitFigure(const PlotFigure& figure);

}  // namespace deb::report
