// Design optimisation (deb/optimise/optimiser.h) of budgets loaded from YAML
// (deb/load/optimise_yaml.h), against closed forms: two flat force sources
// of levels a and b through the gains kv and 1/kv give the variance
// (a kv^2 + b / kv^2) (f_max - f_min), least at kv* = (b/a)^(1/4) = 2 here;
// a requirement on a second output w that reads a through kv alone (RMS
// proportional to kv) that allows kv <= 1.5 moves the optimum onto it, an active
// constraint; one that allows kv <= 0.25, below the bound 0.5, leaves no
// feasible design, and the least violating is the bound. Every rule of the
// bounds and of --vary as an error.
#include <doctest/doctest.h>

#include <cctype>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <vector>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/optimise_yaml.h"
#include "deb/results/optimise_files.h"
#include "tests/support/budget_errors.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

// Each test's files, removed when it ends.
class Dir : public test::ScratchDir {
 public:
  Dir() : ScratchDir("optimise") {}
};

const std::string kBudget = R"(name: opt
parameters:
  kv: {value: 5, min: 0.5, max: 10}
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - {name: a, unit: N, spectrum: {type: flat, level: 1.0e-6}}
  - {name: b, unit: N, spectrum: {type: flat, level: 16.0e-6}}
paths:
  - {name: pa, type: gain, gain: [[kv], [kv]], outputs: [y, w], input_unit: N, output_unit: um}
  - {name: pb, type: gain, gain: [[1/kv], [0]], outputs: [y, w], input_unit: N, output_unit: um}
contributors:
  - {name: ca, source: a, path: pa}
  - {name: cb, source: b, path: pb}
outputs:
  - {name: z, signal: y, unit: um}
  - {name: w, signal: w, unit: um}
)";

// w's RMS is kv sqrt(1e-6 * 99) um.
std::string WithLimit(double kv_max) {
  char limit[64];
  std::snprintf(limit, sizeof limit, "%.17g", kv_max * std::sqrt(99e-6));
  return test::Replace(kBudget, "{name: w, signal: w, unit: um}",
                       "{name: w, signal: w, unit: um, rms_max: " + std::string(limit) + "}");
}

OptimiseResult Optimise(const std::string& file, OptimiseMethod method, int starts = 1, int threads = 0) {
  const OptimiseBudget b = LoadOptimiseFile(file, {"kv"});
  OptimiseObjective objective;
  objective.terms = {{"z", 1.0}};
  OptimiseOptions o;
  o.method = method;
  o.starts = starts;
  o.threads = threads;
  return RunOptimise(b.variables, objective, o, b.loader);
}

TEST_CASE("a kv^2 + b / kv^2: kv* = (b/a)^(1/4) = 2 to 1e-6 by every method") {
  const Dir dir;
  const std::string file = dir.Write("b.yaml", kBudget);
  for (OptimiseMethod m : {OptimiseMethod::kAuto, OptimiseMethod::kCobyla, OptimiseMethod::kBobyqa,
                           OptimiseMethod::kSlsqp, OptimiseMethod::kMma}) {
    CAPTURE(ToString(m));
    const OptimiseResult r = Optimise(file, m);
    REQUIRE(r.feasible);
    // The gains are the paths' D: SLSQP and MMA get exact gradients.
    if (m == OptimiseMethod::kSlsqp || m == OptimiseMethod::kMma)
      CHECK(r.gradients.rfind("exact: ", 0) == 0);
    else if (m != OptimiseMethod::kAuto)
      CHECK(r.gradients == "none (a derivative-free method)");
    const double kv = r.starts[r.best].values[0];
    MESSAGE(ToString(r.method) << ": kv* " << kv << " (relative error " << std::abs(kv - 2.0) / 2.0 << ") in "
                               << r.evaluations << " evaluations");
    CHECK(std::abs(kv - 2.0) <= 1e-6 * 2.0);
    // The least variance: (2 sqrt(a b)) * 99 um^2.
    CHECK(r.starts[r.best].objective == doctest::Approx(std::sqrt(2 * std::sqrt(16e-12) * 99)).epsilon(1e-10));
    CHECK(r.nominal_objective == doctest::Approx(std::sqrt((25e-6 + 16e-6 / 25) * 99)).epsilon(1e-12));
  }
  CHECK(Optimise(file, OptimiseMethod::kAuto).method == OptimiseMethod::kBobyqa);
}

