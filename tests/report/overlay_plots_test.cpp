#include "deb/report/overlay_plots.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "deb/budget/comparison.h"
#include "deb/report/spectrum_plots.h"

#include "deb/io/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("overlay plots give PSD and CPS per shared output, A and B as two data blocks of one CSV") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult a = Evaluate(budget);
  BudgetResult b = a;
  b.outputs.pop_back();  // an output only A has gets no overlay
  const auto plots = OverlayPlots("A", a, "B", b);
  REQUIRE(plots.size() == 2 * b.outputs.size());
  CHECK(plots[0].name == FileStem(b.outputs[0].name) + "_psd_overlay");
  CHECK(plots[1].name == FileStem(b.outputs[0].name) + "_cps_overlay");
  const std::string& csv = plots[1].csv;
  const auto split = csv.find("\n\n\n# B\n");
  REQUIRE(split != std::string::npos);
  // Each block: comment, header, the points of the run's display range (and one either side).
  const FrequencyRange range = DisplayRange(a.outputs[0], a.grid);
  const std::vector<double>& f = a.grid.f_hz();
  const double lo = *(std::lower_bound(f.begin(), f.end(), range.lo_hz * (1 - 1e-12)) - (range.lo_hz > f.front()));
  const double hi = *std::lower_bound(f.begin(), f.end(), range.hi_hz * (1 - 1e-12));
  std::istringstream in(csv.substr(csv.find("# A\n"), split));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::size_t rows_a = 0;
  double first = 0.0, last = 0.0;
  while (std::getline(in, line) && !line.empty()) {
    const double x = std::stod(line.substr(0, line.find(',')));
    if (rows_a++ == 0) first = x;
    last = x;
  }
  CHECK(rows_a > 10);
  CHECK(first >= lo);
  CHECK(last <= hi);
  CHECK(plots[1].script.find("index 0") != std::string::npos);
  CHECK(plots[1].script.find("index 1") != std::string::npos);
  CHECK(plots[1].script.find("dashtype (8,5)") != std::string::npos);
  // CPS on a linear axis from 0 to just above the larger total (or requirement), as in deb run.
  const double y_max = std::max({a.outputs[0].variance, a.outputs[0].rms_max.value_or(0.0) *
                                                             a.outputs[0].rms_max.value_or(0.0)}) * 1.06;
  CHECK(plots[1].script.find("set yrange [0:") != std::string::npos);
  CHECK(plots[1].script.find("logscale y") == std::string::npos);
  const std::size_t at = plots[1].script.find("set yrange [0:") + 14;
  const double shown = std::stod(plots[1].script.substr(at));
  CHECK(shown > 0.0);
  CHECK(std::fmod(std::log10(y_max / shown) + 100.0, 1.0) == doctest::Approx(0.0).epsilon(1e-6));  // y_max / 10^e
  // The requirement, and whether each side meets it.
  CHECK(plots[1].script.find("title 'requirement: " + Short(*a.outputs[0].rms_max) + " (A pass, B pass)'") !=
        std::string::npos);
  // PSD at most kOverlayPsdDecades deep.
  const std::string& psd = plots[0].script;
  const std::size_t r = psd.find("set yrange [");
  REQUIRE(r != std::string::npos);
  const double y0 = std::stod(psd.substr(r + 12)), y1 = std::stod(psd.substr(psd.find(':', r) + 1));
  CHECK(std::log10(y1 / y0) <= kOverlayPsdDecades + 1.0 + 1e-9);
}

TEST_CASE("an overlay leaves out a contributor negligible in both results, and keeps one that appears") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  BudgetResult a = Evaluate(budget);
  a.outputs[0].contributors[1].variance = 1e-9 * a.outputs[0].variance;  // sensor_noise negligible
  REQUIRE(a.outputs[0].contributors[1].variance < kNegligibleShare * a.outputs[0].variance);
  CHECK(OverlayPlots("A", a, "B", a)[0].script.find("sensor\\_noise") == std::string::npos);
  BudgetResult b = a;
  b.outputs[0].contributors[1].variance = 0.5 * b.outputs[0].variance;  // appears in B: both sides drawn
  const std::string script = OverlayPlots("A", a, "B", b)[0].script;
  CHECK(script.find("A: sensor\\_noise") != std::string::npos);
  CHECK(script.find("B: sensor\\_noise") != std::string::npos);
}

}  // namespace deb::report
