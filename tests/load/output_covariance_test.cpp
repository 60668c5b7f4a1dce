// The covariance matrix of a set of outputs (`covariance:`): against the
// closed form of a mass-spring-damper, against the engine's own variance of
// a combined output, against tones through known transfer functions; and the
// request's rules as located errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/result_writer.h"
#include "deb/systems/lyapunov.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

double Rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// m x'' + c x' + k x = F: m = 1 kg, f_n = 5 Hz, zeta = 0.05; F white, S0 = 1e-4 N^2/Hz.
const double kM = 1.0, kK = std::pow(2 * kPi * 5.0, 2), kC = 2 * 0.05 * std::sqrt(kK * kM), kS0 = 1e-4;

std::string Oscillator(const std::string& outputs, const std::string& covariance) {
  return "name: msd\ngrid: {type: auto, min_hz: 0.01, max_hz: 10000}\n"
         "sources:\n  - {name: f, unit: N, spectrum: {type: flat, level: " + Num(kS0) + "}}\n"
         "paths:\n  - {name: msd, type: state_space, A: [[0, 1], [" + Num(-kK / kM) + ", " + Num(-kC / kM) +
         "]], B: [[0], [" + Num(1 / kM) + "]], C: [[1, 0], [0, 1]], D: [[0], [0]], input_unit: N,"
         " outputs: [x, v], output_units: [m, m/s]}\n"
         "contributors:\n  - {name: force, source: f, path: msd}\noutputs:\n" + outputs + covariance;
}

const std::string kOscillatorOutputs =
    "  - {name: x, signal: x, unit: um}\n"
    "  - {name: v, signal: v, unit: um/s}\n"
    "  - {name: p, unit: um, combination: {x: 1, v: 10 ms}}\n";

// Two masses on springs, a force on each (correlated channels), and tones on both.
std::string TwoMasses(const std::string& grid) {
  return "name: two\ngrid: " + grid + "\n"
         "sources:\n"
         "  - {name: f, unit: N, channels: [f1, f2], correlation: 0.5, spectrum: {type: flat, level: 1.0e-4}}\n"
         "  - name: hum\n    unit: N\n    channels: [f1, f2]\n    spectrum:\n      type: tones\n"
         "      tones:\n        - {f_hz: 7, rms: [0.01, 0.02], phase_deg: [0, 60]}\n"
         "        - {f_hz: 30, rms: [0.005, 0.001], phase_deg: [0, -120]}\n"
         "paths:\n"
         "  - {name: masses, type: state_space, A: [[0, 0, 1, 0], [0, 0, 0, 1], [-3000, 2000, -3, 1],"
         " [4000, -4000, 2, -2]], B: [[0, 0], [0, 0], [1, 0], [0, 2]], C: [[1, 0, 0, 0], [0, 1, 0, 0]],"
         " D: [[0, 0], [0, 0]], input_unit: N, outputs: [x1, x2], output_unit: m}\n"
         "contributors:\n  - {name: force, source: f, path: masses}\n  - {name: hum, source: hum, path: masses}\n"
         "outputs:\n"
         "  - {name: a, signal: x1, unit: um}\n"
         "  - {name: b, signal: x2, unit: nm}\n"
         "  - {name: d, unit: um, combination: {x1: 1, x2: -0.4}}\n"
         "covariance: [a, b]\n";
}

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { Evaluate(LoadBudgetText(text, "c.yaml")); });
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("mass-spring-damper: var x = W/(2ck), var v = W/(2cm), cov(x, v) = 0, cov(x, x + a v) = var x") {
  const BudgetResult r =
      Evaluate(LoadBudgetText(Oscillator(kOscillatorOutputs, "covariance: [x, v, p]\n"), "c.yaml"));
  REQUIRE(r.covariance.has_value());
  const CovarianceResult& cov = *r.covariance;
  CHECK(cov.outputs == std::vector<std::string>{"x", "v", "p"});
  CHECK(cov.units == std::vector<std::string>{"um", "um/s", "um"});
  // Closed form (two-sided W = S0 / 2), in um and um/s; p = x + 0.01 s v.
  const double w = kS0 / 2, a = 0.01;
  const double var_x = 1e12 * w / (2 * kC * kK), var_v = 1e12 * w / (2 * kC * kM);
  const double expected[3][3] = {{var_x, 0.0, var_x},
                                 {0.0, var_v, a * var_v},
                                 {var_x, a * var_v, var_x + a * a * var_v}};
  REQUIRE(cov.exact_matrix.has_value());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double scale = std::sqrt(expected[i][i] * expected[j][j]);
      CHECK(std::abs((*cov.exact_matrix)(i, j) - expected[i][j]) <= 1e-9 * scale);
      // The grid misses the tails below 0.01 Hz and above 10 kHz (~1e-4).
      CHECK(std::abs(cov.matrix(i, j) - expected[i][j]) <= 1e-3 * scale);
      CHECK(cov.matrix(i, j) == cov.matrix(j, i));
    }
  // H_v = j w H_x: the cross-spectrum is imaginary at every frequency.
  CHECK(std::abs(cov.correlation(0, 1)) < 1e-12);
  CHECK(cov.correlation(0, 0) == 1.0);
  // The diagonal is each output's variance as the engine computed it.
  for (int i = 0; i < 3; ++i) CHECK(Rel(cov.matrix(i, i), r.outputs[i].variance) <= 1e-12);
  REQUIRE(cov.contributors.size() == 1);
  CHECK(cov.contributors[0].name == "force");
  CHECK((cov.contributors[0].matrix - cov.matrix).cwiseAbs().maxCoeff() <= 1e-12 * var_v);
}

