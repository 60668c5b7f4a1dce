#include "deb/report/figure/plot_style.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <regex>
#include <set>
#include <utility>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/report_writer.h"
#include "deb/report/budget/spectrum_plots.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

using namespace deb::test;

// Two flat sources through unit gains: the second contributor (index 1) has
// 100 times the variance of the first, so share order is the reverse of
// budget order.
constexpr const char* kReversedShares = R"(
name: reversed_shares
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - {name: small, unit: nm, spectrum: {type: flat, level: 1}}
  - {name: large, unit: nm, spectrum: {type: flat, level: 100}}
paths:
  - {name: one, type: gain, gain: [[1]], input_unit: nm, output_unit: nm, outputs: [z]}
contributors:
  - {name: minor, source: small, path: one}
  - {name: major, source: large, path: one}
outputs:
  - {name: z, signal: z, unit: nm}
)";

}  // namespace

TEST_CASE("contributor styles are valid colours, distinct for 16 contributors, and the same on every call") {
  const std::regex hex("#[0-9a-f]{6}");
  std::set<std::string> colours;
  std::set<std::pair<double, std::string>> grey_styles;
  for (std::size_t i = 0; i < 16; ++i) {
    const SeriesStyle s = ContributorStyle(i);
    CHECK(std::regex_match(s.colour, hex));
    CHECK(std::regex_match(s.edge_colour, hex));
    CHECK(s.colour == ContributorStyle(i).colour);
    colours.insert(s.colour);
    if (i < 12) grey_styles.insert({s.lightness, s.dash});
  }
  CHECK(colours.size() == 16);
  CHECK(grey_styles.size() == 12);  // lightness x dash tells 12 lines apart without colour
}

TEST_CASE("neighbouring contributors, and lines with the same dash pattern, differ clearly in lightness") {
  for (std::size_t i = 0; i + 1 < 24; ++i)
    CHECK(std::abs(ContributorStyle(i).lightness - ContributorStyle(i + 1).lightness) >= 15.0);
  for (std::size_t i = 0; i < 12; ++i)
    for (std::size_t j = i + 1; j < 12; ++j)
      if (ContributorStyle(i).dash == ContributorStyle(j).dash)
        CHECK(std::abs(ContributorStyle(i).lightness - ContributorStyle(j).lightness) >= 20.0);
}

TEST_CASE("in a greyscale print the first 12 contributors keep 12 grey levels, the colour's L* and its grey agreeing") {
  std::vector<double> grey;
  for (std::size_t i = 0; i < 12; ++i) {
    const SeriesStyle s = ContributorStyle(i);
    // Both the CIE L* and the Rec. 601 grey a printer makes: greens and
    // cyans of high chroma print 10 L* darker than their L*.
    CHECK_MESSAGE(std::abs(Lightness(s.colour) - s.lightness) <= 3.0, i << " " << s.colour);
    CHECK_MESSAGE(std::abs(GreyLightness(s.colour) - s.lightness) <= 3.0, i << " " << s.colour);
    grey.push_back(GreyLightness(s.colour));
  }
  for (std::size_t i = 0; i < 12; ++i) {
    CHECK(std::abs(grey[i] - grey[(i + 1) % 12]) >= 14.0);  // neighbours, also 11 and 12
    for (std::size_t j = i + 1; j < 12; ++j) {
      CHECK_MESSAGE(std::abs(grey[i] - grey[j]) >= 1.0, i << " " << j);  // 12 distinct levels
      // Fills of one kind (solid 0-5, hatched 6-11) are 10 L* apart, less the tolerance.
      if ((i < 6) == (j < 6)) CHECK_MESSAGE(std::abs(grey[i] - grey[j]) >= 4.0, i << " " << j);
    }
  }
  // Levels 5 L* apart: rounded to 5, the 12 greys fall on 12 steps.
  std::set<long> levels;
  for (std::size_t i = 0; i < 12; ++i) levels.insert(std::lround(ContributorStyle(i).lightness / 5.0));
  CHECK(levels.size() == 12);
  CHECK(GreyLightness("#777777") == doctest::Approx(50.0).epsilon(0.01));
  CHECK(GreyLightness("#00ff00") == doctest::Approx(Lightness("#969696")).epsilon(0.01));  // 0.587 x 255
}

