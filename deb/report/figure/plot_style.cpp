#include "deb/report/figure/plot_style.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/report/document/svg_figure.h"
#include "deb/report/figure/plot.h"

namespace deb::report {
namespace {

// Lightness levels (L* of the colour and of its grey in print) in an order
// that keeps neighbours >= 20 apart, gives the contributors sharing a dash
// pattern (i, i + 6) levels >= 25 apart, spreads the first six (solid fills)
// 10 apart, and gives the next six (hatched fills) the levels in between:
// 12 distinct greys. The first two, in most reports, are 30 apart.
constexpr std::array<double, 12> kLightness = {30, 60, 80, 50, 70, 40, 65, 35, 55, 25, 45, 75};
constexpr std::array<const char*, 6> kDashes = {"solid", "(10,5)", "(12,4,2,4)", "(4,4)", "(2,3)", "(16,4,4,4,4,4)"};
// gnuplot fill patterns as its SVG terminal draws them (the PNGs and
// report.pdf's figures): 4 and 7 fall to the right, 5 and 6 rise, 6 and 7
// steeper and denser; 1 and 2 crosshatches. Hatched neighbours alternate.
constexpr std::array<int, 6> kPatterns = {4, 5, 1, 7, 6, 2};
constexpr double kGreyTolerance = 3.0;  // L*, between the level and the colour's two greys
constexpr double kGoldenAngleDeg = 137.50776405;
// Hues (CIE LCh) of the first 8 contributors, a qualitative palette matched
// to their lightness (kLightness): dark blue, orange, light yellow, purple,
// sky blue, crimson, light green, dark olive. Hues closer than 45° differ by
// >= 25 in lightness. Contributors 8-23 choose theirs (ContributorHue);
// 24.. take the same hues turned by 22.5°, then by -22.5°, 11.25°.
constexpr std::array<double, 8> kFirstHues = {255, 40, 95, 300, 210, 345, 140, 75};
constexpr std::array<double, 4> kHueTurns = {0.0, 22.5, -22.5, 11.25};
constexpr double kFirstHueDeg = kFirstHues[0];
constexpr double kChroma = 58.0;

// Linear sRGB of CIE L*a*b* (D65 white).
std::array<double, 3> LabToLinearRgb(double l, double a, double b) {
  const double fy = (l + 16.0) / 116.0, fx = fy + a / 500.0, fz = fy - b / 200.0;
  const auto finv = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d ? t * t * t : 3.0 * d * d * (t - 4.0 / 29.0);
  };
  const double x = 0.95047 * finv(fx), y = finv(fy), z = 1.08883 * finv(fz);
  return {3.2404542 * x - 1.5371385 * y - 0.4985314 * z, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
          0.0556434 * x - 0.2040259 * y + 1.0572252 * z};
}

bool InGamut(const std::array<double, 3>& rgb) {
  return std::all_of(rgb.begin(), rgb.end(), [](double v) { return v >= -1e-9 && v <= 1.0 + 1e-9; });
}

int Encode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255.0 * s));
}

// sRGB components (0..255) of "#rrggbb".
std::array<int, 3> Components(const std::string& colour) {
  DEB_DEMAND(colour.size() == 7 && colour[0] == '#');
  std::array<int, 3> c{};
  for (int i = 0; i < 3; ++i) c[i] = std::stoi(colour.substr(1 + 2 * i, 2), nullptr, 16);
  return c;
}

