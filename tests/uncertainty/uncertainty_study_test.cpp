// Uncertainty studies (deb/uncertainty/uncertainty_study.h) of budgets
// loaded from YAML (deb/load/uncertainty_yaml.h), against closed forms: a
// flat force PSD of level s 1e-6 N^2/Hz through a gain of 1 um/N on 1-100
// Hz has the variance 99e-6 s um^2, so with s uniform on [1, 3] the RMS
// meets R with probability (R^2 / 99e-6 - 1) / 2. An unused parameter d
// with a distribution has no influence: its rank correlation and Sobol
// indices are ~0. The first-order sigma, the worst corner, the same result
// for any thread count, and every rule of the distributions as a located
// error.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/uncertainty_yaml.h"
#include "deb/results/uncertainty_files.h"
#include "deb/uncertainty/sample_design.h"
#include "tests/support/budget_errors.h"
#include "tests/support/linear_level_budget.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

// Each test's files, removed when it ends.
class Dir : public test::ScratchDir {
 public:
  Dir() : ScratchDir("uncertainty") {}
};

const std::string& kBudget = test::kLinearLevelBudget;

constexpr double kLimit = 0.014;
const double kPMeet = (kLimit * kLimit / 99e-6 - 1.0) / 2.0;

UncertaintyResult Study(const std::string& file, SamplingMethod method, std::size_t samples, int threads = 0) {
  const UncertaintyBudget b = LoadUncertaintyFile(file);
  UncertaintyOptions o;
  o.method = method;
  o.samples = samples;
  o.seed = 2026;
  o.threads = threads;
  return RunUncertainty(b.spec, o, b.variant);
}

TEST_CASE("the spec: distributions in SI, the unit kept, a percentage of the value") {
  const Dir dir;
  const UncertaintyBudget b = LoadUncertaintyFile(dir.Write("b.yaml", kBudget));
  REQUIRE(b.spec.parameters.size() == 2);
  CHECK(b.spec.parameters[0].name == "s");
  CHECK(b.spec.parameters[1].name == "d");
  CHECK(b.spec.parameters[1].unit == "mm");
  CHECK(b.spec.parameters[1].unit_si == doctest::Approx(1e-3).epsilon(1e-15));
  CHECK(b.spec.parameters[1].nominal == doctest::Approx(5e-3).epsilon(1e-15));
  CHECK(b.spec.parameters[1].distribution.sigma == doctest::Approx(5e-4).epsilon(1e-15));
  CHECK_FALSE(b.spec.Correlated());
}

TEST_CASE("P(meet) of an RMS with a uniform variance: the closed form within deb's Wilson interval at 1e4 samples") {
  const Dir dir;
  const std::string file = dir.Write("b.yaml", kBudget);
  const struct {
    SamplingMethod method;
    std::size_t samples;
  } cases[] = {{SamplingMethod::kMonteCarlo, 10000},
               {SamplingMethod::kLatinHypercube, 10000},
               // Sobol: 2^12 base samples, 4 budgets each (A, B and A with each
               // of the 2 columns from B); the statistics take A and B: 8192.
               {SamplingMethod::kSobol, 4096}};
  for (const auto& c : cases) {
    CAPTURE(ToString(c.method));
    const UncertaintyResult r = Study(file, c.method, c.samples);
    REQUIRE(r.metrics.size() == 2);  // z and z.c1
    const StudyMetric& z = r.metrics[0];
    REQUIRE(z.limit.has_value());
    const double p = static_cast<double>(z.met) / static_cast<double>(r.samples);
    MESSAGE(ToString(c.method) << ": P(meet) " << p << " in [" << z.p_meet.low << ", " << z.p_meet.high
                               << "], closed form " << kPMeet << "; " << r.samples << " samples");
    CHECK(z.p_meet.low <= kPMeet);
    CHECK(kPMeet <= z.p_meet.high);
    CHECK(z.nominal == doctest::Approx(std::sqrt(99e-6 * 2)).epsilon(1e-12));
    // The mean of sqrt(99e-6 s) over s in [1, 3]: sqrt(99e-6) (3^1.5 - 1) / 3.
    const double mean = std::sqrt(99e-6) * (std::pow(3.0, 1.5) - 1.0) / 3.0;
    CHECK(std::abs(z.moments.mean - mean) < 4 * z.moments.sd / std::sqrt(static_cast<double>(r.samples)));
    // d has no influence.
    CHECK(std::abs(z.spearman[1]) < 4.0 / std::sqrt(static_cast<double>(r.samples)));
    CHECK(z.spearman[0] > 0.999);
    if (c.method == SamplingMethod::kSobol) {
      MESSAGE("Sobol indices: s " << z.sobol[0].first << " / " << z.sobol[0].total << ", d " << z.sobol[1].first
                                  << " / " << z.sobol[1].total);
      CHECK(z.sobol[0].first == doctest::Approx(1.0).epsilon(0.01));
      CHECK(z.sobol[0].total == doctest::Approx(1.0).epsilon(0.01));
      CHECK(std::abs(z.sobol[1].first) < 0.01);
      CHECK(std::abs(z.sobol[1].total) < 0.01);
    }
    CHECK(r.all_met == z.met);
  }
}