TEST_CASE("var(a + k b) of a combined output equals Pa + 2k Pab + k^2 Pb, per contributor and in total") {
  const BudgetResult r =
      Evaluate(LoadBudgetText(TwoMasses("{type: auto, min_hz: 0.1, max_hz: 1000}"), "c.yaml"));
  REQUIRE(r.covariance.has_value());
  const CovarianceResult& cov = *r.covariance;
  // a in um, b in nm: d = a - 0.4 x2 = a - 0.4e-3 b, in um.
  const double k = -0.4e-3;
  const auto combined = [k](const Eigen::MatrixXd& m) { return m(0, 0) + 2 * k * m(0, 1) + k * k * m(1, 1); };
  const OutputResult& d = r.outputs[2];
  CHECK(Rel(combined(cov.matrix), d.variance) <= 1e-10);
  REQUIRE(cov.contributors.size() == 2);
  for (std::size_t c = 0; c < 2; ++c) {
    CHECK(Rel(combined(cov.contributors[c].matrix), d.contributors[c].variance) <= 1e-10);
    CHECK(cov.contributors[c].matrix(0, 0) == r.outputs[0].contributors[c].variance);
    CHECK(cov.contributors[c].matrix(1, 1) == r.outputs[1].contributors[c].variance);
  }
  CHECK(std::abs(cov.correlation(0, 1)) > 0.05);  // the masses move together
  CHECK(std::abs(cov.correlation(0, 1)) < 1.0);
  // The exact matrix: the same identity against the exact variances of d.
  REQUIRE(cov.exact_matrix.has_value());
  double exact_d = 0.0;
  for (const ContributorResult& c : d.contributors) exact_d += *c.exact_variance;
  CHECK(Rel(combined(*cov.exact_matrix), exact_d) <= 1e-9);
  CHECK(Rel(combined(*cov.exact_matrix), d.variance) <= 1e-3);
  for (int i = 0; i < 2; ++i)
    CHECK(Rel((*cov.exact_matrix)(i, i), *r.outputs[i].contributors[0].exact_variance +
                                             *r.outputs[i].contributors[1].exact_variance) <= 1e-9);
}

