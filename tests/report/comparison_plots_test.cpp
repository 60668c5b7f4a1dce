#include "deb/report/comparison_plots.h"

#include <doctest/doctest.h>

#include "deb/io/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("band labels are short") {
  CHECK(BandText(0.1, 1.0) == "0.1–1 Hz");
  CHECK(BandText(100, 1000) == "100–1000 Hz");
}

TEST_CASE("the band plot's CSV holds the engine's band RMS per contributor and in total") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const Plot p = BandPlot(result, 0);
  CHECK(p.name == "z_velocity_bands");
  std::istringstream lines(p.csv);
  std::string line;
  std::getline(lines, line);  // comment
  std::getline(lines, line);
  CHECK(line == "band,lo_hz,hi_hz,total,floor,sensor_noise");
  for (const BandResult& b : result.outputs[0].bands) {
    REQUIRE(std::getline(lines, line));
    int band;
    double lo, hi, total, floor, sensor;
    REQUIRE(std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%lf,%lf", &band, &lo, &hi, &total, &floor, &sensor) == 6);
    CHECK(lo == doctest::Approx(b.band.lo_hz));
    CHECK(total == doctest::Approx(std::sqrt(b.variance)).epsilon(1e-9));
    CHECK(floor == doctest::Approx(std::sqrt(b.contributor_variance[0])).epsilon(1e-9));
    CHECK(sensor == doctest::Approx(std::sqrt(b.contributor_variance[1])).epsilon(1e-9));
  }
}

TEST_CASE("the overview has one panel per output, at most eight per page, spread evenly over the pages") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  BudgetResult result = Evaluate(budget);
  std::vector<Plot> pages = OverviewPlots(result);
  REQUIRE(pages.size() == 1);
  CHECK(pages[0].name == "overview");
  CHECK(pages[0].script.find("set multiplot layout 1,2") != std::string::npos);
  CHECK(pages[0].script.find("PASS (requirement 20)") != std::string::npos);
  const auto copy = result.outputs;
  for (int i = 0; i < 3; ++i) result.outputs.insert(result.outputs.end(), copy.begin(), copy.end());
  pages = OverviewPlots(result);  // 8 outputs
  REQUIRE(pages.size() == 1);
  CHECK(pages[0].script.find("set multiplot layout 2,4") != std::string::npos);
  result.outputs.push_back(copy[0]);
  pages = OverviewPlots(result);  // 9 outputs: 5 + 4
  REQUIRE(pages.size() == 2);
  CHECK(pages[0].name == "overview_1");
  CHECK(pages[0].script.find("set multiplot layout 2,3") != std::string::npos);
  CHECK(pages[1].script.find("set multiplot layout 2,2") != std::string::npos);
}

}  // namespace deb::report
