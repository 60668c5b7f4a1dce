#include "deb/report/path_plots.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/budget/path_response.h"
#include "deb/io/budget_yaml.h"
#include "report_test_support.h"

namespace deb::report {

TEST_CASE("one path plot per contributor and output, whose CSV holds |h| of every source channel") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = PathPlots(budget, result);
  REQUIRE(plots.size() == budget.contributors.size() * budget.outputs.size());
  CHECK(plots[0].name == "path_floor_to_z_velocity");
  CHECK(plots[3].name == "path_sensor_noise_to_z_displacement");
  CHECK(plots[3].script.find("[nm/(µm/s)]") != std::string::npos);
  const PathResponse r = ComputePathResponse(budget, 1, 1, result.grid.f_hz());
  std::istringstream lines(plots[3].csv);
  std::string line;
  std::getline(lines, line);  // comment
  std::getline(lines, line);
  CHECK(line == "frequency_hz,geophone_noise");
  std::getline(lines, line);
  double f, mag;
  REQUIRE(std::sscanf(line.c_str(), "%lf,%lf", &f, &mag) == 2);
  CHECK(f == doctest::Approx(result.grid.f_hz()[0]));
  CHECK(mag == doctest::Approx(std::sqrt(r.gain2[0][0])).epsilon(1e-9));
}

TEST_CASE("a source channel without transfer is named as zero in the key") {
  const Budget budget = LoadBudgetText(R"(
name: uncoupled
grid: {type: log, min_hz: 1, max_hz: 100, points: 30}
sources:
  - {name: v, unit: um/s, channels: [x, z], spectrum: {type: flat, level: 1}}
paths:
  - {name: g, type: gain, gain: [[0, 2]], input_unit: um/s, output_unit: um/s, outputs: [y]}
contributors:
  - {name: c, source: v, path: g}
outputs:
  - {name: out, signal: y, unit: um/s}
)",
                                       "uncoupled.yaml");
  const std::vector<Plot> plots = PathPlots(budget, Evaluate(budget));
  REQUIRE(plots.size() == 1);
  CHECK(plots[0].script.find("title 'x (zero)'") != std::string::npos);
  CHECK(plots[0].script.find("title 'z'") != std::string::npos);
}

}  // namespace deb::report