TEST_CASE("a weighted sum RMS(z) + 0.5 RMS(w): the kv where its derivative vanishes, found by bisection") {
  // RMS(z) = sqrt(99e-6 (kv^2 + 16 / kv^2)), RMS(w) = kv sqrt(99e-6): the
  // sum's derivative is proportional to (kv - 16/kv^3) / sqrt(kv^2 + 16/kv^2) + 0.5,
  // negative at 0.5 and positive at 2.
  const auto slope = [](double kv) { return (kv - 16.0 / std::pow(kv, 3)) / std::sqrt(kv * kv + 16.0 / (kv * kv)) + 0.5; };
  double lo = 0.5, hi = 2.0;
  REQUIRE(slope(lo) < 0.0);
  REQUIRE(slope(hi) > 0.0);
  for (int i = 0; i < 200; ++i) (slope(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double kv_star = 0.5 * (lo + hi);
  const auto sum = [](double kv) { return std::sqrt(99e-6 * (kv * kv + 16.0 / (kv * kv))) + 0.5 * kv * std::sqrt(99e-6); };

  const Dir dir;
  const std::string file = dir.Write("b.yaml", kBudget);
  const OptimiseBudget b = LoadOptimiseFile(file, {"kv"});
  const OptimiseObjective objective = b.Objective(" z + 0.5 * w ");
  REQUIRE(objective.terms.size() == 2);
  CHECK(objective.Text() == "the weighted sum RMS(z) + 0.5 RMS(w)");
  for (OptimiseMethod m : {OptimiseMethod::kBobyqa, OptimiseMethod::kSlsqp}) {
    CAPTURE(ToString(m));
    OptimiseOptions o;
    o.method = m;
    const OptimiseResult r = RunOptimise(b.variables, objective, o, b.loader);
    const double kv = r.starts[r.best].values[0];
    MESSAGE(ToString(r.method) << ": kv* " << kv << " against " << kv_star);
    CHECK(std::abs(kv - kv_star) <= 1e-6 * kv_star);
    CHECK(r.starts[r.best].objective == doctest::Approx(sum(kv_star)).epsilon(1e-10));
    CHECK(r.nominal_objective == doctest::Approx(sum(5.0)).epsilon(1e-12));
  }
  // Every rule of the terms, and an output that is not there.
  for (const char* bad : {"z + ", "2*", "-1*z", "0*z", "x*z", "inf*z", "z + z", "z w"}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(b.Objective(bad), doctest::Contains("--objective"), InputError);
  }
  CHECK_THROWS_WITH_AS(RunOptimise(b.variables, b.Objective("z + 2*zz"), {}, b.loader),
                       doctest::Contains("--objective zz: no output of that name"), InputError);
}

TEST_CASE("a requirement that allows kv <= 1.5: the optimum on it, reported active") {
  const Dir dir;
  const std::string file = dir.Write("b.yaml", WithLimit(1.5));
  for (OptimiseMethod m : {OptimiseMethod::kCobyla, OptimiseMethod::kSlsqp, OptimiseMethod::kMma}) {
    CAPTURE(ToString(m));
    const OptimiseResult r = Optimise(file, m);
    REQUIRE(r.feasible);
    // The gains are the paths' D: SLSQP and MMA get exact gradients.
    if (m == OptimiseMethod::kSlsqp || m == OptimiseMethod::kMma)
      CHECK(r.gradients.rfind("exact: ", 0) == 0);
    else if (m != OptimiseMethod::kAuto)
      CHECK(r.gradients == "none (a derivative-free method)");
    const double kv = r.starts[r.best].values[0];
    MESSAGE(ToString(r.method) << ": kv* " << kv << " in " << r.evaluations << " evaluations");
    CHECK(std::abs(kv - 1.5) <= 1e-6 * 1.5);
    REQUIRE(r.requirements.size() == 1);
    CHECK(r.requirements[0].name == "w");
    CHECK(r.requirements[0].active);
  }
  CHECK(Optimise(file, OptimiseMethod::kAuto).method == OptimiseMethod::kSlsqp);
  // Without the requirement binding (kv <= 3 allows the optimum 2), it is not active.
  const OptimiseResult loose = Optimise(dir.Write("b.yaml", WithLimit(3.0)), OptimiseMethod::kCobyla);
  CHECK(std::abs(loose.starts[loose.best].values[0] - 2.0) <= 1e-6 * 2.0);
  CHECK_FALSE(loose.requirements[0].active);
}

TEST_CASE("no feasible design: the least violating, at the bound") {
  const Dir dir;
  const OptimiseResult r = Optimise(dir.Write("b.yaml", WithLimit(0.25)), OptimiseMethod::kCobyla);
  CHECK_FALSE(r.feasible);
  CHECK(r.starts[r.best].values[0] == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(r.starts[r.best].worst_ratio == doctest::Approx(2.0).epsilon(1e-5));
}

TEST_CASE("several starts: the same result and files for 1 and 2 threads") {
  const Dir dir;
  const std::string file = dir.Write("b.yaml", WithLimit(1.5));
  const OptimiseResult one = Optimise(file, OptimiseMethod::kCobyla, 3, 1);
  const OptimiseResult two = Optimise(file, OptimiseMethod::kCobyla, 3, 2);
  REQUIRE(one.starts.size() == 3);
  CHECK(OptimiseSummaryJson("opt", one) == OptimiseSummaryJson("opt", two));
  CHECK(OptimiseHistoryCsv(one) == OptimiseHistoryCsv(two));
  const std::string yaml = OptimumYaml("../b.yaml", "opt", one, {"grid.points=60"});
  CHECK(yaml.find("extends: '../b.yaml'\nname: opt_optimum\ndescription: 'The optimum of deb optimise: kv = 1.5") !=
        std::string::npos);
  CHECK(yaml.find("'\nparameters:\n  kv: 1.5") != std::string::npos);
  CHECK(yaml.find("--set 'grid.points=60'") != std::string::npos);
}

TEST_CASE("starts run elsewhere and sent back as bytes: the same result, bit for bit") {
  // What mpirun does: each start run apart (here in reverse order, one at a
  // time), its outcome sent as bytes and read back, the outcomes in start order.
  const Dir dir;
  const std::string file = dir.Write("b.yaml", WithLimit(1.5));
  const OptimiseResult threads = Optimise(file, OptimiseMethod::kSlsqp, 3);
  const OptimiseBudget b = LoadOptimiseFile(file, {"kv"});
  OptimiseObjective objective;
  objective.terms = {{"z", 1.0}};
  OptimiseOptions o;
  o.method = OptimiseMethod::kSlsqp;
  o.starts = 3;
  std::vector<std::size_t> order;
  const StartRunner apart = [&](std::size_t count, const std::function<StartOutcome(std::size_t)>& run) {
    std::vector<std::string> bytes(count);
    for (std::size_t k = count; k-- > 0;) {
      order.push_back(k);
      bytes[k] = StartOutcomeToBytes(run(k));
    }
    std::vector<StartOutcome> out;
    for (const std::string& x : bytes) out.push_back(StartOutcomeFromBytes(x));
    return out;
  };
  const OptimiseResult sent = RunOptimise(b.variables, objective, o, b.loader, apart);
  CHECK(order == std::vector<std::size_t>{2, 1, 0});
  REQUIRE(sent.starts.size() == 3);
  CHECK(OptimiseSummaryJson("opt", sent) == OptimiseSummaryJson("opt", threads));
  CHECK(OptimiseHistoryCsv(sent) == OptimiseHistoryCsv(threads));
  CHECK(sent.requirements.size() == threads.requirements.size());
  CHECK(sent.requirements[0].active);  // the limit kv <= 1.5 holds the optimum
  // A rank that does not write gets no outcomes back, and no result.
  const StartRunner elsewhere = [](std::size_t, const std::function<StartOutcome(std::size_t)>&) {
    return std::vector<StartOutcome>{};
  };
  CHECK(RunOptimise(b.variables, objective, o, b.loader, elsewhere).starts.empty());
  // Bytes carry an infinite objective (a design that failed) and text exactly.
  StartOutcome failed;
  failed.start.objective = std::numeric_limits<double>::infinity();
  failed.start.stop = "NLopt failed: ''\n";
  failed.history.push_back({2, {0.1, 0.30000000000000004}, std::numeric_limits<double>::infinity(), 1e300, "unstable"});
  const StartOutcome back = StartOutcomeFromBytes(StartOutcomeToBytes(failed));
  CHECK(std::isinf(back.start.objective));
  CHECK(back.start.stop == failed.start.stop);
  REQUIRE(back.history.size() == 1);
  CHECK(back.history[0].values == failed.history[0].values);
  CHECK(back.history[0].error == "unstable");
  CHECK(back.history[0].start == 2);
}

TEST_CASE("the optimum.yaml loads as a budget with the optimum's values") {
  const Dir dir;
  const std::string file = dir.Write("b.yaml", kBudget);
  const OptimiseResult r = Optimise(file, OptimiseMethod::kBobyqa);
  const std::string optimum = dir.Write("out/optimum.yaml", OptimumYaml("../b.yaml", "opt", r, {}));
  const Budget b = LoadBudgetFile(optimum);
  CHECK(b.name == "opt_optimum");
  // It says what it is (its report shows it), and of what.
  CHECK(b.description.rfind("The optimum of deb optimise: ", 0) == 0);
  CHECK(b.description.find(r.objective.Text() + " minimised") != std::string::npos);
  const BudgetResult result = Evaluate(b);
  CHECK(result.outputs[0].rms() == doctest::Approx(r.starts[r.best].objective).epsilon(1e-12));
  // Values to at most 15 significant digits: the 17th of an SI value shown
  // in mm was conversion noise ("399.99999999999994 mm").
  const std::string text = OptimumYaml("../b.yaml", "opt", r, {});
  const std::string values = text.substr(text.find("\nparameters:\n"));
  std::size_t digits = 0, most = 0;
  for (char c : values) {
    digits = std::isdigit(static_cast<unsigned char>(c)) ? digits + 1 : c == '.' ? digits : 0;
    most = std::max(most, digits);
  }
  CHECK(most <= 15);
}

TEST_CASE("the thesis' Kv and h: BOBYQA within 60 evaluations, no worse than any point of a grid over the box") {
  // The thesis budget (no requirements) with Kv and h as design variables.
  const Dir dir;
  const std::string file = dir.Write("thesis.yaml", "extends: '" + std::string(DEB_SOURCE_DIR) +
                                                        "/budgets/nizamoglu2015_h210.yaml'\nname: thesis\n"
                                                        "parameters:\n  Kv: {value: 50, min: 5, max: 300}\n"
                                                        "  h: {value: 210 mm, min: -300 mm, max: 400 mm}\n");
  const OptimiseBudget b = LoadOptimiseFile(file, {"Kv", "h"});
  OptimiseObjective z;
  z.terms = {{"z_velocity", 1.0}};
  OptimiseOptions o;
  o.method = OptimiseMethod::kBobyqa;
  o.max_evaluations = 60;
  const OptimiseResult r = RunOptimise(b.variables, z, o, b.loader);
  const OptimiseStart& best = r.starts[r.best];
  MESSAGE("BOBYQA: Kv " << best.values[0] << ", h " << best.values[1] * 1e3 << " mm, RMS " << best.objective
                        << " um/s in " << r.evaluations << " evaluations (" << best.stop << ")");
  CHECK(r.evaluations <= 60);
  CHECK(best.stop.find("converged") == 0);
  // A 15 x 15 grid over the box, and a line of Kv at the optimum's h
  // (the bound 400 mm) with spacing 0.25: none lower, and the line's best
  // within its spacing of the optimum.
  const std::vector<DesignVariable>& v = b.variables;
  const auto rms = [&](double kv, double h) {
    return Evaluate(b.loader({kv, h}), EngineOptions::VariancesOnly()).outputs[0].rms();
  };
  double grid_best = 1e300;
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j)
      grid_best = std::min(grid_best, rms(v[0].min + (v[0].max - v[0].min) * i / 14.0, v[1].min + (v[1].max - v[1].min) * j / 14.0));
  CHECK(best.objective <= grid_best);
  CHECK(best.values[1] == doctest::Approx(0.4).epsilon(1e-9));
  double line_kv = 0.0, line_best = 1e300;
  for (double kv = 25.0; kv <= 38.0; kv += 0.25) {
    const double x = rms(kv, 0.4);
    if (x < line_best) {
      line_best = x;
      line_kv = kv;
    }
  }
  CHECK(std::abs(best.values[0] - line_kv) <= 0.25);
  CHECK(best.objective <= line_best);
  // The optimum's h is the range's bound, and its description says so (the
  // report called 400 mm the optimum with no word of it); Kv is inside its range.
  CHECK(VariablesAtBound(r) == std::vector<std::size_t>{1});
  // The objective is nearly flat in h near 400 mm: at 225 mm (a quarter of the range in), Kv as it is, it is
  // within 1 %, and the text says so rather than send the engineer to widen the range. The probe's figure is
  // the budget's own at that point.
  REQUIRE(r.bound_probes.size() == 1);
  REQUIRE(r.bound_probes[0].variable == 1);
  CHECK(r.bound_probes[0].at.values[1] == doctest::Approx(0.225));
  const double at_225 = rms(best.values[0], 0.225);
  CHECK(r.bound_probes[0].at.objective == doctest::Approx(at_225).epsilon(1e-9));
  CHECK(at_225 / best.objective - 1.0 < kFlatObjective);
  CHECK(BoundsText(r) == "On a bound: h at its maximum 400 mm (at 225 mm, the others as they are, the objective is " +
                             SignificantText(100.0 * (at_225 / best.objective - 1.0), 2) +
                             " % worse): nearly flat there; the bound, not a clear optimum, decides the value.");
  CHECK(OptimumDescription(r, "").find(BoundsText(r)) != std::string::npos);
  CHECK(OptimiseSummaryJson("thesis", r).find("\"at_bound\": [\n      \"h\"\n    ]") != std::string::npos);
}

TEST_CASE("robust: the P95 over a's tolerance moves kv* to (b / a_P95)^(1/4)") {
  // a uncertain: at a fixed kv the RMS rises with a, so its P95 over the
  // samples is the RMS at the samples' P95 of a; with 21 samples that is
  // exactly the 20th smallest (numpy's percentile: h = 0.95 x 20 = 19).
  const Dir dir;
  const std::string file = dir.Write(
      "b.yaml", test::Replace(test::Replace(kBudget, "  kv: {value: 5, min: 0.5, max: 10}\n",
                                            "  kv: {value: 5, min: 0.5, max: 10}\n"
                                            "  a: {value: 1, distribution: {uniform: {min: 0.5, max: 1.5}}}\n"),
                              "level: 1.0e-6}", "level: a * 1.0e-6}"));
  const OptimiseBudget b = LoadOptimiseFile(file, {"kv"}, {}, true);
  REQUIRE(b.uncertain.parameters.size() == 1);
  OptimiseObjective z;
  z.terms = {{"z", 1.0}};
  z.quantile = 0.95;
  for (int k = 20; k >= 0; --k) z.samples.push_back({0.5 + k / 20.0});  // any order
  OptimiseOptions o;
  o.method = OptimiseMethod::kBobyqa;
  const OptimiseResult r = RunOptimise(b.variables, z, o, b.loader);
  const double expected = std::pow(16.0 / 1.45, 0.25);
  MESSAGE("robust kv* " << r.starts[r.best].values[0] << ", closed form " << expected);
  CHECK(r.starts[r.best].values[0] == doctest::Approx(expected).epsilon(1e-6));
  CHECK(z.Text() == "the P95 of the RMS of z under the tolerances (21 samples)");
  // With gradients: central differences of the percentile, saying so.
  o.method = OptimiseMethod::kSlsqp;
  const OptimiseResult slsqp = RunOptimise(b.variables, z, o, b.loader);
  CHECK(slsqp.gradients == "central differences: the objective is a percentile under the tolerances");
  CHECK(slsqp.starts[slsqp.best].values[0] == doctest::Approx(expected).epsilon(1e-5));
  // A budget with no tolerance besides the variables: --robust has nothing to sample.
  CHECK_THROWS_WITH_AS(LoadOptimiseFile(dir.Write("c.yaml", kBudget), {"kv"}, {}, true),
                       doctest::Contains("--robust: no parameter besides those of --vary has a distribution"),
                       InputError);
}

TEST_CASE("a required phase margin: L = k / (s (s + 1)) keeps 45 deg up to k = sqrt(2)") {
  // The process sensitivity 1 / (s^2 + s + k) of a white force has the
  // variance S0 / (2 k) (its RMS falls as k rises), and the phase margin
  // 90 deg - atan(w_c) with k = w_c sqrt(1 + w_c^2): 45 deg at w_c = 1 rad/s,
  // k = sqrt(2). The optimum lies on the margin, which is active.
  const Dir dir;
  const std::string budget = R"(name: pm
parameters:
  k: {value: 0.5, min: 0.1, max: 10}
grid: {type: log, min_hz: 0.001, max_hz: 100, points: 400}
sources:
  - {name: d, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - {name: G, type: transfer_function, num: [1], den: [1, 1, 0], input_unit: N, output_unit: m}
  - {name: K, type: gain, gain: [[k]], input_unit: m, output_unit: N}
  - {name: PS, type: feedback, plant: G, controller: K, margins: {phase_deg: 45}}
contributors:
  - {name: c, source: d, path: PS}
outputs:
  - {name: x, signal: y, unit: m}
)";
  const OptimiseBudget b = LoadOptimiseFile(dir.Write("pm.yaml", budget), {"k"});
  OptimiseObjective x;
  x.terms = {{"x", 1.0}};
  for (OptimiseMethod m : {OptimiseMethod::kSlsqp, OptimiseMethod::kCobyla}) {
    OptimiseOptions o;
    o.method = m;
    const OptimiseResult r = RunOptimise(b.variables, x, o, b.loader);
    CAPTURE(ToString(m));
    REQUIRE(r.feasible);
    MESSAGE(ToString(m) << ": k* " << r.starts[r.best].values[0] << " in " << r.evaluations << " evaluations");
    CHECK(r.starts[r.best].values[0] == doctest::Approx(std::sqrt(2.0)).epsilon(1e-6));
    REQUIRE(r.requirements.size() == 1);
    CHECK(r.requirements[0].name == "loop G/K phase margin");
    CHECK(r.requirements[0].margin);
    CHECK(r.requirements[0].active);
  }
  // The margin rules: located errors.
  using test::CheckLocated;
  const auto error = [&](const std::string& to) {
    return test::ErrorOfBudget(dir.Write("b.yaml", test::Replace(budget, "margins: {phase_deg: 45}", to)));
  };
  CheckLocated(error("margins: {phase_deg: 200}"), "paths[2].margins.phase_deg", "a phase margin is below 180 deg");
  CheckLocated(error("margins: {modulus: 1.5}"), "paths[2].margins.modulus", "is at most 1");
  CheckLocated(error("margins: {}"), "paths[2].margins", "no margin: give gain_db, phase_deg or modulus");
  CheckLocated(error("margins: {phase: 45}"), "paths[2].margins.phase", "unknown key 'phase'");
  CheckLocated(error("margins: {gain_db: -6}"), "paths[2].margins.gain_db", "-6");
}

TEST_CASE("bad bounds and --vary: errors naming the rule") {
  const Dir dir;
  using test::CheckLocated;
  const auto error = [&](const std::string& from, const std::string& to) {
    return test::ErrorOfBudget(dir.Write("b.yaml", test::Replace(kBudget, from, to)));
  };
  CheckLocated(error("min: 0.5, max: 10", "min: 10, max: 0.5"), "parameters.kv.max", "max 0.5 must be above min 10");
  CheckLocated(error("min: 0.5, max: 10", "min: 0.5, max: 4"), "parameters.kv.value",
               "the value 5 lies outside [min, max] = [0.5, 4]");
  CheckLocated(error("min: 0.5, max: 10", "min: 0.5"), "parameters.kv", "a design variable has both bounds: give max");
  CheckLocated(error("min: 0.5, max: 10", "min: 0.5 m, max: 10"), "parameters.kv.min", "'0.5 m' is not the quantity of kv");
  const std::string file = dir.Write("b.yaml", test::Replace(kBudget, "  kv: {value: 5, min: 0.5, max: 10}\n",
                                                             "  kv: {value: 5, min: 0.5, max: 10}\n  g: 3\n"));
  const auto vary = [&](const std::vector<std::string>& names) -> std::string {
    try {
      LoadOptimiseFile(file, names);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no InputError)";
  };
  CHECK(vary({"kw"}).find("--vary kw: no parameter of that name (did you mean 'kv'?)") != std::string::npos);
  CHECK(vary({"g"}).find("--vary g: the parameter has no bounds; give them in the budget") != std::string::npos);
  CHECK(vary({"kv", "kv"}).find("--vary kv: named twice") != std::string::npos);
  CHECK(vary({}).find("--vary: name the parameters to optimise") != std::string::npos);
  // BOBYQA with a requirement to meet; max-ratio without requirements; an unknown objective.
  const OptimiseBudget constrained = LoadOptimiseFile(dir.Write("c.yaml", WithLimit(1.5)), {"kv"});
  OptimiseObjective z;
  z.terms = {{"z", 1.0}};
  OptimiseOptions bobyqa;
  bobyqa.method = OptimiseMethod::kBobyqa;
  CHECK_THROWS_WITH_AS(RunOptimise(constrained.variables, z, bobyqa, constrained.loader),
                       doctest::Contains("--method bobyqa handles bounds only"), InputError);
  const OptimiseBudget free = LoadOptimiseFile(dir.Write("d.yaml", kBudget), {"kv"});
  OptimiseObjective ratio;
  ratio.max_ratio = true;
  CHECK_THROWS_WITH_AS(RunOptimise(free.variables, ratio, {}, free.loader),
                       doctest::Contains("the objective max-ratio needs requirements"), InputError);
  OptimiseObjective unknown;
  unknown.terms = {{"q", 1.0}};
  CHECK_THROWS_WITH_AS(RunOptimise(free.variables, unknown, {}, free.loader),
                       doctest::Contains("--objective q: no output of that name (the outputs: z, w; or max-ratio)"),
                       InputError);
}

TEST_CASE("an optimum on a bound is nearly flat or limited by the range, as the probe a quarter in says") {
  OptimiseResult r;
  r.variables = {{"Kv", "N/(mm/s)", 1e3, 50e3, 0.0, 200e3}, {"h", "mm", 1e-3, 0.21, 0.04, 0.4}};
  OptimiseStart best;
  best.values = {31.5e3, 0.4};
  best.objective = 11.126;
  r.starts = {best};
  r.bound_probes = {{1, {-1, {31.5e3, 0.31}, 11.14, 0.9, ""}}};
  CHECK(BoundsText(r) ==
        "On a bound: h at its maximum 400 mm (at 310 mm, the others as they are, the objective is 0.13 % worse): "
        "nearly flat there; the bound, not a clear optimum, decides the value.");
  // 5 % worse a quarter in: the bound matters.
  r.bound_probes[0].at.objective = 11.7;
  CHECK(BoundsText(r) ==
        "On a bound: h at its maximum 400 mm (at 310 mm, the others as they are, the objective is 5.2 % worse): the "
        "range given, not the budget, limits the optimum there (widen it to see further).");
  // Nearly as good but missing a requirement: not flat.
  r.bound_probes[0].at.objective = 11.14;
  r.bound_probes[0].at.worst_ratio = 1.5;
  r.requirements = {RequirementRatio{}};
  CHECK(BoundsText(r).find("0.13 % worse and a requirement fails): the range given") != std::string::npos);
}

}  // namespace
}  // namespace deb
