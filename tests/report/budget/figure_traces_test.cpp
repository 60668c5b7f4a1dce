// deb/report/budget/figure_traces.h: a report keeps each path response at
// the frequencies that draw it as the whole grid would. Checked against the
// engine's full traces: between the kept frequencies, straight lines over
// log f through the kept values stay within the stated tolerance of every
// grid value (|h|^2 in decades, the phase in radians); far fewer points are
// kept; a reduced response is kept as it is.
#include "deb/report/budget/figure_traces.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "deb/budget/engine.h"
#include "deb/budget/response_traces.h"
#include "deb/load/budget_yaml.h"
#include "deb/core/math_constants.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("a report's path responses keep few frequencies and draw every grid value to the tolerance") {
  const BudgetResult full = Evaluate(LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml")));
  const BudgetResult kept = WithFigureTraces(full);
  const std::vector<double>& f = full.grid.f_hz();
  std::size_t before = 0, after = 0;
  double worst_decades = 0.0, worst_rad = 0.0;
  REQUIRE(kept.traces->paths.size() == full.traces->paths.size());
  for (std::size_t c = 0; c < full.traces->paths.size(); ++c)
    for (std::size_t o = 0; o < full.traces->paths[c].size(); ++o) {
      const PathResponse& a = full.traces->paths[c][o];
      const PathResponse& b = kept.traces->paths[c][o];
      REQUIRE(a.f_hz.empty());
      REQUIRE(b.f_hz.size() >= 2);
      CHECK(b.f_hz.front() == f.front());
      CHECK(b.f_hz.back() == f.back());
      CHECK(b.channels == a.channels);
      before += f.size();
      after += b.f_hz.size();
      for (std::size_t k = 0; k < a.gain2.size(); ++k) {
        std::size_t j = 0;
        for (std::size_t i = 0; i < f.size(); ++i) {
          while (j + 2 < b.f_hz.size() && b.f_hz[j + 1] < f[i]) ++j;
          const double w = std::log(f[i] / b.f_hz[j]) / std::log(b.f_hz[j + 1] / b.f_hz[j]);
          if (a.gain2[k][i] > 0.0 && b.gain2[k][j] > 0.0 && b.gain2[k][j + 1] > 0.0) {
            const double drawn = std::log10(b.gain2[k][j]) + w * (std::log10(b.gain2[k][j + 1]) - std::log10(b.gain2[k][j]));
            worst_decades = std::max(worst_decades, std::fabs(drawn - std::log10(a.gain2[k][i])));
          }
          const double phase = b.phase_rad[k][j] + w * (b.phase_rad[k][j + 1] - b.phase_rad[k][j]);
          worst_rad = std::max(worst_rad, std::fabs(phase - a.phase_rad[k][i]));
        }
      }
    }
  MESSAGE("kept " << after << " of " << before << " frequencies; worst " << worst_decades << " decade in |h|^2, "
                  << worst_rad << " rad in phase");
  CHECK(after * 4 < before);
  CHECK(worst_decades <= kTraceTolerance * (1 + 1e-9));
  CHECK(worst_rad <= kTraceTolerance * kPi * (1 + 1e-9));

  // Reduced once, kept as it is: a store's result redraws the same report.
  const BudgetResult again = WithFigureTraces(kept);
  for (std::size_t c = 0; c < kept.traces->paths.size(); ++c)
    for (std::size_t o = 0; o < kept.traces->paths[c].size(); ++o) {
      CHECK(again.traces->paths[c][o].f_hz == kept.traces->paths[c][o].f_hz);
      CHECK(again.traces->paths[c][o].gain2 == kept.traces->paths[c][o].gain2);
    }
  // The engine's result is left as it was.
  CHECK(full.traces->paths[0][0].f_hz.empty());
}

}  // namespace deb::report