TEST_CASE("first-order sigma, the worst corner, and the same result for any thread count") {
  const Dir dir;
  const std::string file = dir.Write("b.yaml", kBudget);
  const UncertaintyResult one = Study(file, SamplingMethod::kMonteCarlo, 500, 1);
  const UncertaintyResult two = Study(file, SamplingMethod::kMonteCarlo, 500, 2);
  CHECK(UncertaintySummaryJson("lin", one) == UncertaintySummaryJson("lin", two));
  CHECK(UncertaintySamplesCsv(one) == UncertaintySamplesCsv(two));
  const StudyMetric& z = one.metrics[0];
  // d RMS / d s = RMS / (2 s) at s = 2; sigma_s = 2 / sqrt(12).
  const double rms = std::sqrt(99e-6 * 2);
  CHECK(z.gradient[0] == doctest::Approx(rms / 4).epsilon(1e-6));
  CHECK(std::abs(z.gradient[1]) < 1e-9);
  CHECK(z.fosm_sd == doctest::Approx(rms / 4 * 2 / std::sqrt(12.0)).epsilon(1e-6));
  // The corner: s at its maximum 3.
  CHECK(z.worst_corner_value == doctest::Approx(std::sqrt(99e-6 * 3)).epsilon(1e-12));
  CHECK(z.worst_corner[0] == 3.0);
  CHECK(one.corner_method == "all 4 vertices of the tolerance box");
}

TEST_CASE("a discrete choice of floor class, VC-C or VC-D: P(meet) is the probability of the class that meets") {
  // The floor as a VC curve of band velocity floor_v (8-80 Hz, 11 bands)
  // through a unit path: the RMS is v sqrt(11) (to the grid's integration
  // of the band edges, 0.2 % here), VC-C's 12.5 um/s or VC-D's 6.25 um/s
  // with probabilities 0.7 and 0.3, VC-D's exactly half VC-C's; a
  // requirement between them is met with probability 0.3.
  const std::string text = R"(name: floor_class
parameters:
  floor_v:
    value: 12.5 um/s
    description: floor class, VC-C or VC-D
    distribution: {discrete: {values: [12.5 um/s, 6.25 um/s], p: [0.7, 0.3]}}
grid: {type: log, min_hz: 1, max_hz: 200, points: 400}
sources:
  - {name: floor, unit: um/s, spectrum: {type: vc, velocity: floor_v}}
paths:
  - {name: unit, type: gain, gain: [[1]], input_unit: um/s, output_unit: um/s}
contributors:
  - {name: c, source: floor, path: unit}
outputs:
  - {name: v, signal: y, unit: um/s, rms_max: 30}
)";
  const Dir dir;
  const std::string file = dir.Write("b.yaml", text);
  for (SamplingMethod method : {SamplingMethod::kMonteCarlo, SamplingMethod::kLatinHypercube}) {
    CAPTURE(ToString(method));
    const UncertaintyResult r = Study(file, method, 10000);
    const StudyMetric& v = r.metrics[0];
    MESSAGE("nominal " << v.nominal << ", closed form " << 12.5 * std::sqrt(11.0));
    CHECK(v.nominal == doctest::Approx(12.5 * std::sqrt(11.0)).epsilon(2e-3));
    const double rms_c = v.nominal, rms_d = v.nominal / 2;
    for (double x : v.values) CHECK((std::abs(x - rms_c) <= 1e-12 * rms_c || std::abs(x - rms_d) <= 1e-12 * rms_d));
    MESSAGE(ToString(method) << ": P(meet) " << static_cast<double>(v.met) / r.samples << " in [" << v.p_meet.low
                             << ", " << v.p_meet.high << "], exact 0.3");
    CHECK(v.p_meet.low <= 0.3);
    CHECK(0.3 <= v.p_meet.high);
    CHECK(v.worst_corner_value == doctest::Approx(rms_c).epsilon(1e-12));
  }
}