// Linear value of an encoded sRGB component 0..255.
double Decode(double encoded) {
  const double v = encoded / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// CIE L* of relative luminance y.
double LightnessOfLuminance(double y) {
  return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : 24389.0 / 27.0 * y;
}

// A colour of hue h_deg whose CIE L* and Rec. 601 grey both lie within
// kGreyTolerance of l: chroma up to c, reduced where the two disagree (greens
// and cyans print darker than their L*), the L* asked for nudged by up to 4.
std::string PrintableColour(double l, double c, double h_deg) {
  for (double chroma = c; chroma > 0.0; chroma -= 2.0) {
    std::string best;
    double best_error = kGreyTolerance;
    for (double dl = -4.0; dl <= 4.0; dl += 0.5) {
      const std::string colour = LchColour(l + dl, chroma, h_deg);
      const double error = std::max(std::abs(Lightness(colour) - l), std::abs(GreyLightness(colour) - l));
      if (error <= best_error) {
        best = colour;
        best_error = error;
      }
    }
    if (!best.empty()) return best;
  }
  return LchColour(l, 0.0, 0.0);  // grey: both are l
}

// CIE L*a*b* of "#rrggbb".
std::array<double, 3> LabOf(const std::string& colour) {
  const auto c = Components(colour);
  const double r = Decode(c[0]), g = Decode(c[1]), b = Decode(c[2]);
  const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
  const auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

// CIE76 ΔE.
double DeltaE(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Contributors 8-23 (those a report holds in its table of styles): the
// colour at their lightness level whose hue, in steps of 7.5°, lies
// farthest (CIE76 ΔE) from the 11 contributors before them, which share a
// chart's bars with them. (Turning the palette's hues by a fixed angle gave
// two browns and two greens among 12 bars.) Later ones turn the palette.
// Between two hatched fills the distance counts lightness at half weight:
// their hatch lines mix light and dark strokes, so that a hue is what tells
// them apart (at full weight three greens of L* 35, 45 and 65 were chosen
// for wafer_stage's hatched bars, alike in report.pdf's band charts).
constexpr std::size_t kChosenHues = 24;
constexpr double kHatchedLightnessWeight = 0.5;
constexpr double kLeastDeltaE = 6.0;  // from every earlier contributor

// Whether contributor `index` is drawn hatched: indices 6-11 of every 12, and
// 0-5 of every other 12, so that 24 contributors differ in grey level or in
// hatching.
bool Hatched(std::size_t index) { return (index % 12 >= 6) != ((index / 12) % 2 == 1); }

// Returns the hue (degrees) of contributor `index` at `lightness`.
double ContributorHue(std::size_t index, double lightness) {
  if (index < 8 || index >= kChosenHues)
    return std::fmod(kFirstHues[index % 8] + kHueTurns[(index / 8) % 4] + 360.0, 360.0);
  std::vector<std::array<double, 3>> before, earlier;
  std::vector<double> lightness_weight;
  for (std::size_t j = index >= 11 ? index - 11 : 0; j < index; ++j) {
    before.push_back(LabOf(ContributorStyle(j).colour));
    lightness_weight.push_back(Hatched(j) && Hatched(index) ? kHatchedLightnessWeight : 1.0);
  }
  for (std::size_t j = 0; j + 11 < index; ++j) earlier.push_back(LabOf(ContributorStyle(j).colour));
  double best = 0.0, best_distance = -1.0;
  for (int step = 0; step < 48; ++step) {
    const std::array<double, 3> lab = LabOf(PrintableColour(lightness, kChroma, 7.5 * step));
    // Never the colour of an earlier contributor (one of the same lightness
    // twelve places back), which shares no chart's bars with it but does
    // share the table of styles and the key of a drill-down.
    if (std::any_of(earlier.begin(), earlier.end(), [&](const auto& e) { return DeltaE(lab, e) < kLeastDeltaE; }))
      continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < before.size(); ++k) {
      std::array<double, 3> other = before[k];
      other[0] = lab[0] + lightness_weight[k] * (other[0] - lab[0]);
      nearest = std::min(nearest, DeltaE(lab, other));
    }
    if (nearest > best_distance + 1e-9) {
      best = 7.5 * step;
      best_distance = nearest;
    }
  }
  return best;
}

SeriesStyle MakeContributorStyle(std::size_t index) {
  SeriesStyle s;
  s.lightness = kLightness[index % kLightness.size()];
  const double hue = ContributorHue(index, s.lightness);
  s.colour = PrintableColour(s.lightness, kChroma, hue);
  s.edge_colour = LchColour(std::max(s.lightness - 28.0, 12.0), kChroma, hue);
  s.dash = kDashes[index % kDashes.size()];
  if (Hatched(index)) {
    s.fill_pattern = kPatterns[index % kPatterns.size()];
    // Dark lines on light fills, light lines on dark ones; either shows on the
    // key's white. The dense crosshatch (2) covers most of its area: its
    // lines nearer the fill's lightness, or the area reads in the hatch's
    // colour and the key's small sample in the fill's (wafer_stage's
    // environment/, pink in the key and plum in the plot).
    const bool dense = s.fill_pattern == 2;
    s.hatch_colour = PrintableColour(s.lightness >= 50.0 ? std::max(s.lightness - (dense ? 28.0 : 42.0), 12.0)
                                                         : s.lightness + (dense ? 28.0 : 30.0),
                                     40.0, hue);
  }
  return s;
}

}  // namespace

double Lightness(const std::string& colour) {
  const auto c = Components(colour);
  return LightnessOfLuminance(0.2126 * Decode(c[0]) + 0.7152 * Decode(c[1]) + 0.0722 * Decode(c[2]));
}

double GreyLightness(const std::string& colour) {
  const auto c = Components(colour);
  return LightnessOfLuminance(Decode(0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]));  // luma of the encoded values
}

