// budgets/optical_table.yaml, written from parameters and blocks, against an
// independent computation.
//
// The reference: an engineer's own budget of this table (a hand-derived
// state space, the PID expanded by hand) evaluated by deb and checked with
// numpy on 2 million log points (H from A, B, C and the PID, the loop closed
// by hand), which agreed to the 4 digits printed: 0.9683 nm RMS in total,
// acoustic 0.872, ripple 0.347, amplifier 0.187, capacitive sensor 0.112,
// floor 0.0968; 0.6976 nm in 1-100 Hz; phase margin 48 degrees at 215 Hz.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/budget/path_analysis.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contributor_of.h"

namespace deb {
namespace {

const std::string kFile = std::string(DEB_SOURCE_DIR) + "/budgets/optical_table.yaml";

// Agrees with a figure printed to `digits` significant digits.
void CheckPrinted(double value, double printed, int digits) {
  const double half_unit = 0.5 * std::pow(10.0, std::floor(std::log10(printed)) - (digits - 1));
  CHECK_MESSAGE(std::abs(value - printed) <= half_unit, value << " vs the reference's " << printed);
}

}  // namespace

TEST_CASE("the two-mass optical table from blocks gives the independent computation's figures, to its 4 digits") {
  const BudgetResult r = Evaluate(LoadBudgetFile(kFile));
  REQUIRE(r.outputs.size() == 1);
  const OutputResult& gap = r.outputs[0];
  CheckPrinted(gap.rms(), 0.9683, 4);
  const std::pair<const char*, double> contributors[] = {
      {"acoustic", 0.872}, {"ripple", 0.347}, {"amplifier", 0.187}, {"cap_sensor", 0.112}, {"floor", 0.0968}};
  for (const auto& expected : contributors)
    CheckPrinted(std::sqrt(test::ContributorOf(gap, expected.first).variance), expected.second, 3);
  REQUIRE(gap.band_requirements.size() == 1);
  CheckPrinted(gap.band_requirements[0].rms(), 0.6976, 4);
  // One physical loop, closed as S (unity by loop_gain) and as T (loop_gain by unity): analysed once.
  REQUIRE(r.loops.size() == 1);
  const LoopResult& loop = r.loops[0];
  REQUIRE(loop.same_loop.size() == 1);
  CHECK(loop.plant != loop.same_loop[0].plant);
  REQUIRE(loop.margins.phase_margin);
  CheckPrinted(loop.margins.phase_margin->phase_margin_deg, 48.0, 2);
  CheckPrinted(loop.margins.phase_margin->f_hz, 215.0, 3);
}

TEST_CASE("the closed loop's responses to the two forces: the independent computation's figures at 1 and 100 Hz") {
  // The same walk-through: |F_ac -> gap| 5.49 and |F_act -> gap| 4.98 nm/N at
  // 1 Hz, 64.8 and 68.0 nm/N at 100 Hz.
  const Budget b = LoadBudgetFile(kFile);
  const PathAnalysis closed(b.FindPath("closed"), {0});
  double h[2][3] = {};
  const std::vector<double> f = {1.0, 100.0};
  closed.ForEachResponse(f, [&](std::size_t k, const Eigen::MatrixXcd& r) {
    for (int j = 0; j < 3; ++j) h[k][j] = std::abs(r(0, j)) * 1e9;  // m/N -> nm/N (the path is in m)
  });
  CheckPrinted(h[0][1], 5.49, 3);
  CheckPrinted(h[0][2], 4.98, 3);
  CheckPrinted(h[1][1], 64.8, 3);
  CheckPrinted(h[1][2], 68.0, 3);
}

}  // namespace deb
