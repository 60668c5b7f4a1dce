#include "deb/report/compare/uncertainty_plots.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/support/csv_blocks.h"

namespace deb::report {
namespace {

// Output z [um] over 10 samples 10, 11, ..., 19 (4 meet the limit 13);
// parameter k (N/m) drives it, m barely.
UncertaintyResult Study() {
  UncertaintyResult r;
  UncertainParameter k, m;
  k.name = "k";
  k.unit = "N/m";
  m.name = "m";
  r.spec.parameters = {k, m};
  r.samples = 10;
  StudyMetric z;
  z.output = "z";
  z.unit = "um";
  z.limit = 13.0;
  z.nominal = 12.0;
  for (int s = 0; s < 10; ++s) z.values.push_back(10.0 + s);
  z.met = 4;
  z.spearman = {0.9, -0.2};
  r.metrics = {z};
  r.parameter_values = {std::vector<double>(10, 1.0), std::vector<double>(10, 2.0)};
  return r;
}

}  // namespace

TEST_CASE("the distribution figure: a histogram of fractions that sum to 1, an ECDF to 1, both lines keyed with the unit") {
  const std::vector<Plot> plots = UncertaintyPlots(Study());
  REQUIRE(plots.size() == 3);
  const Plot& d = plots[0];
  CHECK(d.name == "z_uncertainty");
  double sum = 0.0;
  for (double f : test::CsvBlockColumn(d.csv, 0, 1)) sum += f;
  CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));
  const std::vector<double> cdf = test::CsvBlockColumn(d.csv, 1, 1);
  REQUIRE(cdf.size() >= 2);
  CHECK(cdf.back() == 1.0);
  // The title names P(meet) with the limit's unit: 4 of 10.
  CHECK(d.figure.title.find("P(RMS ≤ 13 µm) = 40") != std::string::npos);
  REQUIRE(d.figure.panels.size() == 2);
  const std::vector<FigureAnnotation>& lines = d.figure.panels[0].annotations;
  REQUIRE(lines.size() == 2);
  CHECK(lines[0].key == "requirement 13 µm");
  CHECK(lines[1].key == "nominal design 12.00 µm");  // to 4 digits, as the tables
  // The nominal line is drawn over the samples' bars: not in their colour,
  // nor a dark grey that vanished on them.
  CHECK(lines[1].colour != d.figure.panels[0].series[0].colour);
  CHECK(lines[1].colour != "#404040");
  CHECK(d.caption.find("nominal design's RMS dotted orange") != std::string::npos);
}

TEST_CASE("the drivers figure greys a rank correlation within the sampling noise and draws the noise band") {
  // 10 samples: the band is 1.96 / 3 = 0.653; k at 0.9 is beyond it, m at -0.2 within.
  const std::vector<Plot> plots = UncertaintyPlots(Study());
  const Plot& d = plots[1];
  CHECK(d.name == "z_drivers");
  const std::vector<double> beyond = test::CsvBlockColumn(d.csv, 0, 5), within = test::CsvBlockColumn(d.csv, 0, 6);
  REQUIRE(beyond.size() == 2);
  CHECK(beyond == std::vector<double>{0.9, 0.0});  // the strongest on top: k, then m
  CHECK(within == std::vector<double>{0.0, -0.2});
  int band = 0;
  for (const FigureAnnotation& a : d.figure.panels[0].annotations)
    if (a.kind == AnnotationKind::kVerticalLine && std::abs(std::abs(a.x0) - 1.959963984540054 / 3.0) < 1e-12) ++band;
  CHECK(band == 2);
  CHECK(d.caption.find("within the dotted lines at ±0.65") != std::string::npos);
}

TEST_CASE("the scatter figure draws the two strongest drivers, each sample a row, and names both lines") {
  const std::vector<Plot> plots = UncertaintyPlots(Study());
  const Plot& s = plots[2];
  CHECK(s.name == "z_scatter");
  CHECK(test::CsvBlockColumn(s.csv, 0, 0).size() == 10);
  CHECK(s.figure.columns == 2);
  // The second driver, m at -0.2, is within the noise of 10 samples (0.65): its panel says so.
  REQUIRE(s.figure.panels.size() == 2);
  CHECK(s.figure.panels[0].title.find("noise") == std::string::npos);
  CHECK(s.figure.panels[1].title.find(", noise)") != std::string::npos);
  CHECK(s.caption.find("the requirement dashed red, the nominal design's RMS dotted orange") != std::string::npos);
}

}  // namespace deb::report
