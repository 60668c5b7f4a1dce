#include "deb/report/budget/loop_plots.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include "deb/budget/engine.h"
#include "deb/budget/response_traces.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("every evaluated loop gets a Bode, an S/T and a Nyquist figure whose marks are the loop's margins") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = LoopPlots(result);
  std::size_t evaluated = 0;
  for (const LoopResult& r : result.loops) evaluated += r.evaluated && r.margins.channels == 1;
  REQUIRE(evaluated > 0);
  REQUIRE(plots.size() == 3 * evaluated);
  const auto stage = std::find_if(result.loops.begin(), result.loops.end(),
                                  [](const LoopResult& r) { return r.plant == "stage" && r.controller == "controller"; });
  REQUIRE(stage != result.loops.end());
  const auto bode = std::find_if(plots.begin(), plots.end(),
                                 [](const Plot& p) { return p.name == "loop_stage_controller_bode"; });
  REQUIRE(bode != plots.end());
  const LoopMargins& m = stage->margins;
  REQUIRE(m.phase_margin);

  // The CSV: S and T from L itself, the phase unwrapped (no step of a turn).
  std::istringstream lines(bode->csv);
  std::string line;
  std::getline(lines, line);
  std::getline(lines, line);
  CHECK(line == "frequency_hz,abs_L,phase_L_deg,abs_S,abs_T,re_L,im_L");
  double max_s = 0.0, last_phase = 0.0;
  bool first = true;
  while (std::getline(lines, line)) {
    double f, l, ph, s, t, re, im;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &f, &l, &ph, &s, &t, &re, &im) == 7);
    const std::complex<double> L(re, im);
    CHECK(l == doctest::Approx(std::abs(L)).epsilon(1e-8));
    CHECK(s == doctest::Approx(1.0 / std::abs(1.0 + L)).epsilon(1e-8));
    CHECK(t == doctest::Approx(std::abs(L / (1.0 + L))).epsilon(1e-8));
    if (!first) CHECK(std::fabs(ph - last_phase) < 90.0);
    first = false;
    last_phase = ph;
    max_s = std::max(max_s, s);
  }
  // The peak of |S| on the grid is 1 / modulus margin, to the grid's resolution.
  CHECK(max_s == doctest::Approx(1.0 / m.modulus_margin).epsilon(1e-3));

  // The gain crossover marker sits at |L| = 1 at the phase margin's frequency.
  const FigurePanel& top = bode->figure.panels.at(0);
  const auto pm = std::find_if(top.annotations.begin(), top.annotations.end(),
                               [](const FigureAnnotation& a) { return a.kind == AnnotationKind::kMarker; });
  REQUIRE(pm != top.annotations.end());
  CHECK(pm->x0 == doctest::Approx(m.phase_margin->f_hz));
  CHECK(pm->y0 == 1.0);
  CHECK(bode->figure.panels.at(1).y.label == "arg L [°]");

  // The Nyquist plot: unit circle, the modulus margin's circle around -1, equal axes.
  const Plot& ny = *(bode + 2);
  REQUIRE(ny.name == "loop_stage_controller_nyquist");
  const FigurePanel& np = ny.figure.panels.at(0);
  CHECK(np.equal_axes);
  std::vector<const FigureAnnotation*> circles;
  for (const FigureAnnotation& a : np.annotations)
    if (a.kind == AnnotationKind::kCircle) circles.push_back(&a);
  REQUIRE(circles.size() == 2);
  CHECK(circles[0]->x0 == 0.0);
  CHECK(circles[0]->x1 == 1.0);
  CHECK(circles[1]->x0 == -1.0);
  CHECK(circles[1]->x1 == doctest::Approx(m.modulus_margin));
  // Re L against Im L and its mirror image.
  CHECK(np.series.at(0).x_column == 6);
  CHECK(np.series.at(0).y_columns == std::vector<std::size_t>{7});
  CHECK(np.series.at(1).y_divisor == -1.0);
  // -1 is named in the key, not by a label on the unit circle, which always passes through it.
  const auto minus_one = std::find_if(np.annotations.begin(), np.annotations.end(),
                                      [](const FigureAnnotation& a) { return a.kind == AnnotationKind::kMarker; });
  REQUIRE(minus_one != np.annotations.end());
  CHECK(minus_one->x0 == -1.0);
  CHECK(minus_one->label.empty());
  CHECK(minus_one->key == "critical point -1");
}

