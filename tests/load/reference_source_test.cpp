// Budget sources of `type: reference`: Peterson's NLNM / NHNM in the source's unit.
#include <doctest/doctest.h>

#include <cmath>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Periods 0.2, 0.25, 1, 2 s.
const char* kBudget = R"(name: quiet_site
grid: {type: explicit, f_hz: [0.5, 1, 4, 5]}
sources:
  - name: ground
    spectrum: {type: reference, model: nlnm}
paths:
  - {name: g, type: gain, gain: 1, input_unit: m/s^2, output_unit: m/s^2, outputs: [z]}
contributors:
  - {name: ground, source: ground, path: g}
outputs:
  - {name: z, signal: z, unit: m/s^2}
)";

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { Evaluate(LoadBudgetText(text, "b.yaml", ".")); });
}

double FromDb(double db) { return std::pow(10.0, db / 10.0); }

TEST_CASE("a reference source is Peterson's acceleration PSD: A + B log10(P) dB from OFR 93-322 (rel 1e-12)") {
  const Budget b = LoadBudgetText(kBudget, "b.yaml", ".");
  CHECK(b.sources[0].unit == "m/s^2");
  CHECK(b.sources[0].channel_names == std::vector<std::string>{"ground"});
  const BudgetResult r = Evaluate(b);
  const std::vector<double>& psd = r.outputs[0].total_psd;
  // NLNM rows of spectra/peterson_1993_noise_models.csv: P = 2 s in 1.24-2.40
  // (-168.60, 52.48), 1 s in 0.80-1.24 (-166.40, 28.90), 0.25 s and 0.2 s in
  // 0.17-0.40 (-166.70, 0).
  CHECK(psd[0] == doctest::Approx(FromDb(-168.60 + 52.48 * std::log10(2.0))).epsilon(1e-12));
  CHECK(psd[1] == doctest::Approx(FromDb(-166.40)).epsilon(1e-12));
  CHECK(psd[2] == doctest::Approx(FromDb(-166.70)).epsilon(1e-12));
  CHECK(psd[3] == doctest::Approx(FromDb(-166.70)).epsilon(1e-12));

  // NHNM: 1 s in 0.80-3.80 (-116.85, 32.51), 0.25 s in 0.22-0.32 (-150.34, -80.50).
  const BudgetResult high = Evaluate(LoadBudgetText(Replace(kBudget, "model: nlnm", "model: NHNM"), "b.yaml", "."));
  CHECK(high.outputs[0].total_psd[1] == doctest::Approx(FromDb(-116.85)).epsilon(1e-12));
  CHECK(high.outputs[0].total_psd[2] == doctest::Approx(FromDb(-150.34 - 80.50 * std::log10(0.25))).epsilon(1e-12));
}

TEST_CASE("unit: um/s gives the velocity PSD, the acceleration PSD x 1e12 / (2 pi f)^2, as the engine's own conversion") {
  const std::string velocity_text =
      Replace(Replace(Replace(kBudget, "  - name: ground\n", "  - name: ground\n    unit: um/s\n"),
                      "input_unit: m/s^2, output_unit: m/s^2", "input_unit: um/s, output_unit: um/s"),
              "unit: m/s^2}", "unit: um/s}");
  const Budget velocity = LoadBudgetText(velocity_text, "b.yaml", ".");
  CHECK(velocity.sources[0].unit == "um/s");
  CHECK(velocity.sources[0].spectrum->Describe().find("] in um/s (scale 1e+06, integrated once in time)") !=
        std::string::npos);
  const BudgetResult v = Evaluate(velocity);
  const BudgetResult a = Evaluate(LoadBudgetText(kBudget, "b.yaml", "."));
  // The acceleration source read through a path in um/s: deb converts at the connection.
  const BudgetResult through = Evaluate(LoadBudgetText(
      Replace(Replace(kBudget, "input_unit: m/s^2, output_unit: m/s^2", "input_unit: um/s, output_unit: um/s"),
              "unit: m/s^2}", "unit: um/s}"),
      "b.yaml", "."));
  const std::vector<double> f_hz = {0.5, 1.0, 4.0, 5.0};
  for (std::size_t k = 0; k < f_hz.size(); ++k) {
    CAPTURE(f_hz[k]);
    const double w = 2.0 * kPi * f_hz[k];
    CHECK(v.outputs[0].total_psd[k] == doctest::Approx(a.outputs[0].total_psd[k] * 1e12 / (w * w)).epsilon(1e-12));
    CHECK(v.outputs[0].total_psd[k] == doctest::Approx(through.outputs[0].total_psd[k]).epsilon(1e-12));
  }
  CHECK(ErrorOf(Replace(kBudget, "  - name: ground\n", "  - name: ground\n    unit: urad\n"))
            .find("b.yaml:5:11: sources[0].unit: cannot convert 'm/s^2' to 'urad'") == 0);
}

