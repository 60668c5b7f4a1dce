#include "deb/budget/response_traces.h"
#include "deb/report/budget/path_plots.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/budget/engine.h"
#include "deb/budget/path_response.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/figure/plot_style.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

// The path plots of a budget with one flat source of `channels` through a
// static gain row `gain` (e.g. "[[0, 2]]") onto one output.
std::vector<Plot> GainPathPlots(const std::string& channels, const std::string& gain) {
  const Budget budget = LoadBudgetText(R"(
name: gain_paths
grid: {type: log, min_hz: 1, max_hz: 100, points: 30}
sources:
  - {name: v, unit: um/s, channels: )" + channels + R"(, spectrum: {type: flat, level: 1}}
paths:
  - {name: g, type: gain, gain: )" + gain + R"(, input_unit: um/s, output_unit: um/s, outputs: [y]}
contributors:
  - {name: c, source: v, path: g}
outputs:
  - {name: out, signal: y, unit: um/s}
)",
                                       "gain_paths.yaml");
  return PathPlots(Evaluate(budget));
}

TEST_CASE("one path plot per contributor and output, whose CSV holds |h| of every source channel") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = PathPlots(result);
  REQUIRE(plots.size() == budget.contributors.size() * budget.outputs.size());
  CHECK(plots[0].name == "path_transmissibility_to_z_velocity");
  CHECK(plots[3].name == "path_sensor_sensitivity_to_z_displacement");
  CHECK(plots[3].figure.panels.at(0).y.label == "magnitude |h| [nm/(µm/s)]");
  const PathResponse r = ComputePathResponse(budget, result, 1, 1, result.grid.f_hz());
  std::istringstream lines(plots[3].csv);
  std::string line;
  std::getline(lines, line);  // comment
  std::getline(lines, line);
  CHECK(line == "frequency_hz,geophone_noise,geophone_noise phase_deg");
  std::getline(lines, line);
  double f, mag;
  REQUIRE(std::sscanf(line.c_str(), "%lf,%lf", &f, &mag) == 2);
  CHECK(f == doctest::Approx(result.grid.f_hz()[0]));
  CHECK(mag == doctest::Approx(std::sqrt(r.gain2[0][0])).epsilon(1e-9));
}

TEST_CASE("a source channel without transfer is named as zero in the key") {
  const std::vector<Plot> plots = GainPathPlots("[x, z]", "[[0, 2]]");
  REQUIRE(plots.size() == 1);
  CHECK(FindSeries(plots[0].figure, "x")->key == "x (zero)");
  CHECK(FindSeries(plots[0].figure, "z")->key == "z");
  // A zero transfer has no phase: the phase panel draws z alone.
  REQUIRE(plots[0].figure.panels.size() == 2);
  REQUIRE(plots[0].figure.panels[1].series.size() == 1);
  CHECK(plots[0].figure.panels[1].series[0].name == "z");
}

TEST_CASE("a path plot reaches half a decade beyond every pole of its path, though the variance lies below it") {
  // The source holds all its variance in 2-5 Hz, so the output's plots show
  // 1-10 Hz; the path has a lightly damped resonance at 200 Hz.
  const Budget budget = LoadBudgetText(R"(
name: hidden_resonance
grid: {type: log, min_hz: 0.1, max_hz: 10000, points: 600}
sources:
  - {name: v, unit: um, spectrum: {type: flat, level: 1, lo_hz: 2, hi_hz: 5}}
paths:
  - {name: mode, type: transfer_function, num: [1579136.7], den: [1, 25.13274, 1579136.7], input_unit: um, output_unit: um, outputs: [y]}
contributors:
  - {name: c, source: v, path: mode}
outputs:
  - {name: out, signal: y, unit: um}
)",
                                       "hidden_resonance.yaml");
  const BudgetResult result = Evaluate(budget);
  const FrequencyRange display = DisplayRange(result.outputs[0], result.grid);
  REQUIRE(display.hi_hz == doctest::Approx(10.0));
  REQUIRE(result.traces->poles_hz[0].has_value());
  const std::pair<double, double> poles = *result.traces->poles_hz[0];
  const FrequencyRange r = PathRange(poles, display, result.grid);
  CHECK(poles.first == doctest::Approx(200.0).epsilon(1e-6));
  CHECK(poles.second == doctest::Approx(200.0).epsilon(1e-6));
  CHECK(r.lo_hz == doctest::Approx(display.lo_hz));
  CHECK(r.hi_hz == doctest::Approx(1000.0));  // 200 Hz x 10^0.5 = 632 Hz, to the decade
  CHECK(r.trimmed);
  const std::vector<Plot> plots = PathPlots(result);
  REQUIRE(plots.size() == 1);
  CHECK(*plots[0].figure.panels[0].x.min == doctest::Approx(1.0));
  CHECK(*plots[0].figure.panels[0].x.max == doctest::Approx(1000.0));
  CHECK(plots[0].script.find("widened to the path''s poles (f_{n} 200 Hz)") != std::string::npos);
  CHECK(plots[0].caption.find("Shown: 1–1000 Hz") != std::string::npos);
  // The CSV holds the resonance: its largest |h| is near 1 / (2 zeta) = 50.
  double peak = 0.0;
  std::istringstream lines(plots[0].csv);
  std::string line;
  std::getline(lines, line);
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    double f, mag;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf", &f, &mag) == 2);
    peak = std::max(peak, mag);
  }
  CHECK(peak > 10.0);

  // Clamped to the grid: a grid ending at 300 Hz ends the plot there.
  const FrequencyGrid short_grid = FrequencyGrid::Log(0.1, 300.0, 400);
  const FrequencyRange clamped = PathRange(poles, FrequencyRange{1.0, 10.0, true}, short_grid);
  CHECK(clamped.hi_hz == doctest::Approx(300.0));
  // A pole outside the grid does not widen it: the traces know no pole there.
  Budget low = budget;
  low.grid = GridSpec();
  low.grid.kind = GridKind::kLog;
  low.grid.auto_options.min_hz = 0.1;
  low.grid.auto_options.max_hz = 100.0;
  low.grid.points = 400;
  const BudgetResult low_result = Evaluate(low);
  REQUIRE(low_result.grid.max_hz() == doctest::Approx(100.0));
  CHECK_FALSE(low_result.traces->poles_hz[0].has_value());
  CHECK(PathRange(low_result.traces->poles_hz[0], FrequencyRange{1.0, 10.0, true}, low_result.grid).hi_hz ==
        doctest::Approx(10.0));
}