TEST_CASE("a loop's data keep only the rows its figures need, and every curve between them stays within tolerance") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const std::vector<Plot> plots = LoopPlots(result);
  std::size_t loop = 0;
  while (loop < result.loops.size() && result.loops[loop].plant != "stage") ++loop;
  REQUIRE(loop < result.loops.size());
  const LoopTrace& trace = result.traces->loops.at(loop);
  const auto bode = std::find_if(plots.begin(), plots.end(),
                                 [](const Plot& p) { return p.name == "loop_stage_controller_bode"; });
  REQUIRE(bode != plots.end());
  // The three figures of the loop draw the same rows.
  CHECK((bode + 1)->csv == bode->csv);
  CHECK((bode + 2)->csv == bode->csv);

  std::vector<double> f;
  std::vector<std::complex<double>> l;
  std::istringstream lines(bode->csv);
  std::string line;
  std::getline(lines, line);
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    double fk, m, ph, s, t, re, im;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &fk, &m, &ph, &s, &t, &re, &im) == 7);
    f.push_back(fk);
    l.emplace_back(re, im);
  }
  // The full trace has 13 815 frequencies; the figures need a few hundred.
  REQUIRE(trace.f_hz.size() > 10000);
  CHECK(f.size() < trace.f_hz.size() / 20);
  CHECK(f.front() == trace.f_hz.front());
  CHECK(f.back() == trace.f_hz.back());

  // At every frequency of the trace, the curves as drawn (straight between
  // the kept rows over log f) are within the stated tolerance of the trace:
  // |L|, |S|, |T| to 0.002 decade; L within the Nyquist window to 0.2 % of
  // the window's clamp (9 units), with 1e-6 for the CSV's rounding.
  double worst_decades = 0.0, worst_nyquist = 0.0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < trace.f_hz.size(); ++i) {
    const double fi = trace.f_hz[i];
    while (k + 2 < f.size() && f[k + 1] < fi) ++k;
    const double w = std::log(fi / f[k]) / std::log(f[k + 1] / f[k]);
    const std::complex<double> L = trace.loop_gain[i];
    const auto drawn_log = [&](const auto& of) {
      return std::log10(of(l[k])) + w * (std::log10(of(l[k + 1])) - std::log10(of(l[k])));
    };
    const auto mag = [](std::complex<double> z) { return std::abs(z); };
    const auto sens = [](std::complex<double> z) { return 1.0 / std::abs(1.0 + z); };
    const auto comp = [](std::complex<double> z) { return std::abs(z / (1.0 + z)); };
    worst_decades = std::max({worst_decades, std::fabs(drawn_log(mag) - std::log10(mag(L))),
                              std::fabs(drawn_log(sens) - std::log10(sens(L))),
                              std::fabs(drawn_log(comp) - std::log10(comp(L)))});
    if (L.real() > -3.0 && L.real() < 1.5 && std::fabs(L.imag()) < 2.25) {
      const std::complex<double> drawn = l[k] + w * (l[k + 1] - l[k]);
      worst_nyquist = std::max({worst_nyquist, std::fabs(drawn.real() - L.real()), std::fabs(drawn.imag() - L.imag())});
    }
  }
  CHECK(worst_decades < 2e-3 + 1e-6);
  CHECK(worst_nyquist < 2e-3 * 9.0 + 1e-6);
  MESSAGE("loop rows " << f.size() << " of " << trace.f_hz.size() << "; worst " << worst_decades
                       << " decade, " << worst_nyquist << " in the Nyquist window");
}

}  // namespace deb::report
