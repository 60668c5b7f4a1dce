// Internal: not part of the public API.
// What a figure marks beside its data: limit lines (a requirement), segments
// (a band's limit across its bars), markers with a label (where the
// cumulative RMS crosses a requirement) and free text. Coordinates are the
// plot's data coordinates; labels are enhanced text.
#pragma once

#include <string>

namespace deb::report {

enum class AnnotationKind {
  kHorizontalLine,  // y = y0 across the plot
  kVerticalLine,    // x = x0 across the plot
  kSegment,         // (x0, y0) to (x1, y1)
  kMarker,          // a point at (x0, y0), `label` beside it
  kLabel,           // `label` starting at (x0, y0), offset by (label_dx, label_dy)
  kText,            // `label` at graph coordinates (x0, y0) in 0..1
  kCircle,          // centre (x0, y0), radius x1 in x units (equal axes)
  kKeyEntry,        // only an entry in the key: a line, or with point_type > 0 a marker, or a fill
};

struct FigureAnnotation {
  AnnotationKind kind = AnnotationKind::kHorizontalLine;
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  std::string colour = "#000000";
  std::string dash = "solid";
  double width = 2.0;
  std::string label;  // enhanced text; markers and text
  std::string label_colour;  // markers: the label's colour; empty: `colour`
  std::string key;    // lines, and markers: an entry in the key (enhanced text); empty: none
  int point_type = 7;  // markers
  double label_dx = 1.0, label_dy = 1.0;  // label offset from a marker, in characters
  bool label_left = false;  // markers: the label ends left of the point (right-aligned); label_layout.h
  bool on_y2 = false;  // y in the y2 axis' coordinates
  bool behind = false;  // drawn under the data (lines and segments); else over it
  // kSegment: a bar across each end, in its key sample too: a band's limit,
  // which a dashed curve of a similar colour (a group's) is not.
  bool bracket = false;
  double point_size = 1.6;  // markers and key entries of a marker
  bool fill_sample = false;  // kKeyEntry: a fill of `colour` (semi-transparent), not a line
};

}  // namespace deb::report