TEST_CASE("fills beyond the first six contributors are hatched, in a pattern of their own and a contrasting colour") {
  std::set<int> patterns;
  std::set<std::pair<double, int>> fills;
  for (std::size_t i = 0; i < 24; ++i) {
    const SeriesStyle s = ContributorStyle(i);
    const bool hatched = (i % 12 >= 6) != (i >= 12);
    CHECK_MESSAGE((s.fill_pattern != 0) == hatched, i);
    if (i >= 6 && i < 12) patterns.insert(s.fill_pattern);
    if (hatched) CHECK(std::abs(GreyLightness(s.hatch_colour) - GreyLightness(s.colour)) >= 25.0);
    fills.insert({s.lightness, s.fill_pattern});
  }
  CHECK(patterns.size() == 6);
  CHECK(fills.size() == 24);  // 24 contributors, 24 fills told apart without colour

  const std::vector<std::string> solid = FillClauses(ContributorStyle(0), "'d.csv' using 1:2", "boxes", "title 'a'", "#303030");
  REQUIRE(solid.size() == 1);
  CHECK(solid[0] == "'d.csv' using 1:2 with boxes fillcolor rgb '" + ContributorStyle(0).colour + "' title 'a'");
  const SeriesStyle h = ContributorStyle(6);
  const std::vector<std::string> hatched = FillClauses(h, "'d.csv' using 1:2", "boxes", "title 'g'", "#303030");
  REQUIRE(hatched.size() == 3);
  CHECK(hatched[0] == "'d.csv' using 1:2 with boxes fillcolor rgb '" + h.colour + "' notitle");
  CHECK(hatched[1] == "'d.csv' using 1:2 with boxes fillstyle transparent pattern " + std::to_string(h.fill_pattern) +
                          " border linecolor rgb '" + h.colour + "' fillcolor rgb '" + h.hatch_colour + "' title 'g'");
  CHECK(hatched[2].find("fillstyle empty border linecolor rgb '#303030'") != std::string::npos);
  CHECK(FillClauses(h, "x", "filledcurves", "notitle").size() == 2);
}

TEST_CASE("the stacked CPS and the band bars of a budget with 8 contributors hatch the 7th and 8th") {
  std::string yaml = "name: eight\ngrid: {type: log, min_hz: 1, max_hz: 100, points: 50}\nsources:\n";
  for (int i = 0; i < 8; ++i)
    yaml += "  - {name: s" + std::to_string(i) + ", unit: nm, spectrum: {type: flat, level: " + std::to_string(i + 1) + "}}\n";
  yaml += "paths:\n  - {name: one, type: gain, gain: [[1]], input_unit: nm, output_unit: nm, outputs: [z]}\ncontributors:\n";
  for (int i = 0; i < 8; ++i) yaml += "  - {name: c" + std::to_string(i) + ", source: s" + std::to_string(i) + ", path: one}\n";
  yaml += "outputs:\n  - {name: z, signal: z, unit: nm}\n";
  const Budget budget = LoadBudgetText(yaml, "eight.yaml");
  const fs::path dir = TempDir("eight") / "report";
  ReportOptions options;
  options.plots = false;
  WriteReportDirectory(Evaluate(budget), {}, options, dir.string());
  for (const char* plot : {"z_cps.gp", "z_bands.gp", "overview.gp"}) {
    const std::string script = ReadAll(dir / "plots" / plot);
    CHECK_MESSAGE(script.find("fillstyle transparent pattern " + std::to_string(ContributorStyle(6).fill_pattern) +
                              " border linecolor rgb '" + ContributorStyle(6).colour + "'") != std::string::npos,
                  plot);
    CHECK_MESSAGE(script.find("fillcolor rgb '" + ContributorStyle(7).hatch_colour + "'") != std::string::npos, plot);
  }
  // The key shows the hatch: the title sits on the hatched clause.
  CHECK(ReadAll(dir / "plots" / "z_bands.gp").find("'" + ContributorStyle(6).hatch_colour + "' title 'c6'") !=
        std::string::npos);
  CHECK(ReadAll(dir / "plots" / "colours.csv").find("6,c6," + ContributorStyle(6).colour + ",") != std::string::npos);
}

