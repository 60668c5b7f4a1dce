#include "deb/budget/loop_analysis.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/budget/engine.h"
#include "deb/budget/path_composition.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

Path Siso(const std::string& name, const TransferFunction& tf, const std::string& in, const std::string& out) {
  Path p;
  p.name = name;
  p.system = ToStateSpace(tf);
  p.input_names = {name + "_in"};
  p.output_names = {name + "_out"};
  p.input_units = {in};
  p.output_units = {out};
  return p;
}

// A 5 kg rigid stage P = 1/(m s^2) (N -> um) under a lead K = kp (1 + s/wz)/(1 + s/wp)
// (nm -> N) with wz = wc/3, wp = 3 wc and kp = m wc^2 / 3 (in N/m): |P K| = 1 exactly at wc, where the
// lead gives its largest phase, asin((9 - 1)/(9 + 1)) = asin 0.8; PM = asin 0.8 = 53.130 deg.
struct LeadLoop {
  double m = 5.0, wc = kTwoPi * 30.0;
  Path plant = Siso("stage", TransferFunction({1e6}, {m, 0.0, 0.0}), "N", "um");  // 1e6 um/m
  Path controller = Siso("lead", TransferFunction({m * wc * wc / 3.0 * 1e-9 * 3.0 / wc, m * wc * wc / 3.0 * 1e-9},
                                                  {1.0 / (3.0 * wc), 1.0}),
                         "nm", "N");  // kp in N/nm
};

Budget LoopBudget(const std::vector<Path>& paths) {
  Budget b;
  b.name = "loops";
  auto s = Source{};
  s.name = "force";
  s.unit = "N";
  s.spectrum = std::make_shared<FlatSpectrum>(1e-8);
  s.channel_names = {"f"};
  b.sources = {s};
  b.paths = paths;
  for (const Path& p : paths) b.contributors.push_back({"c_" + p.name, "force", p.name, ExactVariance::kOff, {}, {}, false});
  Output o;
  o.name = "x";
  o.signal = paths.front().output_names.front();
  o.unit = "um";
  b.outputs = {o};
  return b;
}

std::vector<double> LogGrid(double f_lo, double f_hi, int n) {
  std::vector<double> f(n);
  for (int k = 0; k < n; ++k) f[k] = f_lo * std::pow(f_hi / f_lo, static_cast<double>(k) / (n - 1));
  return f;
}

TEST_CASE("a feedback path keeps its loop: a lead on a rigid stage has PM = asin 0.8 at the designed 30 Hz") {
  // Closed form above; tolerance 1e-9 (bisection to 1e-13 in log f). The unit
  // scale nm -> um (1e3) at the junction is part of the loop gain: a wrong
  // scale would move the crossover by sqrt(1000).
  const LeadLoop d;
  Path closed = FeedbackOfPaths({&d.plant, "plant"}, {&d.controller, "controller"});
  closed.name = "closed";
  REQUIRE(closed.loops.size() == 1);
  CHECK(closed.loops[0].plant == "stage");
  CHECK(closed.loops[0].controller == "lead");
  const std::vector<LoopResult> loops = AnalyseLoops(LoopBudget({closed}), LogGrid(0.5, 2000.0, 300));
  REQUIRE(loops.size() == 1);
  REQUIRE(loops[0].evaluated);
  REQUIRE(loops[0].margins.gain_crossovers.size() == 1);
  CHECK(loops[0].margins.gain_crossovers[0].f_hz == doctest::Approx(30.0).epsilon(1e-9));
  REQUIRE(loops[0].margins.phase_margin);
  CHECK(loops[0].margins.phase_margin->phase_margin_deg == doctest::Approx(std::asin(0.8) * 180.0 / M_PI).epsilon(1e-9));
  // The phase stays above -180: no gain margin; at the crossover |1 + L| = 2 sin(PM/2) bounds the modulus margin.
  CHECK_FALSE(loops[0].margins.upper_gain_margin);
  CHECK_FALSE(loops[0].margins.lower_gain_margin);
  CHECK(loops[0].margins.modulus_margin <= 2.0 * std::sin(std::asin(0.8) / 2.0) + 1e-12);
  CHECK(MarginsText(loops[0]).find("phase margin 53.13 deg at 30 Hz") != std::string::npos);
}

TEST_CASE("a loop that several paths hold is analysed once, naming each path; series paths keep their parts' loops") {
  const LeadLoop d;
  Path closed = FeedbackOfPaths({&d.plant, "plant"}, {&d.controller, "controller"});
  closed.name = "closed";
  const Path gain = Siso("sensor", TransferFunction({2.0}, {1.0}), "um", "V");
  Path chain = SeriesOfPaths({{&closed, "of[0]"}, {&gain, "of[1]"}});
  chain.name = "chain";
  REQUIRE(chain.loops.size() == 1);
  const std::vector<LoopResult> loops = AnalyseLoops(LoopBudget({closed, chain}), LogGrid(0.5, 2000.0, 100));
  REQUIRE(loops.size() == 1);
  CHECK(loops[0].paths == std::vector<std::string>{"closed", "chain"});
}