TEST_CASE("on a grid without panels the diagonal is still each output's variance, and the matrix a covariance") {
  const BudgetResult r = Evaluate(LoadBudgetText(TwoMasses("{type: log, min_hz: 0.1, max_hz: 1000, points: 400}"),
                                                 "c.yaml"));
  const CovarianceResult& cov = *r.covariance;
  for (int i = 0; i < 2; ++i) CHECK(cov.matrix(i, i) == r.outputs[i].variance);
  // The coarse log grid misses a few % of the resonances' variance on the diagonal and off it
  // alike: the correlation is the exact one's to the quadrature's error.
  const Eigen::MatrixXd& exact = *cov.exact_matrix;
  const double exact_correlation = exact(0, 1) / std::sqrt(exact(0, 0) * exact(1, 1));
  CHECK(Rel(cov.matrix(0, 0), exact(0, 0)) > 1e-2);
  CHECK(std::abs(cov.correlation(0, 1) - exact_correlation) <= 1e-3);
}

TEST_CASE("a tone through two low-passes and a weighting: Re(H1 a conj(H2 W a)) exactly") {
  const double w1 = 2 * kPi * 10, w2 = 2 * kPi * 40, w3 = 2 * kPi * 25, f0 = 20, amplitude = 0.3;
  const std::string text =
      "name: tone\ngrid: {type: auto, min_hz: 1, max_hz: 1000}\n"
      "sources:\n  - name: hum\n    unit: um\n    spectrum: {type: tones, tones: [{f_hz: " + Num(f0) +
      ", rms: " + Num(amplitude) + "}]}\n"
      "paths:\n  - {name: lp, type: state_space, A: [[" + Num(-w1) + ", 0], [0, " + Num(-w2) + "]], B: [[" +
      Num(w1) + "], [" + Num(w2) + "]], C: [[1, 0], [0, 1]], D: [[0], [0]], input_unit: um, outputs: [y1, y2],"
      " output_unit: um}\n"
      "contributors:\n  - {name: hum, source: hum, path: lp}\n"
      "outputs:\n  - {name: one, signal: y1, unit: um}\n"
      "  - {name: two, signal: y2, unit: nm, weighting: {num: [" + Num(w3) + "], den: [1, " + Num(w3) + "]}}\n"
      "covariance: [one, two]\n";
  const BudgetResult r = Evaluate(LoadBudgetText(text, "t.yaml"));
  const std::complex<double> s(0.0, 2 * kPi * f0);
  const std::complex<double> y1 = w1 / (s + w1) * amplitude, y2 = 1e3 * w2 / (s + w2) * w3 / (s + w3) * amplitude;
  const double expected = std::real(y1 * std::conj(y2));
  const CovarianceResult& cov = *r.covariance;
  CHECK(Rel(cov.matrix(0, 1), expected) <= 1e-12);
  CHECK(Rel(cov.matrix(0, 0), std::norm(y1)) <= 1e-12);
  CHECK(Rel(cov.matrix(1, 1), std::norm(y2)) <= 1e-12);
  REQUIRE(cov.exact_matrix.has_value());
  CHECK(Rel((*cov.exact_matrix)(0, 1), expected) <= 1e-12);
  CHECK(Rel(cov.correlation(0, 1), expected / std::abs(y1) / std::abs(y2)) <= 1e-12);
}

TEST_CASE("a coloured source has no exact matrix, and says why") {
  const std::string text = Oscillator(kOscillatorOutputs, "covariance: [x, v]\n");
  const std::string coloured = "spectrum: {type: flat, level: " + Num(kS0) + ", lo_hz: 1, hi_hz: 100}";
  std::string changed = text;
  changed.replace(changed.find("spectrum: {type: flat, level: " + Num(kS0) + "}"),
                  ("spectrum: {type: flat, level: " + Num(kS0) + "}").size(), coloured);
  const BudgetResult r = Evaluate(LoadBudgetText(changed, "c.yaml"));
  REQUIRE(r.covariance.has_value());
  CHECK_FALSE(r.covariance->exact_matrix.has_value());
  CHECK(Has(r.covariance->exact_note, "contributor 'force' has no exact variance on output 'x'"));
  CHECK(Has(r.covariance->exact_note, "not white"));
}

