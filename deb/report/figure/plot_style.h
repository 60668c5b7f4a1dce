// Internal: not part of the public API.
// The one visual style of a deb report. Contributors keep one colour and one
// dash pattern in every plot of a report, keyed by their index in the budget
// (not by their share, which differs per output). Colours are built in CIE
// L*C*h: the first 8 form a qualitative palette (hues
// chosen per lightness level, so that no two read alike in colour or in
// grey), the next 16 each the hue farthest in colour (CIE76 ΔE) from the 11
// before them (any 12 in a row at least ΔE 28 apart), and lightness runs through a ladder of 12 levels (25..80, alternating
// dark and light), so that a greyscale print still tells layers and lines
// apart. The level is met both by the colour's L* and by the grey a printer
// makes of it (Rec. 601 luma), within 3; greens and cyans lose chroma for it.
// Filled layers and bars of contributors 6-17 (then of every other six) are
// hatched over their colour (gnuplot fill patterns, 6 kinds), so that 12
// fills differ in grey and the second six also in texture, and 24 fills
// differ in one or the other. Lines add one of 6 dash patterns; lines
// sharing a pattern differ by >= 25 in lightness.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "deb/report/figure/report_options.h"

namespace deb::report {

struct SeriesStyle {
  std::string colour;       // "#rrggbb"
  std::string edge_colour;  // darker, for outlines of filled layers
  std::string dash;         // gnuplot dash type: "solid" or "(a,b,...)"
  double lightness = 0.0;   // CIE L* of colour, 0..100
  int point_type = 0;       // gnuplot point type of the markers on a line; 0: no markers
  int fill_pattern = 0;     // gnuplot fill pattern hatched over a fill of colour; 0: solid
  std::string hatch_colour; // of the hatch lines: dark on a light colour, light on a dark one
};

// Style of the contributor with budget index `index`; the same for every
// report and every run.
SeriesStyle ContributorStyle(std::size_t index);

// Style of group `group` (its place in ComputeGroups' depth-first order) of
// an output of `contributors` contributors: the contributor styles that follow
// the last contributor's, so that a group never looks like a contributor of
// the same report, and looks alike in every plot it appears in.
SeriesStyle GroupStyle(std::size_t contributors, std::size_t group);

// Style of source channel `index` in a path plot with several channels: a
// family of its own, so that a channel is never taken for a contributor of
// the same report. Channels are solid lines with open markers (circle,
// square, triangle, diamond, ...: a distinct point type for 12 channels), in
// colours of a separate palette: hues step by the golden angle from 75°,
// skipping those within 25° of the hues of contributors 0 and 1 (present in
// almost every report), at lightness 38, 58, 48, 66 (lines that read on white).
SeriesStyle ChannelStyle(std::size_t index);
inline constexpr int kChannelMarkers = 14;  // markers per curve, about

// The plot clauses that fill `source` ("'f.csv' using 1:2:3") drawn `with`
// ("filledcurves", "boxes") in `style`: the solid colour, and for a hatched
// style the hatch over it (a transparent pattern bordered in the colour) and,
// if `outline_colour` is given, an outline in it (bars keep their edge).
// `key` ("title '...'" or "notitle") goes on the solid fill, or on the hatch
// of a hatched style so that the key shows it.
std::vector<std::string> FillClauses(const SeriesStyle& style, const std::string& source, const std::string& with,
                                     const std::string& key, const std::string& outline_colour = "");

// CIE L* of an sRGB colour "#rrggbb", and the L* of the grey a greyscale
// print makes of it (Rec. 601 luma of the encoded components, as printers
// and most converters do).
double Lightness(const std::string& colour);
double GreyLightness(const std::string& colour);

// Sum of all contributors; the requirement line.
inline constexpr const char* kTotalColour = "#000000";
// The palette of a map of an RMS over two parameters, low end first:
// perceptually ordered, light where the RMS is low (viridis reversed).
inline const std::vector<std::string> kMapPalette = {"#fde725", "#5ec962", "#21918c", "#3b528b", "#440154"};
inline constexpr const char* kRequirementColour = "#b2182b";
inline constexpr const char* kRequirementDash = "(14,6)";
// A measured reference (drawn, never summed).
inline constexpr const char* kReferenceColour = "#707070";
inline constexpr const char* kReferenceDash = "(8,5)";

inline constexpr const char* kFont = "DejaVu Sans";
inline constexpr const char* kMonoFont = "DejaVu Sans Mono";

// Terminal settings for one output file. PNG and SVG pages are 1200 x 720
// pixels; PDF pages are A4 landscape. Data lines are drawn at linewidth >= 2,
// which is >= 1.5 pt in PDF (0.75 pt per unit) and SVG (1.2 px per unit).
// A PNG is drawn by gnuplot as SVG (this terminal: the PNG's pixels, fonts
// at 96 dpi as gnuplot's cairo PNG terminal sets them, kPngSourceVariable
// set) into GnuplotOutputFile, and rasterised by FinishPlotFile: gnuplot
// writes SVG in a tenth of the time its PNG terminal takes, and deb's
// threads share the rasterising out evenly.
std::string TerminalCommand(PlotFormat format);
std::string FileExtension(PlotFormat format);  // "png", "svg", "pdf"
// The PNG's size in pixels.
inline constexpr int kPngWidthPx = 1200, kPngHeightPx = 720;
// The file gnuplot writes to draw `file` in `format`: `file`, except for a
// PNG, whose SVG source is "<file>.svg".
std::string GnuplotOutputFile(PlotFormat format, const std::string& file);
// The commands that draw the script `script_file` as `file` in `format`
// (DrawCommands with TerminalCommand into GnuplotOutputFile); FinishPlotFile
// completes the file.
std::string FormatDrawCommands(PlotFormat format, const std::string& file, const std::string& script_file);
// What follows gnuplot's drawing of GnuplotOutputFile(format, path): a PNG
// is rasterised from its SVG (report/document/svg_figure.h), which is then
// removed; other formats are done.
// @throws WriteError naming the file that cannot be read or written.
void FinishPlotFile(PlotFormat format, const std::string& path);

// Settings every plot script starts with (after `reset`): encoding, CSV
// input, grid, borders, fonts of titles and keys.
std::string StylePreamble();

// sRGB colour "#rrggbb" of CIE L*C*h (D65) lightness l, chroma c and hue
// h_deg; the chroma is reduced until the colour lies inside the sRGB gamut.
std::string LchColour(double l, double c, double h_deg);
// "#rrggbb" mixed with white: each sRGB component moved `white_share`
// (0..1) of the way to 255. A pale copy of a colour, for a curve drawn
// wide under another.
std::string Tint(const std::string& colour, double white_share);

}  // namespace deb::report
