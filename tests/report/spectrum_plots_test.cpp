#include "deb/report/spectrum_plots.h"

#include <doctest/doctest.h>

#include <regex>

#include "deb/io/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("the RMS axis puts each label r at the variance r squared, thinned near zero") {
  // Variance axis up to 420 (RMS 20.5): step 5 -> labels 0, 5, 10, 15, 20 at 0, 25, 100, 225, 400.
  CHECK(RmsTics(420.0) == "set y2tics nomirror ('0' 0, '5' 25, '10' 100, '15' 225, '20' 400)");
  // In units of 10^6: labels at r^2 / 1e6.
  CHECK(RmsTics(4.2e6, 1e6).find("'2000' 4") != std::string::npos);
  // Up to 1e4 (RMS 100): 20 sits at 400 = 4 % of the axis and stays; a finer step would crowd.
  const std::string tics = RmsTics(1e4);
  CHECK(tics.find("'20' 400") != std::string::npos);
  CHECK(tics.find("'100' 10000") != std::string::npos);
  // The total gets its own tic; regular ones too close to it give way.
  CHECK(RmsTics(420.0, 1.0, {{14.03, "14.0"}}) == "set y2tics nomirror ('0' 0, '5' 25, '10' 100, '14.0' 196.8409, '15' 225, '20' 400)");
  CHECK(RmsTics(420.0, 1.0, {{19.9, "19.9"}}).find("'20' 400") == std::string::npos);
  // Total and requirement both marked; a requirement crowding the total gives way.
  CHECK(RmsTics(420.0, 1.0, {{14.03, "14.0"}, {20, "20"}}).find("'14.0' 196.8409, '15' 225, '20' 400") != std::string::npos);
  CHECK(RmsTics(420.0, 1.0, {{14.03, "14.0"}, {14.2, "14.2"}}).find("14.2") == std::string::npos);
}

TEST_CASE("the display range holds all but a thousandth of every contributor's variance, in whole decades") {
  const FrequencyGrid grid = FrequencyGrid::Log(1e-4, 1e8, 1201);
  OutputResult o;
  ContributorResult c;
  // A white PSD on 3..70 Hz: the CPS rises linearly between the band edges.
  for (double f : grid.f_hz()) c.psd.push_back(f >= 3 && f <= 70 ? 1.0 : 0.0);
  double sum = 0.0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (k) sum += 0.5 * (c.psd[k] + c.psd[k - 1]) * (grid.f_hz()[k] - grid.f_hz()[k - 1]);
    c.cps.push_back(sum);
  }
  c.variance = sum;
  o.contributors.push_back(c);
  const FrequencyRange r = DisplayRange(o, grid);
  CHECK(r.trimmed);
  CHECK(r.lo_hz == doctest::Approx(1.0));
  CHECK(r.hi_hz == doctest::Approx(100.0));
  CHECK(RangeCaption(r) == " Shown: 1–100 Hz; the CSV covers the whole grid.");
  // The note is a second line of the x label, so gnuplot makes room for it
  // below the tic labels instead of printing it over the frame (a label at screen coordinates).
  const std::string axis = FrequencyAxis(r, grid);
  CHECK(axis.find("set xlabel ('frequency [Hz]'.\"\\n\".'{/*0.8 grid: 10^{-4} to 10^{8} Hz; shown: the decades holding "
                  "all but 10^{-3} of every contributor''s variance}')") != std::string::npos);
  CHECK(axis.find("at screen") == std::string::npos);
  CHECK(FrequencyAxis(r, grid, "what is shown").find("shown: what is shown}") != std::string::npos);
  // A contributor spread over the whole grid keeps the whole grid.
  ContributorResult flat;
  flat.cps = {0.0};
  for (std::size_t k = 1; k < grid.size(); ++k) flat.cps.push_back(static_cast<double>(k));
  flat.variance = flat.cps.back();
  o.contributors.push_back(flat);
  CHECK_FALSE(DisplayRange(o, grid).trimmed);
  CHECK(RangeCaption(DisplayRange(o, grid)).empty());
  CHECK(FrequencyAxis(DisplayRange(o, grid), grid).find("set xlabel 'frequency [Hz]'\n") != std::string::npos);
}

TEST_CASE("share order sorts contributors by variance, largest first, ties in budget order") {
  OutputResult o;
  for (double v : {1.0, 5.0, 1.0, 3.0}) {
    ContributorResult c;
    c.variance = v;
    o.contributors.push_back(c);
  }
  CHECK(ShareOrder(o) == std::vector<std::size_t>{1, 3, 0, 2});
}

TEST_CASE("the stacked CPS plot reads its own CSV, whose top layer sums to the total CPS") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  ReportOptions options;
  options.reverse_cps = true;
  const std::vector<Plot> plots = SpectrumPlots(result, 0, options);
  REQUIRE(plots.size() == 3);
  CHECK(plots[0].name == "z_velocity_cps");
  CHECK(plots[1].name == "z_velocity_reverse_cps");
  CHECK(plots[2].name == "z_velocity_psd");
  for (const Plot& p : plots) CHECK(p.script.find("'" + p.name + ".csv'") != std::string::npos);
  // The last data row of the CPS CSV: contributors add up to the total.
  const std::string& csv = plots[0].csv;
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  double f, a, b, total;
  REQUIRE(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf", &f, &a, &b, &total) == 4);
  CHECK(a + b == doctest::Approx(total).epsilon(1e-9));
  CHECK(total == doctest::Approx(result.outputs[0].variance).epsilon(1e-9));
  // The requirement is drawn at rms_max^2 = 400 and the key says it passes.
  CHECK(plots[0].script.find("400 with lines") != std::string::npos);
  CHECK(plots[0].script.find("requirement: 20 (pass)") != std::string::npos);
  // The reverse CPS starts at the total variance.
  const std::string& rev = plots[1].csv;
  const std::size_t first_row = rev.find('\n', rev.find('\n') + 1) + 1;
  REQUIRE(std::sscanf(rev.c_str() + first_row, "%lf,%lf,%lf,%lf", &f, &a, &b, &total) == 4);
  CHECK(total == doctest::Approx(result.outputs[0].variance).epsilon(1e-9));
}

TEST_CASE("the variance axis of a large output is scaled by a power of ten named in its label") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = SpectrumPlots(result, 1, {});  // z_displacement, variance ~ 2.6e6 nm^2
  CHECK(plots[0].script.find("[10^{6} nm^{2}]") != std::string::npos);
  CHECK(plots[0].script.find("/1000000)") != std::string::npos);
}

}  // namespace deb::report
