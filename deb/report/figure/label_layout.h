// Internal: not part of the public API.
// Where a marker's label goes (a phase margin, the frequency where the RMS
// crosses its requirement): beside its point in free space, never over
// another label or past the axes, else in the key. A label is a box of its
// shown characters on the narrowest canvas a figure is drawn on (report.pdf's
// figures, 662 px wide, PdfFigureTerminal), in fractions of the plot area;
// it is tried above its point, then below, one and then two lines away,
// each right of the point and then left, and the first place inside the
// axes that meets no label placed before it, no marker's point and no
// horizontal line (a requirement or a band's limit) is kept. A label that fits
// nowhere becomes the marker's entry in the key (a panel without a key gets
// one beside it), numbered "(1) ...", "(2) ..." with the number placed beside
// the point as a label is, so that the key says which marker it names (the
// number too fitting nowhere, the entry is the label alone).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "deb/report/figure/plot_figure.h"

namespace deb::report {

// The characters a reader sees of enhanced text: UTF-8 characters once,
// without the markup (braces, ^ and _ of super- and subscripts, the font
// switches' / and *) and the escapes' backslashes.
std::size_t ShownCharacters(const std::string& enhanced);

// The box of a label, in fractions of the plot area (0..1 inside the axes).
struct LabelBox {
  double x0, x1, y0, y1;
  bool Overlaps(const LabelBox& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool Inside() const { return x0 >= 0.0 && x1 <= 1.0 && y0 >= 0.0 && y1 <= 1.0; }
};

// A character's width and a line's height in fractions of the plot area of
// report.pdf's figures (11 px DejaVu Sans: about 6.5 px a character; a plot
// area at least 430 px wide, a stacked panel's beside its key, and 250 px
// tall, a panel of a stack its share of that).
inline constexpr double kLabelCharWidth = 6.5 / 430.0;
inline constexpr double kLabelLineHeight = 15.0 / 250.0;
// The same in a stack of panels (a Bode figure: `share` < 1), whose key
// beside it leaves the plot 310 px wide, and 195 px tall in all (report.pdf,
// measured on wafer_stage's loop gain).
inline constexpr double kStackedLabelCharWidth = 6.5 / 310.0;
inline constexpr double kStackedLabelLineHeight = 15.0 / 195.0;

// Where `a` (a marker) sits in the panel, in fractions of the plot area; none
// when an axis has no explicit range.
std::optional<std::pair<double, double>> PlotFraction(const FigurePanel& panel, const FigureAnnotation& a);

// The box of marker `a`'s label as placed (label_dx, label_dy, label_left),
// in a panel that has `share` of its figure's height.
std::optional<LabelBox> LabelBoxOf(const FigurePanel& panel, const FigureAnnotation& a, double share = 1.0);

// Places the labels of every marker of `panel` in its annotations' order:
// sets label_dx, label_dy and label_left, or moves the label into `key`
// (label emptied). A marker whose position is unknown keeps its label where
// it is (right and above).
void PlaceMarkerLabels(FigurePanel& panel, double share = 1.0);

}  // namespace deb::report