TEST_CASE("a Gaussian copula: normal parameters correlated as given") {
  const Dir dir;
  const std::string text = test::Replace(
      test::Replace(kBudget, "s: {value: 2, distribution: {uniform: {min: 1, max: 3}}}",
                    "s: {value: 2, distribution: {normal: {sigma: 0.1}}}"),
      "grid:", "correlations: [{between: [s, d], rho: -0.6}]\ngrid:");
  const UncertaintyResult r = Study(dir.Write("b.yaml", text), SamplingMethod::kMonteCarlo, 4000);
  CHECK(r.spec.Correlated());
  // Pearson correlation of the sampled values: -0.6 within 4 standard errors ((1 - rho^2) / sqrt(N)).
  const auto& a = r.parameter_values[0];
  const auto& b = r.parameter_values[1];
  const Moments ma = MeanAndSd(a), mb = MeanAndSd(b);
  double c = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) c += (a[i] - ma.mean) * (b[i] - mb.mean);
  const double rho = c / static_cast<double>(a.size() - 1) / (ma.sd * mb.sd);
  MESSAGE("sampled correlation " << rho << " (given -0.6)");
  CHECK(std::abs(rho + 0.6) < 4 * (1 - 0.36) / std::sqrt(4000.0));
  CHECK(mb.sd == doctest::Approx(5e-4).epsilon(0.05));
}

TEST_CASE("bad distributions and correlations: located errors naming the rule") {
  const Dir dir;
  const auto error = [&](const std::string& from, const std::string& to) {
    return test::ErrorOfBudget(dir.Write("b.yaml", test::Replace(kBudget, from, to)));
  };
  using test::CheckLocated;
  CheckLocated(error("sigma: 10 %", "sigma: -1"), "parameters.d.distribution.normal",
               "normal: sigma -0.001 must be finite and > 0");
  CheckLocated(error("min: 1, max: 3", "min: 3, max: 1"), "parameters.s.distribution.uniform",
               "uniform: min 3 must be below max 1");
  CheckLocated(error("{uniform: {min: 1, max: 3}}", "{gauss: {sigma: 1}}"), "parameters.s.distribution.gauss",
               "unknown distribution 'gauss'; allowed: normal, uniform, lognormal, truncated_normal, triangular, discrete");
  CheckLocated(error("sigma: 10 %", "sigma: 3 kg"), "parameters.d.distribution.normal.sigma",
               "'3 kg' is not the quantity of d (mm)");
  CheckLocated(error("min: 1, max: 3", "min: 10 %, max: 3"), "parameters.s.distribution.uniform.min",
               "a percentage is allowed for sigma only");
  CheckLocated(error("two_s: 2 * s", "two_s: {value: 2 * s, distribution: {normal: {sigma: 1}}}"),
               "parameters.two_s.distribution", "two_s is derived from other parameters ('2 * s')");
  CheckLocated(error("{normal: {sigma: 10 %}}", "{lognormal: {p95: 4 mm}}"), "parameters.d.distribution.lognormal.p95",
               "p95 4 must be above the value (the median) 5");
  CheckLocated(error("{uniform: {min: 1, max: 3}}", "{discrete: {values: [1, 2], p: [0.5, 0.6]}}"),
               "parameters.s.distribution.discrete", "the probabilities add up to 1.1, not 1");
  const auto correlation = [&](const std::string& list) {
    return error("grid:", "correlations: " + list + "\ngrid:");
  };
  CheckLocated(correlation("[{between: [s, k], rho: 0.5}]"), "correlations[0].between[1]",
               "'k' is not a parameter with a distribution (those with one: s, d)");
  CheckLocated(correlation("[{between: [s, s], rho: 0.5}]"), "correlations[0].between",
               "a parameter is not correlated with itself");
  CheckLocated(correlation("[{between: [s, d], rho: 1.5}]"), "correlations[0].rho", "rho 1.5 must be within [-1, 1]");
  CheckLocated(correlation("[{between: [s, d], rho: 0.5}, {between: [d, s], rho: 0.5}]"), "correlations[1].between",
               "the correlation of these two is given twice");
  CheckLocated(correlation("[{between: [s, d], rho: 1}]"), "correlations", "not positive definite");
  // No distribution at all: the study says what to add.
  const std::string plain = test::Replace(
      test::Replace(kBudget, "s: {value: 2, distribution: {uniform: {min: 1, max: 3}}}", "s: 2"),
      "d: {value: 5 mm, distribution: {normal: {sigma: 10 %}}}", "d: 5 mm");
  try {
    LoadUncertaintyFile(dir.Write("b.yaml", plain));
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("no parameter has a distribution") != std::string::npos);
  }
}