std::string LchColour(double l, double c, double h_deg) {
  const double h = h_deg * kPi / 180.0;
  double lo = 0.0, hi = c;
  if (!InGamut(LabToLinearRgb(l, c * std::cos(h), c * std::sin(h)))) {
    for (int i = 0; i < 40; ++i) {  // largest in-gamut chroma by bisection
      const double mid = 0.5 * (lo + hi);
      (InGamut(LabToLinearRgb(l, mid * std::cos(h), mid * std::sin(h))) ? lo : hi) = mid;
    }
    c = lo;
  }
  const auto rgb = LabToLinearRgb(l, c * std::cos(h), c * std::sin(h));
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", Encode(rgb[0]), Encode(rgb[1]), Encode(rgb[2]));
  return text;
}

std::string Tint(const std::string& colour, double white_share) {
  DEB_DEMAND(white_share >= 0.0 && white_share <= 1.0);
  const auto c = Components(colour);
  char text[8];
  const auto mix = [&](int v) { return static_cast<int>(std::lround(v + white_share * (255 - v))); };
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", mix(c[0]), mix(c[1]), mix(c[2]));
  return text;
}

SeriesStyle ContributorStyle(std::size_t index) {
  // The colour search costs ~500 colour conversions a style and reports ask
  // often: each of the first 24 is made once, when it is first asked for
  // (all 24 at once took a millisecond of a 2-contributor run).
  static std::array<std::once_flag, 24> made;
  static std::array<SeriesStyle, 24> table;
  if (index >= table.size()) return MakeContributorStyle(index);
  std::call_once(made[index], [index] { table[index] = MakeContributorStyle(index); });
  return table[index];
}

SeriesStyle GroupStyle(std::size_t contributors, std::size_t group) { return ContributorStyle(contributors + group); }

std::vector<std::string> FillClauses(const SeriesStyle& style, const std::string& source, const std::string& with,
                                     const std::string& key, const std::string& outline_colour) {
  const std::string solid = source + " with " + with + " fillcolor rgb " + Quote(style.colour);
  if (!style.fill_pattern) return {solid + " " + key};
  // The hatch's border in the fill colour gives its key sample (hatch on
  // the key's white) the colour of the layer.
  std::vector<std::string> clauses = {
      solid + " notitle", source + " with " + with + " fillstyle transparent pattern " +
                              std::to_string(style.fill_pattern) + " border linecolor rgb " + Quote(style.colour) +
                              " fillcolor rgb " + Quote(style.hatch_colour) + " " + key};
  if (!outline_colour.empty())
    clauses.push_back(source + " with " + with + " fillstyle empty border linecolor rgb " + Quote(outline_colour) +
                      " linecolor rgb " + Quote(outline_colour) + " notitle");
  return clauses;
}