TEST_CASE("the matrices from the engine's response traces equal those from evaluating the paths again") {
  // With traces the covariance reads each path's response from them; without
  // (sweeps, sensitivities) it evaluates the path. The same h either way.
  const Budget budget = LoadBudgetText(TwoMasses("{type: auto, min_hz: 0.1, max_hz: 1000}"), "c.yaml");
  EngineOptions drawn, undrawn;
  undrawn.response_traces = false;
  const BudgetResult a = Evaluate(budget, drawn), b = Evaluate(budget, undrawn);
  REQUIRE(a.traces);
  REQUIRE_FALSE(b.traces);
  const CovarianceResult &ca = *a.covariance, &cb = *b.covariance;
  // Each entry relative to its pair's scale sqrt(C_aa C_bb) (a in um, b in nm).
  const auto differ = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
    double worst = 0.0;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      for (Eigen::Index j = 0; j < x.cols(); ++j)
        worst = std::max(worst, std::abs(x(i, j) - y(i, j)) / std::sqrt(x(i, i) * x(j, j)));
    return worst;
  };
  CHECK(differ(ca.matrix, cb.matrix) <= 1e-12);
  CHECK(std::abs(ca.correlation(0, 1)) > 0.05);  // a cross term to compare
  REQUIRE(ca.contributors.size() == cb.contributors.size());
  CHECK(differ(ca.contributors[0].matrix, cb.contributors[0].matrix) <= 1e-12);  // the density part (hum is tonal)
}

TEST_CASE("a modal path's exact matrix: its closed form equals the Lyapunov solve of its realisation") {
  // Two modal paths (four and three modes) under white forces, one source
  // with correlated channels; outputs in different units.
  const std::string text =
      "name: frame\ngrid: {type: auto, min_hz: 0.1, max_hz: 10000}\n"
      "sources:\n"
      "  - {name: f, unit: N, channels: [F, G], correlation: 0.5, spectrum: {type: flat, level: 1.0e-4}}\n"
      "  - {name: g, unit: N, channels: [F, G], spectrum: {type: flat, level: 4.0e-6}}\n"
      "paths:\n"
      "  - {name: one, type: modal, frequencies_hz: [12, 40, 41, 150], damping: 0.02, input_shapes: {F: [0.3, "
      "-0.5, 0.2, 0.7], G: [0.1, 0.4, -0.6, 0.2]}, output_shapes: {z: [1.0, 0.5, -0.3, 0.2], w: [-0.4, 0.9, 0.6, "
      "-0.1]}, input_unit: N, output_unit: m}\n"
      "  - {name: two, type: modal, frequencies_hz: [20, 90, 300], damping: 0.01, input_shapes: {F: [0.5, 0.2, "
      "-0.3], G: [0.2, -0.7, 0.4]}, output_shapes: {z: [0.6, -0.2, 0.3], w: [0.8, 0.4, -0.5]},"
      " input_unit: N, output_unit: m}\n"
      "contributors:\n  - {name: one, source: f, path: one}\n  - {name: two, source: g, path: two}\n"
      "outputs:\n  - {name: z, signal: z, unit: um}\n  - {name: w, signal: w, unit: nm}\n"
      "covariance: [z, w]\n";
  const BudgetResult r = Evaluate(LoadBudgetText(text, "m.yaml"));
  REQUIRE(r.covariance.has_value());
  REQUIRE(r.covariance->exact_matrix.has_value());
  const Eigen::MatrixXd& exact = *r.covariance->exact_matrix;
  // Independently: each path's 2n-state realisation through the Lyapunov
  // solver, W = S0 C / 2 (C the channels' correlation), um and nm.
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(2, 2);
  const std::pair<const char*, Eigen::Matrix2d> parts[] = {
      {"one", (Eigen::Matrix2d() << 1.0, 0.5, 0.5, 1.0).finished() * 1.0e-4 / 2},
      {"two", Eigen::Matrix2d::Identity() * 4.0e-6 / 2}};
  Eigen::VectorXd to_units(2);  // m -> um, m -> nm
  to_units << 1e6, 1e9;
  for (const auto& part : parts) {
    const Path& path = r.paths.at(part.first)->path();
    const StateSpace rows = path.Rational().SelectOutputs({path.OutputIndex("z"), path.OutputIndex("w")});
    const Eigen::MatrixXd x = OutputCovariance(rows, part.second);
    dense += to_units.asDiagonal() * x * to_units.asDiagonal();
  }
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      CAPTURE(a);
      CAPTURE(b);
      CHECK(std::abs(exact(a, b) - dense(a, b)) <= 1e-9 * std::sqrt(dense(a, a) * dense(b, b)));
    }
  CHECK(std::abs(dense(0, 1)) > 1e-2 * std::sqrt(dense(0, 0) * dense(1, 1)));  // correlated: the test can tell
  for (int a = 0; a < 2; ++a)  // the exact variances the engine reports, to rounding
    CHECK(Rel(exact(a, a), *r.outputs[a].contributors[0].exact_variance +
                               *r.outputs[a].contributors[1].exact_variance) <= 1e-14);
}