TEST_CASE("the shipped example: the thesis with tolerances") {
  const std::string file = std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_tolerances.yaml";
  const UncertaintyResult r = Study(file, SamplingMethod::kLatinHypercube, 300);
  const StudyMetric& z = r.metrics[0];
  REQUIRE(z.output == "z_velocity");
  REQUIRE(z.contributor.empty());
  // The nominal design is the thesis' (nizamoglu2015_h210: 12.0523 um/s).
  const BudgetResult nominal = Evaluate(LoadBudgetFile(std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_h210.yaml"));
  CHECK(z.nominal == doctest::Approx(nominal.outputs[0].rms()).epsilon(1e-12));
  // The geophones' noise drives it: the strongest rank correlation; the
  // first-order sd within 20 % of the sampled one (the RMS is nearly linear
  // in the tolerances here).
  for (std::size_t i = 0; i + 1 < r.spec.parameters.size(); ++i) CHECK(std::abs(z.spearman[i]) < z.spearman[3]);
  CHECK(r.spec.parameters[3].name == "s_geo");
  CHECK(z.fosm_sd == doctest::Approx(z.moments.sd).epsilon(0.2));
  CHECK(z.limit.has_value());
  CHECK(z.worst_corner_value > z.p99);
}

TEST_CASE("the shipped example: the metrology frame with an uncertain floor class and datasheet noise") {
  const std::string dir = std::string(DEB_SOURCE_DIR) + "/budgets/";
  const UncertaintyResult r = Study(dir + "metrology_frame_tolerances.yaml", SamplingMethod::kMonteCarlo, 40);
  // The nominal design is the frame's, to the last bit (VC-D by its velocity).
  const BudgetResult frame = Evaluate(LoadBudgetFile(dir + "metrology_frame.yaml"));
  REQUIRE(r.metrics[0].output == "head_z");
  CHECK(r.metrics[0].nominal == frame.outputs[0].rms());
  // The floor's contributor scales with the class's velocity: every sample's
  // is the nominal's times 2 (VC-C), 1 (VC-D) or 3.12 / 6.25 (VC-E), and the
  // floor_v parameter is one of those velocities.
  const StudyMetric* floor = nullptr;
  for (const StudyMetric& m : r.metrics)
    if (m.output == "head_z" && m.contributor == "floor") floor = &m;
  REQUIRE(floor);
  std::size_t classes[3] = {0, 0, 0};
  for (std::size_t s = 0; s < floor->values.size(); ++s) {
    const double v = r.parameter_values[0][s] * 1e6;  // um/s
    const double ratio = floor->values[s] / floor->nominal;
    CAPTURE(v);
    if (v == doctest::Approx(12.5).epsilon(1e-12)) {
      CHECK(ratio == doctest::Approx(2.0).epsilon(1e-12));
      ++classes[0];
    } else if (v == doctest::Approx(6.25).epsilon(1e-12)) {
      CHECK(ratio == doctest::Approx(1.0).epsilon(1e-12));
      ++classes[1];
    } else {
      CHECK(v == doctest::Approx(3.12).epsilon(1e-12));
      CHECK(ratio == doctest::Approx(3.12 / 6.25).epsilon(1e-12));
      ++classes[2];
    }
  }
  CHECK(classes[0] + classes[1] + classes[2] == 40);
  CHECK(classes[1] > classes[0]);  // VC-D the likeliest
}

TEST_CASE("more parameters than Boost's Sobol table holds: an error for every caller, not an assertion") {
  // The run, a shard, a merge and the Python module all plan the study
  // through UncertaintyEvaluationCount's plan.
  UncertaintySpec spec;
  UncertainParameter p;
  p.name = "x";
  p.nominal = 1.0;
  p.distribution.kind = DistributionKind::kUniform;
  p.distribution.min = 0.5;
  p.distribution.max = 1.5;
  spec.parameters.assign(MaxSobolDimensions() / 2 + 1, p);
  spec.correlation = Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(spec.parameters.size()),
                                               static_cast<Eigen::Index>(spec.parameters.size()));
  UncertaintyOptions options;
  options.method = SamplingMethod::kSobol;
  options.samples = 4;
  CHECK_THROWS_WITH_AS(UncertaintyEvaluationCount(spec, options),
                       (std::to_string(spec.parameters.size()) + " uncertain parameters; --method sobol takes at most " +
                        std::to_string(MaxSobolDimensions() / 2))
                           .c_str(),
                       InputError);
  options.method = SamplingMethod::kLatinHypercube;  // any number of dimensions
  CHECK(UncertaintyEvaluationCount(spec, options) > 4);
}

}  // namespace
}  // namespace deb