SeriesStyle ChannelStyle(std::size_t index) {
  // Filled markers first: gnuplot's SVG terminal (the PNGs, report.pdf)
  // strokes an open one with a hairline that reads faintly on a dense curve;
  // the markers are sparse, so a filled one hides little of it.
  constexpr std::array<int, 12> kPoints = {7, 5, 9, 13, 11, 6, 4, 8, 12, 10, 1, 2};
  constexpr std::array<double, 4> kChannelLightness = {38, 58, 48, 66};
  constexpr double kFirstChannelHueDeg = 75.0, kAvoidDeg = 25.0;
  const auto hue_distance = [](double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
  };
  double hue = kFirstChannelHueDeg;
  for (std::size_t accepted = 0, j = 0;; ++j) {
    hue = std::fmod(kFirstChannelHueDeg + kGoldenAngleDeg * static_cast<double>(j), 360.0);
    if (hue_distance(hue, kFirstHueDeg) < kAvoidDeg || hue_distance(hue, kFirstHues[1]) < kAvoidDeg)
      continue;  // the hues of contributors 0 and 1
    if (accepted++ == index) break;
  }
  SeriesStyle s;
  s.lightness = kChannelLightness[index % kChannelLightness.size()];
  s.colour = LchColour(s.lightness, 70.0, hue);
  s.edge_colour = LchColour(std::max(s.lightness - 28.0, 12.0), 70.0, hue);
  s.dash = "solid";
  s.point_type = kPoints[index % kPoints.size()];
  return s;
}

std::string TerminalCommand(PlotFormat format) {
  const std::string font = std::string(" font '") + kFont + ",";
  switch (format) {
    case PlotFormat::kPng:
      // 11 pt at 96 dpi: 14.7 px.
      return "set terminal svg enhanced size " + std::to_string(kPngWidthPx) + "," + std::to_string(kPngHeightPx) +
             " background '#ffffff'" + font + "11' fontscale 1.3333 linewidth 1.2\n" + kPngSourceVariable + " = 1\n";
    case PlotFormat::kSvg:
      return "set terminal svg enhanced size 1200,720 background '#ffffff'" + font + "13' linewidth 1.2\nundefine " +
             kPngSourceVariable + "\n";
    case PlotFormat::kPdf:
      return "set terminal pdfcairo enhanced size 29.7cm,21cm background '#ffffff'" + font +
             "11' linewidth 1.5\nundefine " + kPngSourceVariable + "\n";
  }
  return "";
}

std::string GnuplotOutputFile(PlotFormat format, const std::string& file) {
  return format == PlotFormat::kPng ? file + ".svg" : file;
}

std::string FormatDrawCommands(PlotFormat format, const std::string& file, const std::string& script_file) {
  return DrawCommands(TerminalCommand(format), GnuplotOutputFile(format, file), script_file);
}

void FinishPlotFile(PlotFormat format, const std::string& path) {
  if (format != PlotFormat::kPng) return;
  const std::string source = GnuplotOutputFile(format, path);
  RasteriseSvg(source, path, kPngWidthPx, kPngHeightPx);
  std::error_code ec;
  std::filesystem::remove(source, ec);
  if (ec) throw WriteError("cannot remove " + source + ": " + ec.message());
}

std::string FileExtension(PlotFormat format) {
  switch (format) {
    case PlotFormat::kPng: return "png";
    case PlotFormat::kSvg: return "svg";
    case PlotFormat::kPdf: return "pdf";
  }
  return "";
}

std::string StylePreamble() {
  return "set encoding utf8\n"
         "set datafile separator comma\n"
         "set border 3 linewidth 1.0 linecolor rgb '#404040'\n"
         "set tics nomirror out scale 0.6 textcolor rgb '#202020'\n"
         "set style line 101 linecolor rgb '#c8c8c8' linewidth 0.7 dashtype solid\n"
         "set style line 102 linecolor rgb '#e6e6e6' linewidth 0.6 dashtype solid\n"
         "set grid xtics ytics mxtics linestyle 101, linestyle 102\n"
         "set title font ',14' offset 0,-0.3\n"
         "set key font ',10' samplen 2.5 spacing 1.15 nobox opaque\n"
         "set xlabel offset 0,0.4\n"
         "set style fill solid 1.0 noborder\n";
}

}  // namespace deb::report
