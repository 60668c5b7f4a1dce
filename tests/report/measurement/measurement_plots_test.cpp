#include "deb/report/measurement/measurement_plots.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"

namespace deb::report {

TEST_CASE("a converted spectrum's figure: log axes over the bins above 0 Hz, a curve per channel in its colour") {
  // PSD 4e-2 at 0..100 Hz (one channel), 1e-14 (the other): drawn as ASD (0.2 and 1e-7), 5 decades deep.
  const std::vector<double> f_hz = {0.0, 1.0, 10.0, 100.0};
  Eigen::MatrixXd psd(4, 2);
  psd.col(0).setConstant(4e-2);
  psd.col(1).setConstant(1e-14);
  const Plot p = SpectrumTablePlot(f_hz, psd, {"floor", "sensor_noise"}, "um/s", true, "converted", "asd");
  CHECK(p.script == EmitFigure(p.figure));
  REQUIRE(p.figure.panels.size() == 1);
  const FigurePanel& panel = p.figure.panels[0];
  CHECK(panel.x.scale == AxisScale::kLog);
  CHECK(*panel.x.min == 1.0);  // 0 Hz has no place on a log axis
  CHECK(*panel.x.max == 100.0);
  // ASD 0.2 at the top: the axis ends at the decade above, 1, and is clipped 5 decades below 0.2, at the
  // decade below 2e-6 (not at 1e-7, where the second channel lies).
  CHECK(panel.y.scale == AxisScale::kLog);
  CHECK(*panel.y.max == doctest::Approx(1.0));
  CHECK(*panel.y.min == doctest::Approx(1e-6));
  REQUIRE(panel.series.size() == 2);
  CHECK(panel.series[0].name == "floor");
  CHECK(panel.series[0].data == "asd.plot.csv");
  CHECK(panel.series[0].y_columns == std::vector<std::size_t>{2});
  CHECK(panel.series[0].colour == ContributorStyle(0).colour);
  CHECK(panel.series[1].key == "sensor\\_noise");
  CHECK(panel.series[1].colour == ContributorStyle(1).colour);
  CHECK(panel.y.label.find("ASD") == 0);
}

TEST_CASE("a PSD without any value above 0 says so on a linear axis") {
  const std::vector<double> f_hz = {1.0, 10.0};
  const Eigen::MatrixXd psd = Eigen::MatrixXd::Zero(2, 1);
  const Plot p = SpectrumTablePlot(f_hz, psd, {"x"}, "", false, "zero", "z");
  const FigurePanel& panel = p.figure.panels.at(0);
  CHECK(panel.note == "every value is zero");
  CHECK(panel.y.scale == AxisScale::kLinear);
}

}  // namespace deb::report