// CIE L*a*b* of an sRGB colour "#rrggbb" (D65), for colour differences.
std::array<double, 3> Lab(const std::string& colour) {
  double rgb[3];
  for (int i = 0; i < 3; ++i) {
    const double v = std::stoi(colour.substr(1 + 2 * i, 2), nullptr, 16) / 255.0;
    rgb[i] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  const double x = (0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2]) / 0.95047;
  const double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
  const double z = (0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2]) / 1.08883;
  const auto f = [](double t) { return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

TEST_CASE("the first 8 contributor colours are a qualitative palette: distinct hues that also separate in grey") {
  constexpr double kPi = 3.14159265358979;
  for (std::size_t i = 0; i < 8; ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const auto a = Lab(ContributorStyle(i).colour), b = Lab(ContributorStyle(j).colour);
      const double delta_e = std::sqrt(std::pow(a[0] - b[0], 2) + std::pow(a[1] - b[1], 2) + std::pow(a[2] - b[2], 2));
      CHECK_MESSAGE(delta_e > 35.0, i, " ", j, " ", ContributorStyle(i).colour, " ", ContributorStyle(j).colour);
      // Hues at least 40 deg apart unless the greys differ by >= 15.
      double dh = std::fabs(std::atan2(a[2], a[1]) - std::atan2(b[2], b[1])) * 180.0 / kPi;
      dh = std::min(dh, 360.0 - dh);
      const double grey = std::fabs(GreyLightness(ContributorStyle(i).colour) - GreyLightness(ContributorStyle(j).colour));
      CHECK_MESSAGE((dh > 40.0 || grey >= 15.0), i, " ", j);
    }
}

TEST_CASE("any 12 consecutive contributors, which share a chart's bars, differ clearly in colour") {
  // Contributors 8-23 take the hue farthest from the 11 before them: turning
  // the palette by a fixed angle gave air_turbulence and y_crosstalk two
  // browns, motor_ripple and frame_thermal two greens: the nearest pair was
  // ΔE 15; now 30.
  double nearest = 1e9;
  for (std::size_t i = 0; i < 24; ++i)
    for (std::size_t j = i >= 11 ? i - 11 : 0; j < i; ++j) {
      const auto a = Lab(ContributorStyle(i).colour), b = Lab(ContributorStyle(j).colour);
      const double delta_e = std::sqrt(std::pow(a[0] - b[0], 2) + std::pow(a[1] - b[1], 2) + std::pow(a[2] - b[2], 2));
      nearest = std::min(nearest, delta_e);
      CHECK_MESSAGE(delta_e >= 28.0, i, " ", j, " ", ContributorStyle(i).colour, " ", ContributorStyle(j).colour);
    }
  MESSAGE("nearest pair: ΔE ", nearest);
}

TEST_CASE("a tint mixes a colour with white, component by component") {
  CHECK(Tint("#000000", 0.5) == "#808080");  // 127.5 rounds up
  CHECK(Tint("#ff0000", 0.0) == "#ff0000");
  CHECK(Tint("#0e5274", 1.0) == "#ffffff");
  CHECK(Tint("#204060", 0.25) == "#587088");  // 32 + 0.25 (255 - 32) = 87.75
}

TEST_CASE("source channels have a style family of their own: distinct markers, none of the contributor colours") {
  std::set<std::string> colours, contributor_colours;
  std::set<int> markers;
  for (std::size_t i = 0; i < 12; ++i) contributor_colours.insert(ContributorStyle(i).colour);
  for (std::size_t i = 0; i < 12; ++i) {
    const SeriesStyle s = ChannelStyle(i);
    CHECK(std::regex_match(s.colour, std::regex("#[0-9a-f]{6}")));
    CHECK(s.point_type > 0);
    CHECK(ContributorStyle(i).point_type == 0);  // contributors are lines without markers
    CHECK(contributor_colours.count(s.colour) == 0);
    colours.insert(s.colour);
    markers.insert(s.point_type);
  }
  CHECK(colours.size() == 12);
  CHECK(markers.size() == 12);
  // Past 12 channels the markers repeat, the colours do not: channel 12 keeps
  // channel 0's marker and lightness at another hue.
  CHECK(ChannelStyle(12).point_type == ChannelStyle(0).point_type);
  CHECK(ChannelStyle(12).colour != ChannelStyle(0).colour);
}

TEST_CASE("CIE L*C*h colours: achromatic lightness gives the sRGB grey, and out-of-gamut chroma is reduced") {
  CHECK(LchColour(0, 0, 0) == "#000000");
  CHECK(LchColour(100, 0, 0) == "#ffffff");
  CHECK(LchColour(50, 0, 123) == "#777777");  // L* 50 is sRGB 119
  // Chroma 200 is outside sRGB at any hue; the result is still a colour of that lightness.
  CHECK(LchColour(60, 200, 40).size() == 7);
}

TEST_CASE("contributor colours are stable between runs: the same budget gives the same scripts and colours") {
  const fs::path dir = TempDir("stable");
  for (const char* run : {"a", "b"}) {
    const Command r = RunDeb("run -q " + ExampleBudget() + " --out " + (dir / run).string() + " --format png");
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  }
  CHECK(ReadAll(dir / "a" / "plots" / "colours.csv") == ReadAll(dir / "b" / "plots" / "colours.csv"));
  int scripts = 0;
  for (const auto& f : fs::directory_iterator(dir / "a" / "plots")) {
    if (f.path().extension() != ".gp") continue;
    ++scripts;
    CHECK_MESSAGE(ReadAll(f.path()) == ReadAll(dir / "b" / "plots" / f.path().filename()), f.path().filename());
  }
  CHECK(scripts > 5);
}

TEST_CASE("a contributor's colour follows its index in the budget, not its share") {
  const Budget budget = LoadBudgetText(kReversedShares, "reversed.yaml");
  const BudgetResult result = Evaluate(budget);
  REQUIRE(result.outputs[0].contributors[1].variance > result.outputs[0].contributors[0].variance);
  const fs::path dir = TempDir("keyed") / "report";
  ReportOptions options;
  options.plots = false;  // the scripts are written without drawing
  WriteReportDirectory(result, {}, options, dir.string());
  const std::string colours = ReadAll(dir / "plots" / "colours.csv");
  CHECK(colours.find("0,minor," + ContributorStyle(0).colour) != std::string::npos);
  CHECK(colours.find("1,major," + ContributorStyle(1).colour) != std::string::npos);
  // In the stacked CPS, 'major' is the top layer (drawn and keyed first) but keeps colour 1.
  const PlotFigure cps = SpectrumPlots(result, 0, {})[0].figure;
  REQUIRE(cps.panels[0].series.size() >= 2);
  CHECK(cps.panels[0].series[0].name == "major");
  CHECK(cps.panels[0].series[0].colour == ContributorStyle(1).colour);
  CHECK(FindSeries(cps, "minor")->colour == ContributorStyle(0).colour);
  // The script draws it in that colour.
  CHECK(ReadAll(dir / "plots" / "z_cps.gp").find("'" + ContributorStyle(1).colour + "' title 'major") != std::string::npos);
}

TEST_CASE("every terminal is headless cairo or SVG; a PNG is gnuplot's SVG at its size, rasterised by deb") {
  CHECK(TerminalCommand(PlotFormat::kPng).find("terminal svg enhanced size 1200,720") != std::string::npos);
  CHECK(TerminalCommand(PlotFormat::kPng).find("\ndeb_png = 1\n") != std::string::npos);
  CHECK(TerminalCommand(PlotFormat::kPdf).find("pdfcairo") != std::string::npos);
  CHECK(TerminalCommand(PlotFormat::kSvg).find("terminal svg") != std::string::npos);
  // The others clear the PNG's variable, which a batch's earlier PNG set.
  CHECK(TerminalCommand(PlotFormat::kSvg).find("undefine deb_png") != std::string::npos);
  CHECK(TerminalCommand(PlotFormat::kPdf).find("undefine deb_png") != std::string::npos);
  CHECK(FileExtension(PlotFormat::kPdf) == "pdf");
  CHECK(GnuplotOutputFile(PlotFormat::kPng, "a.png") == "a.png.svg");
  CHECK(GnuplotOutputFile(PlotFormat::kSvg, "a.svg") == "a.svg");
  CHECK(GnuplotOutputFile(PlotFormat::kPdf, "a.pdf") == "a.pdf");
}

}  // namespace deb::report
