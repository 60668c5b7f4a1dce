#include "deb/report/plot_style.h"

#include <doctest/doctest.h>

#include <regex>
#include <set>
#include <utility>

#include "deb/io/budget_yaml.h"
#include "deb/report/report_writer.h"
#include "report_test_support.h"

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
  CHECK(ChannelStyle(3).colour == ChannelStyle(3).colour);
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
  WriteReportDirectory(budget, result, {}, options, dir.string());
  const std::string colours = ReadAll(dir / "plots" / "colours.csv");
  CHECK(colours.find("0,minor," + ContributorStyle(0).colour) != std::string::npos);
  CHECK(colours.find("1,major," + ContributorStyle(1).colour) != std::string::npos);
  // In the stacked CPS, 'major' is the bottom layer (drawn first) but keeps colour 1.
  const std::string cps = ReadAll(dir / "plots" / "z_cps.gp");
  const auto first_fill = cps.find("filledcurves fillcolor rgb '");
  REQUIRE(first_fill != std::string::npos);
  CHECK(cps.compare(first_fill + 28, 7, ContributorStyle(1).colour) == 0);
  CHECK(cps.find("'" + ContributorStyle(0).colour + "' title 'minor") != std::string::npos);
  CHECK(cps.find("'" + ContributorStyle(1).colour + "' title 'major") != std::string::npos);
}

TEST_CASE("every terminal is headless cairo or SVG") {
  CHECK(TerminalCommand(Terminal::kPng).find("pngcairo") != std::string::npos);
  CHECK(TerminalCommand(Terminal::kPdf).find("pdfcairo") != std::string::npos);
  CHECK(TerminalCommand(Terminal::kSvg).find("terminal svg") != std::string::npos);
  CHECK(FileExtension(Terminal::kPdf) == "pdf");
}

}  // namespace deb::report