TEST_CASE("one physical loop built as PS, T and S is analysed once, as plant and controller; another loop is not") {
  // P = 1/(m s^2), K the lead above, in SI units. PS = feedback(P, K); with
  // G K = series(K, P): T = feedback(G K, 1) and S = feedback(1, G K). All
  // three have the loop gain L = P K; feedback(P, 2 K) does not.
  const double m = 5.0, wc = kTwoPi * 30.0, kp = m * wc * wc / 3.0;
  const Path stage = Siso("stage", TransferFunction({1.0}, {m, 0.0, 0.0}), "N", "m");
  const Path lead = Siso("lead", TransferFunction({kp * 3.0 / wc, kp}, {1.0 / (3.0 * wc), 1.0}), "m", "N");
  const Path lead2 = Siso("lead2", TransferFunction({2.0 * kp * 3.0 / wc, 2.0 * kp}, {1.0 / (3.0 * wc), 1.0}), "m", "N");
  const Path unity = Siso("unity", TransferFunction({1.0}, {1.0}), "m", "m");
  Path loop_gain = SeriesOfPaths({{&lead, "of[0]"}, {&stage, "of[1]"}});
  loop_gain.name = "loop_gain";
  Path s_path = FeedbackOfPaths({&unity, "plant"}, {&loop_gain, "controller"});
  s_path.name = "S";
  Path t_path = FeedbackOfPaths({&loop_gain, "plant"}, {&unity, "controller"});
  t_path.name = "T";
  Path ps_path = FeedbackOfPaths({&stage, "plant"}, {&lead, "controller"});
  ps_path.name = "PS";
  Path other = FeedbackOfPaths({&stage, "plant"}, {&lead2, "controller"});
  other.name = "stiffer";
  const std::vector<double> f = LogGrid(0.5, 2000.0, 400);
  const std::vector<LoopResult> alone = AnalyseLoops(LoopBudget({ps_path}), f);
  const std::vector<LoopResult> loops = AnalyseLoops(LoopBudget({s_path, t_path, ps_path, other}), f);
  REQUIRE(loops.size() == 2);
  // Reported as the form that names the physical parts, though S came first.
  CHECK(loops[0].plant == "stage");
  CHECK(loops[0].controller == "lead");
  REQUIRE(loops[0].same_loop.size() == 2);
  CHECK(loops[0].same_loop[0].plant == "unity");
  CHECK(loops[0].same_loop[1].plant == "loop_gain");
  CHECK(loops[0].paths == std::vector<std::string>{"S", "T", "PS"});
  CHECK(SameLoopText(loops[0]) == "unity closed by loop_gain, loop_gain closed by unity");
  // Its margins are those of the loop analysed alone.
  REQUIRE(alone.size() == 1);
  REQUIRE(loops[0].margins.phase_margin);
  CHECK(loops[0].margins.phase_margin->phase_margin_deg ==
        doctest::Approx(alone[0].margins.phase_margin->phase_margin_deg).epsilon(1e-12));
  CHECK(loops[1].controller == "lead2");
  CHECK(loops[1].same_loop.empty());
  CHECK(loops[1].paths == std::vector<std::string>{"stiffer"});
}

TEST_CASE("Evaluate reports the loops and warns below a modulus margin of 0.5") {
  // The same loop with the controller gain 20x lower: crossover near
  // 30/sqrt(20)... the phase of the lead is small there, PM small, |1 + L| < 0.5.
  LeadLoop d;
  d.controller.system = ToStateSpace(TransferFunction(
      {d.m * d.wc * d.wc / 3.0 * 1e-9 * 3.0 / d.wc / 20.0, d.m * d.wc * d.wc / 3.0 * 1e-9 / 20.0},
      {1.0 / (3.0 * d.wc), 1.0}));
  Path closed = FeedbackOfPaths({&d.plant, "plant"}, {&d.controller, "controller"});
  closed.name = "closed";
  Budget b = LoopBudget({closed});
  b.grid.kind = GridKind::kAuto;
  b.grid.range_given = true;
  b.grid.auto_options.min_hz = 0.5;
  b.grid.auto_options.max_hz = 2000.0;
  const BudgetResult r = Evaluate(b);
  REQUIRE(r.loops.size() == 1);
  REQUIRE(r.loops[0].evaluated);
  CHECK(r.loops[0].margins.modulus_margin < kLowModulusMargin);
  bool warned = false;
  for (const std::string& w : r.warnings) warned |= w.find("modulus margin") != std::string::npos;
  CHECK(warned);
}

}  // namespace
}  // namespace deb
