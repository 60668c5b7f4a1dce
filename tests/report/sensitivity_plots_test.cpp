#include "deb/report/sensitivity_plots.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

namespace deb::report {
namespace {

// Output y (variance 4) with contributors a and b; parameters k and m.
OutputResult Output() {
  OutputResult o;
  o.name = "y";
  o.unit = "nm";
  o.variance = 4.0;
  ContributorResult a, b;
  a.name = "a";
  a.variance = 3.0;
  b.name = "b";
  b.variance = 1.0;
  o.contributors = {a, b};
  return o;
}

// d var / d ln p per term: k moves a by +2 and b by -1 (total +1, elasticity 0.25);
// m moves b by -4 (total -4, elasticity -1).
std::vector<Sensitivity> All() {
  return {{"k", "y", "nm", "total", 4.0, 1.0, 0.25}, {"k", "y", "nm", "a", 3.0, 2.0, 2.0 / 3.0},
          {"k", "y", "nm", "b", 1.0, -1.0, -1.0},    {"m", "y", "nm", "total", 4.0, -4.0, -1.0},
          {"m", "y", "nm", "a", 3.0, 0.0, 0.0},      {"m", "y", "nm", "b", 1.0, -4.0, -4.0}};
}

}  // namespace

TEST_CASE("tornado bars: parameters by the magnitude of the total's elasticity, each with its contributors' shares") {
  const auto bars = TornadoBars(All(), Output());
  REQUIRE(bars.size() == 5);  // m: total, b (a moves 0: left out); k: total, a, b
  CHECK(bars[0].parameter == "m");
  CHECK(bars[0].contributor == "total");
  CHECK(bars[0].value == -1.0);
  CHECK(bars[1].contributor == "b");
  CHECK(bars[1].value == -1.0);  // -4 / 4
  CHECK(bars[2].parameter == "k");
  CHECK(bars[3].contributor == "a");
  CHECK(bars[3].contributor_index == 0);
  CHECK(bars[4].contributor == "b");
  // The shares of one parameter sum to the total's elasticity.
  CHECK(bars[3].value + bars[4].value == doctest::Approx(bars[2].value));
}

TEST_CASE("the tornado chart names every bar on the y axis, largest on top, and its data top to bottom") {
  BudgetResult nominal;
  nominal.outputs = {Output()};
  const auto plots = TornadoPlots(All(), nominal);
  REQUIRE(plots.size() == 1);
  CHECK(plots[0].name == "y_tornado");
  const std::string& s = plots[0].script;
  CHECK(s.find("'m: total' 4") != std::string::npos);
  CHECK(s.find("'of which b' 3") != std::string::npos);
  CHECK(s.find("'k: total' 2") != std::string::npos);
  CHECK(s.find("set xrange [-1.3:1.3]") != std::string::npos);  // symmetric about 0, the largest bar + 30 %
  CHECK(plots[0].csv.find("\n4,-1,m,total,-1\n") != std::string::npos);
}

}  // namespace deb::report