TEST_CASE("outside 0.1-100000 s: an error by default, or zero, or the model's end value held; corners feed the grid") {
  const std::string wide = Replace(kBudget, "f_hz: [0.5, 1, 4, 5]", "f_hz: [0.5, 1, 4, 5, 20]");
  const std::string outside = ErrorOf(wide);
  CHECK(outside.find("source 'ground' is defined over [1e-05, 10] Hz only (extrapolation: error), but the frequency "
                     "grid spans [0.5, 20] Hz: keep the grid inside that range, or set the source's extrapolation "
                     "(hold or zero)") != std::string::npos);
  const BudgetResult zero =
      Evaluate(LoadBudgetText(Replace(wide, "model: nlnm", "model: nlnm, extrapolation: zero"), "b.yaml", "."));
  CHECK(zero.outputs[0].total_psd[4] == 0.0);
  // Hold keeps the model's acceleration (the physics does not change with the
  // source's unit); in um/s it falls as 1/(2 pi f)^2 beyond 10 Hz.
  const std::string hold_velocity = Replace(
      Replace(Replace(Replace(wide, "model: nlnm", "model: nlnm, extrapolation: hold"), "  - name: ground\n",
                      "  - name: ground\n    unit: um/s\n"),
              "input_unit: m/s^2, output_unit: m/s^2", "input_unit: um/s, output_unit: um/s"),
      "unit: m/s^2}", "unit: um/s}");
  const BudgetResult hold = Evaluate(LoadBudgetText(hold_velocity, "b.yaml", "."));
  const double w = 2.0 * kPi * 20.0;
  CHECK(hold.outputs[0].total_psd[4] == doctest::Approx(FromDb(-162.36 + 5.64 * std::log10(0.1)) * 1e12 / (w * w))
                                           .epsilon(1e-12));

  // Automatic grid over 0.1-10 Hz: points hug the NLNM corner at 0.8 s (1.25 Hz).
  const Budget automatic =
      LoadBudgetText(Replace(kBudget, "grid: {type: explicit, f_hz: [0.5, 1, 4, 5]}", "grid: {min_hz: 0.1, max_hz: 10}"),
                     "b.yaml", ".");
  const FrequencyGrid grid = BuildGrid(automatic);
  double nearest = 1.0;
  for (double f : grid.f_hz()) nearest = std::min(nearest, std::abs(f / 1.25 - 1.0));
  CHECK(nearest < 1e-4);
  CHECK(Evaluate(automatic).outputs[0].variance > 0.0);
}

TEST_CASE("a reference source rejects a missing or unknown model, a convention and unknown keys, with file:line:col") {
  CHECK(ErrorOf(Replace(kBudget, "model: nlnm", "model: mlnm")) ==
        "b.yaml:5:40: sources[0].spectrum.model: unknown Peterson noise model 'mlnm'; allowed: nlnm, nhnm");
  CHECK(ErrorOf(Replace(kBudget, "model: nlnm", "model: nlnm, extrapolation: clamp"))
            .find("b.yaml:5:61: sources[0].spectrum.extrapolation: unknown extrapolation 'clamp'") == 0);
  CHECK(ErrorOf(Replace(kBudget, "  - name: ground\n", "  - name: ground\n    convention: two-sided\n"))
            .find("sources[0].convention: a reference model is a one-sided PSD by definition") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "model: nlnm", "model: nlnm, file: x.csv")).find("unknown key 'file'") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "type: reference, model: nlnm", "type: reference")) ==
        "b.yaml:5:15: sources[0].spectrum: missing required key 'model'");
}

}  // namespace
}  // namespace deb
