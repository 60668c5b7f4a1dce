// Internal: not part of the public API.
// A figure of the budget report (PlotFigure) as typed data: axes, series in drawing
// order, annotations and a key, on one or more panels sharing a page (a Bode
// plot's magnitude over its phase). Builders (spectrum_plots.h,
// path_plots.h) make Figures; figure_script.h is the one place that turns a
// PlotFigure into gnuplot. Tests read Figures, not scripts: series order,
// colours, limit values.
#pragma once

#include <string>
#include <vector>

#include "deb/report/figure/figure_annotation.h"
#include "deb/report/figure/figure_axis.h"
#include "deb/report/figure/figure_series.h"

namespace deb::report {

// kBesideGrid: right of a grid of panels, once for all of them (the
// panels leave it room); the other panels have none.
// kBelowMap: one row under a map (splot), which keeps no room for a key of its own.
// Set (to 1) before a figure's script is loaded for report.pdf: a key
// placed kOutsideRight then goes below the plot (the figure's narrow canvas
// there, PdfFigureTerminal).
inline constexpr const char* kPdfFigureVariable = "deb_pdf_figure";
// The canvas' height in px of a PDF figure (662 px wide), set with
// kPdfFigureVariable: a grid of small multiples keeps its titles' and
// labels' room in px on a canvas lower than the overview's 600.
inline constexpr const char* kPdfHeightVariable = "deb_pdf_height";
// Set (to 1) by the terminal that draws a PNG's SVG source (TerminalCommand,
// plot_style.h), and undefined by the others: gnuplot's SVG terminal
// estimates text narrower than the cairo one does, so a key beside the plot
// is widened there.
inline constexpr const char* kPngSourceVariable = "deb_png";
// The factor of every dash pattern's lengths in a figure's script: 0.4 in
// report.pdf's figures (kPdfFigureVariable set), 0.4 in a PNG's SVG
// (kPngSourceVariable), else 1.
inline constexpr const char* kDashScaleVariable = "deb_dash";
// The factor of every point size in a figure's script: 0.75 in a PNG's SVG
// source (kPngSourceVariable), where gnuplot's SVG points are larger than
// its PNG terminal's, else 1.
inline constexpr const char* kPointScaleVariable = "deb_point";

enum class KeyPlacement { kNone, kOutsideRight, kInsideTopRight, kInsideTopLeft, kBelow, kAbove, kBesideGrid, kBelowMap };

struct FigureKey {
  KeyPlacement placement = KeyPlacement::kOutsideRight;
  std::string title;  // enhanced text
  // The key lists series in drawing order, then the annotations with a key;
  // `invert` lists them the other way round.
  bool invert = false;
};

struct FigurePanel {
  std::string title;  // enhanced text; a line break starts a second line
  std::string title_colour;  // empty: the style's
  FigureAxis x, y, y2;
  std::vector<FigureSeries> series;  // drawn in this order: the last on top
  std::vector<FigureAnnotation> annotations;
  // Curves as drawn (x, y in the axes' coordinates; a point outside a log
  // axis' range breaks the curve) that markers' labels keep off where any
  // place beside their point allows (label_layout.h).
  std::vector<std::vector<std::pair<double, double>>> label_obstacles;
  FigureKey key;
  std::string note;         // centred text when there is nothing to draw
  double height = 1.0;      // share of the page, relative to the other panels
  double bar_width = 0.0;   // kBars, in x units; 0: gnuplot's
  bool equal_axes = false;  // one unit as long on x as on y (a Nyquist plot)
  // A panel with a kHeatMap series: its colour axis and palette (colours
  // from the low end to the high end).
  FigureAxis colour_axis;
  std::vector<std::string> palette;
};

struct PlotFigure {
  std::string title;                // enhanced text above all panels (multiplot; a line break starts a smaller line); one panel uses its own
  std::vector<FigurePanel> panels;  // top to bottom, sharing the x axis
  // Panels per row: 1 stacks them over a shared x axis; more lays them out
  // in a grid, row by row, each with its own axes.
  std::size_t columns = 1;
  // Stacked panels: the right margin, in characters, that holds the key
  // beside them; 0: the default, room for long entries.
  double key_margin = 0.0;
};

// The series named `name` on panel `panel`, or nullptr.
const FigureSeries* FindSeries(const PlotFigure& figure, const std::string& name, std::size_t panel = 0);

}  // namespace deb::report