TEST_CASE("summary.json carries the matrices as the result holds them, and no covariance without a request") {
  const Budget budget = LoadBudgetText(TwoMasses("{type: auto, min_hz: 0.1, max_hz: 1000}"), "c.yaml");
  const BudgetResult r = Evaluate(budget);
  const CovarianceResult& cov = *r.covariance;
  const auto j = nlohmann::json::parse(SummaryJson(r, {}))["covariance"];
  CHECK(j["outputs"] == nlohmann::json({"a", "b"}));
  CHECK(j["units"] == nlohmann::json({"um", "nm"}));
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      CHECK(j["matrix"][a][b].get<double>() == cov.matrix(a, b));
      CHECK(j["correlation"][a][b].get<double>() == cov.correlation(a, b));
      CHECK(j["exact_matrix"][a][b].get<double>() == (*cov.exact_matrix)(a, b));
      CHECK(j["contributors"][1]["matrix"][a][b].get<double>() == cov.contributors[1].matrix(a, b));
    }
  CHECK(j["contributors"][0]["name"] == "force");
  CHECK(j["contributors"][1]["name"] == "hum");
  CHECK_FALSE(j.contains("exact_note"));

  const Budget plain = LoadBudgetText(Oscillator(kOscillatorOutputs, ""), "c.yaml");
  const BudgetResult none = Evaluate(plain);
  CHECK_FALSE(none.covariance.has_value());
  CHECK_FALSE(nlohmann::json::parse(SummaryJson(none, {})).contains("covariance"));
}

TEST_CASE("covariance requests that cannot be met are located errors") {
  const std::string unknown = ErrorOf(Oscillator(kOscillatorOutputs, "covariance: [x, vv]\n"));
  CHECK(Has(unknown, "c.yaml:"));
  CHECK(Has(unknown, "covariance[1]"));
  CHECK(Has(unknown, "no output named 'vv'"));
  CHECK(Has(unknown, "did you mean 'v'"));
  const std::string twice = ErrorOf(Oscillator(kOscillatorOutputs, "covariance: [x, v, x]\n"));
  CHECK(Has(twice, "covariance[2]"));
  CHECK(Has(twice, "named twice"));
  const std::string one = ErrorOf(Oscillator(kOscillatorOutputs, "covariance: [x]\n"));
  CHECK(Has(one, "covariance"));
  CHECK(Has(one, "at least 2 outputs, got 1"));
  const std::string scalar = ErrorOf(Oscillator(kOscillatorOutputs, "covariance: x\n"));
  CHECK(Has(scalar, "covariance"));
  CHECK(Has(scalar, "lists the names of 2 or more outputs"));
  const std::string metric = ErrorOf(Oscillator(
      kOscillatorOutputs + "  - {name: x_ma, signal: x, unit: um, metric: {type: moving_average, window_s: 0.01}}\n",
      "covariance: [x, x_ma]\n"));
  CHECK(Has(metric, "covariance[1]"));
  CHECK(Has(metric, "moving_average metric and no covariance"));
}

}  // namespace deb
