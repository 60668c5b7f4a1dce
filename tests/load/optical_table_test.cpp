// budgets/optical_table.yaml, written from parameters and blocks, against an
// independent computation, and the lumped_masses path type's errors.
//
// The reference: an engineer's own budget of this table (a hand-derived
// state space, the PID expanded by hand) evaluated by deb and checked with
// numpy on 2 million log points (H from A, B, C and the PID, the loop closed
// by hand), which agreed to the 4 digits printed: 0.9683 nm RMS in total,
// acoustic 0.872, ripple 0.347, amplifier 0.187, capacitive sensor 0.112,
// floor 0.0968; 0.6976 nm in 1-100 Hz; phase margin 48 degrees at 215 Hz.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "deb/budget/engine.h"
#include "deb/budget/path_analysis.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contains.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using test::Contains;

const std::string kFile = std::string(DEB_SOURCE_DIR) + "/budgets/optical_table.yaml";

std::string Text() {
  std::ifstream in(kFile);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

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
  for (const auto& [name, rms] : contributors) {
    bool found = false;
    for (const ContributorResult& c : gap.contributors)
      if (c.name == name) {
        found = true;
        CheckPrinted(std::sqrt(c.variance), rms, 3);
      }
    CHECK_MESSAGE(found, name);
  }
  REQUIRE(gap.band_requirements.size() == 1);
  CheckPrinted(gap.band_requirements[0].rms(), 0.6976, 4);
  REQUIRE(r.loops.size() == 2);  // one loop, closed as S and as T
  for (const LoopResult& loop : r.loops) {
    REQUIRE(loop.margins.phase_margin);
    CheckPrinted(loop.margins.phase_margin->phase_margin_deg, 48.0, 2);
    CheckPrinted(loop.margins.phase_margin->f_hz, 215.0, 3);
  }
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

TEST_CASE("lumped_masses: each broken rule is refused at its key") {
  const std::string text = Text();
  const auto error = [](const std::string& t) { return test::InputErrorOf([&] { LoadBudgetText(t, "b.yaml"); }); };
  struct Case {
    const char* from;
    const char* to;
    const char* says;
  };
  const Case cases[] = {
      {"between: [head, table]", "between: [head, tabel]",
       "paths[0].couplings[1].between[1]: no mass 'tabel' (did you mean 'table'?) (the masses: table, head, ground)"},
      {"between: [head, table]", "between: [head, head]", "between: the same mass twice"},
      {"between: [head, table]", "between: head", "between: name both ends, [a, b] (one may be ground)"},
      {"masses: {table: m_table, head: m_head}", "masses: {table: m_table, head: 0 kg}",
       "paths[0].masses.head: value 0 kg must be > 0"},
      {"masses: {table: m_table, head: m_head}", "masses: {table: m_table, ground: m_head}",
       "'ground' is the moving reference, not a mass"},
      {"k: k_flex, c: c_flex", "k: k_flex, c: m_head", "paths[0].couplings[1].c: 'm_head' is a quantity in kg; this value is in N.s/m"},
      {"k: k_flex, c: c_flex", "k: 0, c: 0", "a coupling needs k (N/m), c (N s/m) or both"},
      {"{name: F_ac, force: head}", "{name: F_ac, force: head, ground: acceleration}",
       "give 'force: mass' (or [mass, reaction]) or 'ground: acceleration'"},
      {"{name: F_ac, force: head}", "{name: F_ac, force: ground}", "'ground' cannot be named here: name a mass"},
      {"{name: floor_acc, ground: acceleration}", "{name: floor_acc, ground: velocity}",
       "the ground moves by its acceleration"},
      {"{name: F_ac, force: head}", "{name: F_act, force: head}", "paths[0].inputs[2].name: name 'F_act' is used twice"},
      {"input_units: [m/s^2, N, N]", "input_units: [m/s^2, N, m]", "input 'F_act' is in N: 'm' is not the same quantity"},
      {"output_unit: m\n  - name: pid", "output_unit: N\n  - name: pid", "output 'gap' is in m: 'N' is not the same quantity"},
      {"{name: gap, displacement: [head, table]}", "{name: gap, displacement: [head, table], velocity: head}",
       "give 'displacement: mass' or 'velocity: mass'"},
  };
  for (const Case& c : cases) {
    const std::string message = error(test::Replace(text, c.from, c.to));
    CHECK_MESSAGE(Contains(message, c.says), std::string(c.to) << "\n  gave: " << message);
    CHECK_MESSAGE(Contains(message, "b.yaml:"), message);
  }
}

}  // namespace deb