TEST_CASE("the avis case study's path plots show its closed-loop poles up to 7.4 Hz, to 100 Hz") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("avis_case_study.yaml"));
  const BudgetResult result = Evaluate(budget);
  REQUIRE(DisplayRange(result.outputs[0], result.grid).hi_hz == doctest::Approx(10.0));
  int found = 0;
  for (const Plot& p : PathPlots(result)) {
    if (p.caption.find("contributor sensor_noise.") == std::string::npos || p.name.find("_to_z_displacement") == std::string::npos) continue;
    ++found;
    CHECK(*p.figure.panels[0].x.min == doctest::Approx(0.01));
    CHECK(*p.figure.panels[0].x.max == doctest::Approx(100.0));
  }
  CHECK(found == 1);
}

TEST_CASE("channels with identical curves are drawn once and named together, in channel styles") {
  const std::vector<Plot> plots = GainPathPlots("[a, b, c]", "[[1, 1, 2]]");
  REQUIRE(plots.size() == 1);
  const std::string& script = plots[0].script;
  CHECK(script.find("title 'a = b'") != std::string::npos);
  CHECK(script.find("title 'b'") == std::string::npos);
  CHECK(script.find("title 'c'") != std::string::npos);
  CHECK(script.find("column(3)") == std::string::npos);  // b is not drawn under a
  CHECK(plots[0].caption.find("named together") != std::string::npos);
  // The channel family, with markers, not the contributor colours.
  CHECK(script.find("'" + ChannelStyle(0).colour + "'") != std::string::npos);
  CHECK(script.find("'" + ChannelStyle(2).colour + "'") != std::string::npos);
  CHECK(script.find("pointtype " + std::to_string(ChannelStyle(2).point_type)) != std::string::npos);
  for (std::size_t i = 0; i < 3; ++i) CHECK(script.find("'" + ContributorStyle(i).colour + "'") == std::string::npos);
  // The CSV still holds every channel.
  CHECK(plots[0].csv.find("frequency_hz,a,b,c,a phase_deg,b phase_deg,c phase_deg\n") != std::string::npos);
}

TEST_CASE("a single-channel path plot keeps its contributor's colour") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const std::vector<Plot> plots = PathPlots(Evaluate(budget));
  const FigureSeries& s = plots[0].figure.panels.at(0).series.at(0);
  CHECK(s.colour == ContributorStyle(0).colour);
  CHECK(s.kind == SeriesKind::kLine);
  CHECK(s.point_type == 0);
}

TEST_CASE("a channel below the magnitude axis is keyed so and gets no phase curve") {
  const std::vector<Plot> plots = GainPathPlots("[x, z]", "[[1e-12, 2]]");
  REQUIRE(plots.size() == 1);
  CHECK(FindSeries(plots[0].figure, "x")->key == "x (below the axis)");
  REQUIRE(plots[0].figure.panels.at(1).series.size() == 1);
  CHECK(plots[0].figure.panels[1].series[0].name == "z");
}

