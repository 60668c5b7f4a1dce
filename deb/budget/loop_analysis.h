// The feedback loops of a budget's paths, analysed as a control engineer
// reads them: the stability margins of every distinct loop (a plant closed
// by a controller with a sign), over the budget's frequency grid. A loop
// that several paths share is analysed once and lists every path that holds
// it: the same plant, controller and sign, or one physical loop built in
// several ways (S, PS and T of one plant and controller: G closed by K, and
// G K closed by 1 or 1 by G K, have the same loop gain L).
#pragma once

#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/systems/loop_margins.h"

namespace deb {

// The modulus margin below which a loop is reported as poorly damped: the
// usual rule |S| <= 2 (6 dB), i.e. the Nyquist curve keeps 0.5 from -1.
inline constexpr double kLowModulusMargin = 0.5;

// A delay or sampled block inside a loop, and how far its rational
// approximation (which gives the loop's poles and exact variances; the
// margins use the exact block) is off at the loop's crossover: the
// phase-margin crossover of a one-channel loop, else the modulus margin's
// frequency.
struct LoopApproximation {
  std::string block;          // IrrationalBlock::Describe()
  std::string approximation;  // IrrationalBlock::DescribeApproximation()
  double f_hz = 0.0;
  double phase_error_deg = 0.0;  // arg(approximation / exact)
  double gain_ratio = 1.0;       // |approximation / exact|
};

// A plant closed by a controller with a sign.
struct LoopForm {
  std::string plant, controller;
  int sign = -1;
};

struct LoopResult {
  std::string plant, controller;
  int sign = -1;
  std::vector<std::string> paths;  // the contributors' paths that close it, in budget order
  // The other forms of this physical loop among the paths: one-channel loops
  // whose loop gain equals this one's at every grid frequency (within 1e-9
  // relative), analysed and drawn once, as this one.
  std::vector<LoopForm> same_loop;
  bool evaluated = false;          // false: `note` says why no margins were computed
  std::string note;
  LoopMargins margins;
  std::vector<LoopApproximation> approximations;  // evaluated loops only
  MarginRequirement required;  // of the first path that gives one
};

// One required margin of a loop against the loop's: `actual` is +inf where
// the loop has no such crossover (no gain crossover: no phase margin to
// lose), NaN where it was not evaluated (which fails).
struct MarginCheck {
  std::string what;  // "gain margin", "phase margin", "modulus margin"
  std::string unit;  // "dB", "deg", ""
  double required = 0.0, actual = 0.0;
  bool pass() const { return actual >= required; }
  // required / actual: <= 1 where it passes (0 for an infinite margin).
  double ratio() const;
};
std::vector<MarginCheck> MarginChecks(const LoopResult& loop);
// "phase margin 38.2 deg >= 30 deg: PASS; modulus margin 0.41 >= 0.5: FAIL";
// "" when the loop requires none.
std::string MarginChecksText(const LoopResult& loop);

// Every distinct loop of the paths that contributors use (one-channel loops
// with the same loop gain merged into the first), with its margins
// over the frequencies f_hz (ascending) that lie where the loop's measured
// data may be evaluated. A loop that cannot be evaluated there (a pole on
// the grid, fewer than 2 frequencies in range) is kept with a note.
std::vector<LoopResult> AnalyseLoops(const Budget& budget, const std::vector<double>& f_hz);

// The loop's margins in one line, 4 significant digits, e.g. "phase margin
// 45.2 deg at 80.1 Hz, gain margin 3.21 (10.13 dB) at 240 Hz, modulus margin
// 0.62 at 150 Hz"; a lower gain margin and missing crossovers are said as
// such; the note if it was not evaluated. Each approximation follows, e.g.
// "; a delay of 100 us by Pade (6, 6): phase error -1.2e-09 deg at 80.1 Hz".
std::string MarginsText(const LoopResult& loop);

// "loop_gain closed by unity, unity closed by loop_gain": the loop's other
// forms; "" when it has none.
std::string SameLoopText(const LoopResult& loop);

}  // namespace deb
