// Tonal sources: each tone propagated exactly as |H(j 2 pi f0) a|^2, against
// the closed form of the path; coherent channels; the CPS steps at f0 and a
// band (lo, hi] holds the tones inside it; bad tones are located errors.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using Complex = std::complex<double>;

// A second-order low-pass, 20 Hz, zeta 0.25: H = wn^2 / (s^2 + 2 zeta wn s + wn^2).
const double kWn = 2 * M_PI * 20.0, kZeta = 0.25;
Complex H(double f_hz) {
  const Complex s(0.0, 2 * M_PI * f_hz);
  return kWn * kWn / (s * s + 2 * kZeta * kWn * s + kWn * kWn);
}

std::string ToneBudget(const std::string& tones, const std::string& extra_source = "",
                   const std::string& grid = "{type: auto, min_hz: 1, max_hz: 1000}") {
  char num[64], den[96];
  std::snprintf(num, sizeof num, "[%.17g]", kWn * kWn);
  std::snprintf(den, sizeof den, "[1, %.17g, %.17g]", 2 * kZeta * kWn, kWn * kWn);
  return "name: tones\ngrid: " + grid + "\nsources:\n" + tones + extra_source +
         "paths:\n  - {name: lowpass, type: transfer_function, num: " + num + ", den: " + den +
         ", input_unit: um/s, output_unit: um/s, outputs: [v]}\n"
         "  - {name: sum, type: state_space, A: [[-1]], B: [[0, 0]], C: [[0]], D: [[1, 1]], inputs: [a, b],"
         " input_unit: um/s, output_unit: um/s, outputs: [v]}\n"
         "contributors:\n  - {name: mains, source: mains, path: lowpass}\n" +
         (extra_source.empty() ? "" : "  - {name: noise, source: noise, path: lowpass}\n") +
         "outputs:\n  - {name: velocity, signal: v, unit: um/s}\nbands: [[1, 40], [40, 100], [100, 1000]]\n";
}

const std::string kTwoTones =
    "  - name: mains\n    unit: um/s\n    spectrum:\n      type: tones\n      tones:\n"
    "        - {f_hz: 50, rms: 0.2}\n        - {f_hz: 150, peak: 0.1}\n";

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { Evaluate(LoadBudgetText(text, "t.yaml")); });
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a tone through a transfer function gives |H(f0)|^2 A^2; the CPS steps at f0; bands hold their tones") {
  const BudgetResult r = Evaluate(LoadBudgetText(ToneBudget(kTwoTones), "t.yaml"));
  const ContributorResult& c = r.outputs[0].contributors[0];
  const double v50 = std::norm(H(50)) * 0.04, v150 = std::norm(H(150)) * 0.005;  // peak 0.1 is rms 0.1/sqrt(2)
  CHECK(std::abs(c.variance / (v50 + v150) - 1.0) < 1e-12);
  REQUIRE(c.exact_variance.has_value());
  CHECK(std::abs(*c.exact_variance / (v50 + v150) - 1.0) < 1e-12);
  REQUIRE(c.tones.size() == 2);
  CHECK(std::abs(c.tones[0].variance / v50 - 1.0) < 1e-12);
  // No density: the CPS is 0 below 50 Hz, v50 from 50 Hz to below 150 Hz, then both.
  const std::vector<double>& f = r.grid.f_hz();
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double expected = (f[k] >= 50 ? v50 : 0.0) + (f[k] >= 150 ? v150 : 0.0);
    CHECK(std::abs(c.cps[k] - expected) <= 1e-15 + 1e-12 * expected);
  }
  const auto& bands = r.outputs[0].bands;
  REQUIRE(bands.size() == 3);
  CHECK(bands[0].contributor_variance[0] == 0.0);
  CHECK(std::abs(bands[1].contributor_variance[0] / v50 - 1.0) < 1e-12);
  CHECK(std::abs(bands[2].contributor_variance[0] / v150 - 1.0) < 1e-12);
}

