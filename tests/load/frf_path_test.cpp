// Budget paths of `type: frf`: a measured frequency response from a file,
// alone and joined with rational paths in series and feedback.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

constexpr double kPi = 3.141592653589793238462643383279502884;

// plant.csv: the mass-spring-damper 1/(s^2 + 2 s + 400) (m/N; f_n = 3.18 Hz,
// zeta = 0.05) tabulated at 400 points per decade over 0.01-1000 Hz as
// magnitude and phase: the "measurement" of the rational path `model`.
class FrfDir {
 public:
  FrfDir() : dir_(std::filesystem::temp_directory_path() / ("deb_frf_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    std::ofstream out(dir_ / "plant.csv");
    out.precision(17);
    out << "# mass-spring-damper, m = 1 kg, c = 2 N s/m, k = 400 N/m\nf_hz, x/F.mag, x/F.phase_deg\n";
    for (int i = 0; i <= 2000; ++i) {
      const double f = std::pow(10.0, -2.0 + i / 400.0);
      const std::complex<double> s(0.0, 2.0 * kPi * f);
      const std::complex<double> h = 1.0 / (s * s + 2.0 * s + 400.0);
      out << f << ", " << std::abs(h) << ", " << std::arg(h) * 180.0 / kPi << "\n";
    }
  }
  ~FrfDir() { std::filesystem::remove_all(dir_); }
  // narrow.csv: the same plant over 0.5-200 Hz only.
  void WriteNarrow() const {
    std::ofstream out(dir_ / "narrow.csv");
    out.precision(17);
    out << "f_hz, x/F.mag, x/F.phase_deg\n";
    for (int i = 0; i <= 100; ++i) {
      const double f = 0.5 * std::pow(400.0, i / 100.0);
      const std::complex<double> s(0.0, 2.0 * kPi * f);
      const std::complex<double> h = 1.0 / (s * s + 2.0 * s + 400.0);
      out << f << ", " << std::abs(h) << ", " << std::arg(h) * 180.0 / kPi << "\n";
    }
  }
  std::string Write(const std::string& budget) const {
    std::ofstream((dir_ / "b.yaml").string()) << budget;
    return (dir_ / "b.yaml").string();
  }

 private:
  std::filesystem::path dir_;
};

const char* kBudget = R"(name: frf
grid: {type: auto, min_hz: 0.01, max_hz: 1000}
sources:
  - {name: force, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - {name: measured, type: frf, file: plant.csv, input_unit: N, output_unit: m}
  - {name: model, type: transfer_function, num: [1], den: [1, 2, 400], inputs: [F], outputs: [x], input_unit: N, output_unit: m}
  - {name: k, type: gain, gain: [[1000]], input_unit: m, output_unit: N}
  - {name: loop_measured, type: feedback, plant: measured, controller: k}
  - {name: loop_model, type: feedback, plant: model, controller: k}
  - {name: to_mm, type: gain, gain: 1, input_unit: m, output_unit: mm, inputs: [x], outputs: [x_mm]}
  - {name: chain, type: series, of: [measured, to_mm]}
contributors:
  - {name: measured, source: force, path: measured}
  - {name: model, source: force, path: model}
  - {name: loop_measured, source: force, path: loop_measured}
  - {name: loop_model, source: force, path: loop_model}
outputs:
  - {name: x, signal: x, unit: um}
)";

double VarianceOf(const OutputResult& o, const std::string& name) {
  for (const auto& c : o.contributors)
    if (c.name == name) return c.variance;
  FAIL("no contributor " << name);
  return 0.0;
}

std::string ErrorOf(const std::string& file) {
  try {
    Evaluate(LoadBudgetFile(file));
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

using test::Replace;

TEST_CASE("a measured SDOF response gives the variance of its rational model to 1e-3, open and closed loop") {
  const FrfDir dir;
  const Budget b = LoadBudgetFile(dir.Write(kBudget));
  CHECK(b.FindPath("measured").HasMeasuredData());
  CHECK(b.FindPath("chain").HasMeasuredData());
  CHECK(b.FindPath("chain").output_units[0] == "mm");
  const BudgetResult r = Evaluate(b);
  const OutputResult& x = r.outputs[0];
  // sigma^2 = S0 / (4 c k) = 1 / 3200 m^2 for the whole axis (one-sided S0 = 1 N^2/Hz).
  const double closed_form_um2 = 1e12 / 3200.0;
  const double measured = VarianceOf(x, "measured"), model = VarianceOf(x, "model");
  MESSAGE("measured " << measured << ", model " << model << ", closed form " << closed_form_um2);
  CHECK(std::abs(measured - model) / model < 1e-3);            // interpolation of the table only
  CHECK(std::abs(measured - closed_form_um2) / closed_form_um2 < 2e-3);  // + the grid's low end
  const double loop_m = VarianceOf(x, "loop_measured"), loop_r = VarianceOf(x, "loop_model");
  CHECK(std::abs(loop_m - loop_r) / loop_r < 1e-3);
  for (const auto& c : x.contributors)
    if (c.name == "measured" || c.name == "loop_measured") {
      CHECK_FALSE(c.exact_variance.has_value());
      CHECK(c.exact_note.find("measured frequency data") != std::string::npos);
    }
  int warned = 0;
  for (const auto& w : r.warnings) warned += w.find("'loop_measured' closes a loop around measured data") != std::string::npos;
  CHECK(warned == 1);
}

TEST_CASE("a grid beyond the measured range is an error naming the path, the file and the range") {
  const FrfDir dir;
  const std::string file = dir.Write(Replace(kBudget, "max_hz: 1000}", "max_hz: 2000}"));
  const std::string m = ErrorOf(file);
  // Rejected before anything is computed (deb check says the same), at the grid the budget set.
  CHECK(m.find("path 'measured' (measured data) is defined over [0.01, 1000] Hz only (extrapolation: error), "
               "but the frequency grid spans [0.01, 2000] Hz: keep the grid inside that range") != std::string::npos);
  CHECK_THROWS_AS(PlanEvaluation(LoadBudgetFile(file)), InputError);
  const std::string held = dir.Write(Replace(Replace(kBudget, "max_hz: 1000}", "max_hz: 2000}"),
                                             "file: plant.csv,", "file: plant.csv, extrapolation: zero,"));
  CHECK_NOTHROW(Evaluate(LoadBudgetFile(held)));
}

TEST_CASE("bad frf entries point at the budget key") {
  const FrfDir dir;
  const std::string missing = ErrorOf(dir.Write(Replace(kBudget, "file: plant.csv", "file: nowhere.csv")));
  CHECK(missing.find("b.yaml:6:39: paths[0].file:") != std::string::npos);
  CHECK(missing.find("cannot open frequency response file") != std::string::npos);
  const std::string extrap = ErrorOf(dir.Write(Replace(kBudget, "file: plant.csv,", "file: plant.csv, extrapolation: clamp,")));
  CHECK(extrap.find("allowed: error, zero, hold") != std::string::npos);
  const std::string names = ErrorOf(dir.Write(Replace(kBudget, "file: plant.csv,", "file: plant.csv, outputs: [z],")));
  CHECK(names.find("output 'x' is not one of the path's outputs (z)") != std::string::npos);
  const std::string key = ErrorOf(dir.Write(Replace(kBudget, "file: plant.csv,", "file: plant.csv, num: [1],")));
  CHECK(key.find("unknown key 'num'") != std::string::npos);
}

TEST_CASE("the shipped measured-stage budget matches the rational model of its loop to 1e-5") {
  // budgets/measured_stage.yaml's FRF is tabulated from P(s) = w^2 / (m s^2 (s^2 +
  // 2 zeta w s + w^2)); the same loop from that transfer function (state space,
  // same grid) gives 7.14202 nm (amplifier) and 7.02927 nm (cable slab).
  const BudgetResult r = Evaluate(LoadBudgetFile(std::string(DEB_SOURCE_DIR) + "/budgets/measured_stage.yaml"));
  const OutputResult& x = r.outputs[0];
  CHECK(std::sqrt(VarianceOf(x, "amplifier")) == doctest::Approx(7.14202).epsilon(1e-5));
  CHECK(std::sqrt(VarianceOf(x, "cable_slab")) == doctest::Approx(7.02927).epsilon(1e-5));
  // The mains hum: tones of 0.2 mN at 50 Hz and 0.05 mN at 150 Hz through H = P / (1 + P K), evaluated
  // from P and K themselves: |H(50)|^2 (2e-4)^2 + |H(150)|^2 (5e-5)^2 = (0.5316305 nm)^2; the measured FRF
  // is interpolated between its points, hence 1e-5.
  CHECK(std::sqrt(VarianceOf(x, "mains_hum")) == doctest::Approx(0.5316305).epsilon(1e-5));
}

TEST_CASE("the loop around the measured stage has the margins of its rational model") {
  // Independent computation from P(s) above and the lead K(s) of the budget
  // (bisection on the closed forms, 2e5-point scan for the modulus margin):
  // |L| = 1 at 30.0629 Hz with PM 53.0149 deg (asin 0.8 = 53.130 of the
  // lead less 0.115 of the 600 Hz mode), L = -0.041110 at 526.04 Hz (gain
  // margin 24.325), min |1 + L| = 0.76731 at 52.317 Hz. The FRF table is
  // interpolated between its points: tolerances 1e-3 relative (frequencies,
  // modulus margin), 0.05 deg, and 0.5 % on the gain margin, read where the
  // mode's phase turns fastest.
  const BudgetResult r = Evaluate(LoadBudgetFile(std::string(DEB_SOURCE_DIR) + "/budgets/measured_stage.yaml"));
  REQUIRE(r.loops.size() == 1);
  const LoopResult& loop = r.loops[0];
  CHECK(loop.plant == "stage");
  CHECK(loop.controller == "controller");
  CHECK(loop.paths == std::vector<std::string>{"closed_loop"});
  REQUIRE(loop.evaluated);
  REQUIRE(loop.margins.phase_margin);
  CHECK(loop.margins.phase_margin->f_hz == doctest::Approx(30.0629).epsilon(1e-3));
  CHECK(std::abs(loop.margins.phase_margin->phase_margin_deg - 53.0149) < 0.05);
  REQUIRE(loop.margins.upper_gain_margin);
  CHECK(loop.margins.upper_gain_margin->gain_margin == doctest::Approx(24.325).epsilon(5e-3));
  CHECK(loop.margins.upper_gain_margin->f_hz == doctest::Approx(526.04).epsilon(1e-3));
  CHECK(loop.margins.modulus_margin == doctest::Approx(0.76731).epsilon(1e-3));
  CHECK(loop.margins.modulus_margin_f_hz == doctest::Approx(52.317).epsilon(1e-3));
}

}  // namespace
}  // namespace deb

namespace deb {
namespace {

TEST_CASE("the automatic grid without a range stays inside measured data; the plan rejects bands beyond it") {
  const FrfDir dir;
  dir.WriteNarrow();
  const std::string budget = R"(name: narrow
grid: {type: auto}
sources:
  - {name: force, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - {name: measured, type: frf, file: narrow.csv, input_unit: N, output_unit: m}
contributors:
  - {name: measured, source: force, path: measured}
outputs:
  - {name: x, signal: x, unit: um}
)";
  const Budget b = LoadBudgetFile(dir.Write(budget));
  const EvaluationPlan plan = PlanEvaluation(b);
  CHECK(plan.grid.min_hz() == 0.5);  // the data's first frequency, not the default 0.1 Hz
  CHECK(plan.grid.max_hz() == doctest::Approx(200.0).epsilon(1e-15));
  REQUIRE(plan.exact_refusal.size() == 1);
  CHECK(plan.exact_refusal[0][0].find("measured frequency data") != std::string::npos);
  const BudgetResult r = Evaluate(b);  // the first run of a new user's budget succeeds
  CHECK(r.grid.min_hz() == plan.grid.min_hz());
  CHECK(r.grid.size() == plan.grid.size());
  CHECK(r.outputs[0].contributors[0].exact_note == plan.exact_refusal[0][0]);

  // Extrapolated data do not limit the default range.
  const Budget held = LoadBudgetFile(dir.Write(Replace(budget, "file: narrow.csv,", "file: narrow.csv, extrapolation: hold,")));
  CHECK(PlanEvaluation(held).grid.min_hz() == 0.1);
  CHECK(PlanEvaluation(held).grid.max_hz() == 1000.0);

  // A band beyond the data widens the automatic grid past it: rejected at the path, before computing.
  const Budget wide = LoadBudgetFile(dir.Write(Replace(budget, "outputs:", "bands: [[0.1, 10]]\noutputs:")));
  try {
    PlanEvaluation(wide);
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "paths[0]");
    CHECK(std::string(e.what()).find("is defined over [0.5, 200] Hz only") != std::string::npos);
  }
}

}  // namespace
}  // namespace deb