TEST_CASE("a path several contributors share is plotted once per output, with magnitude and unwrapped phase") {
  // A first-order low pass at 10 Hz shared by a and b: the phase of
  // 1/(1 + s/w) is -atan(f / 10 Hz).
  const Budget budget = LoadBudgetText(R"(
name: shared_path
grid: {type: log, min_hz: 0.01, max_hz: 10000, points: 400}
sources:
  - {name: s1, unit: N, spectrum: {type: flat, level: 1}}
  - {name: s2, unit: N, spectrum: {type: flat, level: 4}}
  - {name: s3, unit: N, spectrum: {type: flat, level: 2}}
paths:
  - {name: lowpass, type: transfer_function, num: [62.831853], den: [1, 62.831853], input_unit: N, output_unit: nm, outputs: [y]}
  - {name: third, type: transfer_function, num: [248050.213], den: [1, 188.495559, 11843.5253, 248050.213], input_unit: N, output_unit: nm, outputs: [y]}
contributors:
  - {name: a, source: s1, path: lowpass}
  - {name: b, source: s2, path: lowpass}
  - {name: c, source: s3, path: third}
outputs:
  - {name: out, signal: y, unit: nm}
)",
                                       "shared_path.yaml");
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = PathPlots(result);
  REQUIRE(plots.size() == 2);
  CHECK(plots[0].name == "path_lowpass_to_out");
  CHECK(plots[0].caption.find("used by 2 contributors: a, b.") != std::string::npos);
  CHECK(plots[1].name == "path_third_to_out");
  // The phase column (third) against the closed form -atan(f / 10 Hz), in degrees.
  std::istringstream lines(plots[0].csv);
  std::string line;
  std::getline(lines, line);
  std::getline(lines, line);
  CHECK(line == "frequency_hz,s1,s1 phase_deg");
  int rows = 0;
  while (std::getline(lines, line)) {
    double f, mag, deg;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf", &f, &mag, &deg) == 3);
    CHECK(deg == doctest::Approx(-std::atan(f / 10.0) * 180.0 / 3.14159265358979).epsilon(1e-6));
    CHECK(mag == doctest::Approx(1.0 / std::hypot(1.0, f / 10.0)).epsilon(1e-6));
    ++rows;
  }
  CHECK(rows > 10);
  // Two panels: magnitude (log) over phase (linear) on the same frequencies.
  const PlotFigure& fig = plots[0].figure;
  REQUIRE(fig.panels.size() == 2);
  CHECK(fig.panels[0].y.scale == AxisScale::kLog);
  CHECK(fig.panels[1].y.label == "phase [°]");
  CHECK(*fig.panels[0].x.min == *fig.panels[1].x.min);
  CHECK(fig.panels[1].series.at(0).y_columns == std::vector<std::size_t>{3});
  // Three real poles at 10 Hz: the phase passes -180 deg (where arg wraps)
  // and runs on continuously towards -270, never jumping back by a turn.
  std::istringstream third(plots[1].csv);
  std::getline(third, line);
  std::getline(third, line);
  double last = 0.0, lowest = 0.0;
  bool first = true;
  while (std::getline(third, line)) {
    double f, mag, deg;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf", &f, &mag, &deg) == 3);
    if (!first) CHECK(std::fabs(deg - last) < 90.0);
    first = false;
    last = deg;
    lowest = std::min(lowest, deg);
  }
  CHECK(lowest < -260.0);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("contributors driving different inputs of one path get a plot each, of their own input's transfer") {
  // Path p: input a through 1/(1 + s/w1), input b through 2/(1 + s/w2),
  // w1 = 2 pi 1 Hz, w2 = 2 pi 100 Hz. c1 drives a; c2 and c3 drive b. One
  // plot for all three drew a's transfer under the title "used by c1, c2, c3".
  const Budget budget = LoadBudgetText(R"(
name: two_inputs
grid: {type: log, min_hz: 0.01, max_hz: 10000, points: 300}
sources:
  - {name: s, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - name: p
    type: transfer_function
    matrix: [[{num: [6.283185307179586], den: [1, 6.283185307179586]}, {num: [1256.6370614359172], den: [1, 628.3185307179586]}]]
    inputs: [a, b]
    outputs: [y]
    input_unit: N
    output_unit: nm
contributors:
  - {name: c1, source: s, path: p, inputs: [a]}
  - {name: c2, source: s, path: p, inputs: [b]}
  - {name: c3, source: s, path: p, inputs: [b]}
outputs:
  - {name: out, signal: y, unit: nm}
)",
                                       "two_inputs.yaml");
  const std::vector<Plot> plots = PathPlots(Evaluate(budget));
  REQUIRE(plots.size() == 2);
  CHECK(plots[0].name == "path_p_to_out_from_c1");
  CHECK(plots[1].name == "path_p_to_out_from_c2");
  CHECK(plots[0].figure.title == "path p(a) → out, used by c1");
  CHECK(plots[1].figure.title == "path p(b) → out, used by c2, c3");
  // Each CSV holds its own input's |h|: 1/|1 + j f/1 Hz| and 2/|1 + j f/100 Hz|.
  const double corner[2] = {1.0, 100.0}, gain[2] = {1.0, 2.0};
  for (int k = 0; k < 2; ++k) {
    std::istringstream lines(plots[k].csv);
    std::string line;
    std::getline(lines, line);
    std::getline(lines, line);
    int rows = 0;
    while (std::getline(lines, line)) {
      double f, mag, deg;
      REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf", &f, &mag, &deg) == 3);
      CHECK(mag == doctest::Approx(gain[k] / std::hypot(1.0, f / corner[k])).epsilon(1e-6));
      ++rows;
    }
    CHECK(rows > 10);
  }
}

}  // namespace deb::report