TEST_CASE("tones add to a random contributor as uncorrelated terms; a band edge between grid points splits them exactly") {
  const std::string noise = "  - {name: noise, unit: um/s, spectrum: {type: flat, level: 1.0e-4}}\n";
  const BudgetResult both = Evaluate(LoadBudgetText(ToneBudget(kTwoTones, noise), "t.yaml"));
  const BudgetResult tones = Evaluate(LoadBudgetText(ToneBudget(kTwoTones), "t.yaml"));
  const auto& o = both.outputs[0];
  CHECK(std::abs(o.variance - (o.contributors[0].variance + o.contributors[1].variance)) <= 1e-15 * o.variance);
  CHECK(std::abs(o.contributors[0].variance / tones.outputs[0].contributors[0].variance - 1.0) < 1e-12);
  // Band figures of the tonal contributor do not depend on where the band's edges fall between grid points.
  const double v50 = std::norm(H(50)) * 0.04;
  CHECK(std::abs(ContributorVarianceBetween(both.grid, o.contributors[0], 49.999, 50.0) / v50 - 1.0) < 1e-12);
  CHECK(ContributorVarianceBetween(both.grid, o.contributors[0], 50.0, 50.001) == 0.0);
}

TEST_CASE("a tone on the grid's first or last point is in the bands that start or end there") {
  // 1 um/s RMS at 2 Hz on a grid from 2 Hz, 0.5 um/s RMS at 100 Hz on its last point, through a unit
  // gain: the lowest band is closed at the grid's start ([2, 5] holds the 2 Hz tone), (lo, hi] holds the
  // other; so do the default decade bands, which add up to the total.
  const std::string text =
      "name: ends\ngrid: {type: auto, min_hz: 2, max_hz: 100}\nsources:\n"
      "  - name: hum\n    unit: um/s\n    spectrum:\n      type: tones\n      tones:\n"
      "        - {f_hz: 2, rms: 1}\n        - {f_hz: 100, rms: 0.5}\n"
      "paths:\n  - {name: unity, type: state_space, A: [[-1]], B: [[0]], C: [[0]], D: [[1]], input_unit: um/s,"
      " output_unit: um/s, outputs: [v]}\n"
      "contributors:\n  - {name: hum, source: hum, path: unity}\n"
      "outputs:\n  - name: velocity\n    signal: v\n    unit: um/s\n    band_requirements:\n"
      "      - {lo_hz: 2, hi_hz: 5, rms_max: 0.5}\n      - {lo_hz: 50, hi_hz: 100, rms_max: 1}\n";
  const BudgetResult r = Evaluate(LoadBudgetText(text, "t.yaml"));
  const OutputResult& o = r.outputs[0];
  CHECK(std::abs(o.variance - 1.25) < 1e-12);
  REQUIRE(o.band_requirements.size() == 2);
  CHECK(std::abs(o.band_requirements[0].variance - 1.0) < 1e-12);
  CHECK_FALSE(o.band_requirements[0].pass());
  CHECK(std::abs(o.band_requirements[1].variance - 0.25) < 1e-12);
  REQUIRE(o.bands.size() == 2);  // [2, 10] and [10, 100]
  CHECK(std::abs(o.bands[0].variance - 1.0) < 1e-12);
  CHECK(std::abs(o.bands[1].variance - 0.25) < 1e-12);
  // Inside the grid the rule stays (lo, hi]: a band from 2 Hz is closed only because the grid starts there.
  CHECK(ContributorVarianceBetween(r.grid, o.contributors[0], 2.0, 2.5) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(ContributorVarianceBetween(r.grid, o.contributors[0], 99.0, 100.0) == doctest::Approx(0.25).epsilon(1e-12));
  CHECK(ContributorVarianceBetween(r.grid, o.contributors[0], 100.0, 100.0) == 0.0);
}

TEST_CASE("channels of a tone are coherent: equal amplitudes cancel at 180 degrees and add in quadrature at 90") {
  const auto sum_of = [](const std::string& phases) {
    const std::string src = "  - name: mains\n    unit: um/s\n    channels: [a, b]\n    spectrum:\n      type: tones\n"
                            "      tones:\n        - {f_hz: 30, rms: 0.5, phase_deg: " + phases + "}\n";
    std::string text = ToneBudget(src);
    text.replace(text.find("path: lowpass}"), 14, "path: sum}");
    return Evaluate(LoadBudgetText(text, "t.yaml")).outputs[0].contributors[0].variance;
  };
  CHECK(sum_of("[0, 0]") == doctest::Approx(1.0).epsilon(1e-12));   // |0.5 + 0.5|^2
  CHECK(std::abs(sum_of("[0, 180]")) < 1e-30);                       // 0.5 - 0.5
  CHECK(sum_of("[0, 90]") == doctest::Approx(0.5).epsilon(1e-12));  // |0.5 + 0.5 j|^2
}

TEST_CASE("a tone in a unit that differs by a time derivative is converted at its frequency") {
  // 1 nm RMS of displacement at 50 Hz is 2 pi 50 nm/s = 0.314159 um/s of velocity.
  const std::string src = "  - name: mains\n    unit: nm\n    spectrum: {type: tones, tones: [{f_hz: 50, rms: 1}]}\n";
  const double v = Evaluate(LoadBudgetText(ToneBudget(src), "t.yaml")).outputs[0].contributors[0].variance;
  CHECK(std::abs(v / (std::norm(H(50)) * std::pow(2 * M_PI * 50 * 1e-3, 2)) - 1.0) < 1e-12);
}

TEST_CASE("bad tones are located errors: outside the grid, on a pole, twice at one frequency, no amplitude") {
  std::string narrow = ToneBudget(kTwoTones, "", "{type: log, min_hz: 1, max_hz: 100, points: 200}");
  narrow.replace(narrow.find(", [100, 1000]]"), 14, "]");
  const std::string outside = ErrorOf(narrow);
  CHECK(Has(outside, "t.yaml:9:"));  // the tones key
  CHECK(Has(outside, "sources[0].spectrum.tones"));
  CHECK(Has(outside, "the tone at 150 Hz of source 'mains' lies outside the frequency grid"));
  const std::string twice = ErrorOf(
      "name: x\nsources:\n  - name: mains\n    unit: um/s\n    spectrum: {type: tones, tones: [{f_hz: 50, rms: 1}, "
      "{f_hz: 50, rms: 2}]}\npaths:\n  - {name: p, type: gain, gain: [[1]], input_unit: um/s, output_unit: um/s, "
      "outputs: [v]}\ncontributors:\n  - {name: c, source: mains, path: p}\noutputs:\n  - {name: o, signal: v, "
      "unit: um/s}\n");
  CHECK(Has(twice, "two tones at 50 Hz"));
  std::string no_amp = kTwoTones;
  no_amp.replace(no_amp.find("rms: 0.2"), 8, "f: 0.2");
  CHECK(Has(ErrorOf(ToneBudget(no_amp)), "unknown key"));
  std::string both = kTwoTones;
  both.replace(both.find("rms: 0.2"), 8, "rms: 0.2, peak: 0.3");
  CHECK(Has(ErrorOf(ToneBudget(both)), "give the tone's amplitude as rms or as peak"));
  std::string wrong_count = kTwoTones;
  wrong_count.replace(wrong_count.find("rms: 0.2"), 8, "rms: [0.2, 0.1]");
  CHECK(Has(ErrorOf(ToneBudget(wrong_count)), "2 value(s) for 1 channel(s)"));
  // An undamped path resonating exactly at the tone: a pole at f0.
  const std::string pole =
      "name: x\nsources:\n  - name: mains\n    unit: um/s\n    spectrum: {type: tones, tones: [{f_hz: 1, rms: 1}]}\n"
      "paths:\n  - {name: p, type: transfer_function, num: [1], den: [1, 0, 39.47841760435743], input_unit: um/s, "
      "output_unit: um/s, outputs: [v]}\ncontributors:\n  - {name: c, source: mains, path: p}\noutputs:\n"
      "  - {name: o, signal: v, unit: um/s}\ngrid: {type: log, min_hz: 0.1, max_hz: 10, points: 100}\n";
  const std::string on_pole = ErrorOf(pole);
  CHECK((Has(on_pole, "pole") || Has(on_pole, "non-finite")));
}

}  // namespace deb
