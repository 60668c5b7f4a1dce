#include "deb/budget/allocation.h"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/scaled_spectrum.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

Source White(const std::string& name, double level) {
  Source s;
  s.name = name;
  s.unit = "N";
  s.channel_names = {"u"};
  s.spectrum = std::make_shared<FlatSpectrum>(level);
  return s;
}

Path Plant(const std::string& name, std::vector<double> num, std::vector<double> den) {
  Path p;
  p.name = name;
  p.system = ToStateSpace(TransferFunction(std::move(num), std::move(den)));
  p.input_names = {"u"};
  p.output_names = {"y"};
  p.input_units = {"N"};
  p.output_units = {"um"};
  return p;
}

// Two uncorrelated contributors on one output: a resonance at 5 Hz and a low-pass.
Budget TwoContributors(double rms_max) {
  Budget b;
  b.name = "allocation";
  b.grid.range_given = true;
  b.grid.auto_options.min_hz = 0.1;
  b.grid.auto_options.max_hz = 1000.0;
  b.sources = {White("a", 2.0), White("b", 0.5)};
  const double w = 2.0 * 3.141592653589793 * 5.0;
  b.paths = {Plant("resonance", {w * w}, {1.0, 0.04 * w, w * w}), Plant("lowpass", {20.0}, {1.0, 20.0})};
  b.contributors = {{"ca", "a", "resonance", ExactVariance::kAuto, {}, {}, false},
                    {"cb", "b", "lowpass", ExactVariance::kAuto, {}, {}, false}};
  Output o;
  o.name = "y";
  o.signal = "y";
  o.unit = "um";
  o.rms_max = rms_max;
  b.outputs = {o};
  return b;
}

// The output RMS after multiplying source `s` by k.
double RmsWithScaledSource(Budget b, std::size_t s, double k) {
  b.sources[s].spectrum = std::make_shared<ScaledSpectrum>(b.sources[s].spectrum, k);
  return Evaluate(b).outputs[0].rms();
}

}  // namespace

TEST_CASE("scaling a source by its allocation factor puts the output exactly at the limit (1e-6 relative)") {
  const BudgetResult nominal = Evaluate(TwoContributors(1.0));
  const OutputResult& o = nominal.outputs[0];
  REQUIRE(o.contributors.size() == 2);
  // A limit that lets both grow and one that forces them to shrink.
  int checked = 0;
  for (const double fraction : {1.5, 0.97}) {
    const double limit = fraction * o.rms();
    const Budget b = TwoContributors(limit);
    const OutputResult r = Evaluate(b).outputs[0];
    for (std::size_t c = 0; c < 2; ++c) {
      const Allocation a = AllocationFactor(r, c);
      if (!a.factor) continue;  // the other contributor alone exceeds this limit
      CAPTURE(limit);
      CAPTURE(c);
      CHECK(*a.factor > 0.0);
      CHECK(((*a.factor > 1.0) == r.pass()));
      CHECK(std::abs(RmsWithScaledSource(b, c, *a.factor) - limit) / limit < 1e-6);
      ++checked;
    }
  }
  CHECK(checked >= 3);
}

TEST_CASE("a limit below what the other contributors give alone has no allocation factor, with the reason") {
  const OutputResult nominal = Evaluate(TwoContributors(1.0)).outputs[0];
  const double ca = std::sqrt(nominal.contributors[0].variance), cb = std::sqrt(nominal.contributors[1].variance);
  const double limit = 0.9 * std::min(ca, cb);  // each of the two alone exceeds it
  const OutputResult r = Evaluate(TwoContributors(limit)).outputs[0];
  for (std::size_t c = 0; c < 2; ++c) {
    const Allocation a = AllocationFactor(r, c);
    CHECK_FALSE(a.factor.has_value());
    CHECK(a.note.find("other contributors alone") != std::string::npos);
  }
}

TEST_CASE("an output without a requirement has no allocation factor") {
  Budget b = TwoContributors(1.0);
  b.outputs[0].rms_max.reset();
  const Allocation a = AllocationFactor(Evaluate(b).outputs[0], 0);
  CHECK_FALSE(a.factor.has_value());
  CHECK(a.note == "no requirement");
}

TEST_CASE("the allocation factor follows the closed form (limit^2 - others) / own") {
  OutputResult o;
  o.rms_max = 5.0;
  o.contributors.resize(2);
  o.contributors[0].variance = 9.0;
  o.contributors[1].variance = 16.0;
  o.variance = 25.0;
  CHECK(*AllocationFactor(o, 0).factor == doctest::Approx(1.0).epsilon(1e-15));
  o.rms_max = 6.0;
  CHECK(*AllocationFactor(o, 0).factor == doctest::Approx(20.0 / 9.0).epsilon(1e-15));
  CHECK(*AllocationFactor(o, 1).factor == doctest::Approx(27.0 / 16.0).epsilon(1e-15));
  o.rms_max = 3.0;
  CHECK_FALSE(AllocationFactor(o, 0).factor.has_value());  // 16 alone > 9
  CHECK_FALSE(AllocationFactor(o, 1).factor.has_value());  // 9 alone reaches 9: k would be 0
}

TEST_CASE("a band requirement holds the output's RMS within the band and fails on its own") {
  Budget b = TwoContributors(1e6);  // the whole-grid requirement passes
  b.bands = {{1.0, 10.0}};
  b.outputs[0].band_requirements = {{1.0, 10.0, 1e6}, {3.0, 7.0, 1e-9}};
  const OutputResult r = Evaluate(b).outputs[0];
  REQUIRE(r.band_requirements.size() == 2);
  // The same band integrals as the band table's.
  CHECK(r.band_requirements[0].variance == doctest::Approx(r.bands[0].variance).epsilon(1e-14));
  CHECK(r.band_requirements[0].variance < r.variance);
  CHECK(r.band_requirements[0].pass());
  CHECK_FALSE(r.band_requirements[1].pass());
  CHECK(r.pass());           // whole grid
  CHECK_FALSE(r.AllPass());  // but not the 3-7 Hz band
  b.outputs[0].band_requirements = {{1.0, 1e5, 1.0}};
  CHECK_THROWS_WITH_AS(Evaluate(b), doctest::Contains("extends beyond the frequency grid"), InputError);
}

TEST_CASE("a source shared by two contributors has a joint factor that puts the output at the limit (1e-6)") {
  // Source a feeds both paths; each contributor's own factor assumes the other
  // stays, which scaling the shared source does not do.
  Budget b = TwoContributors(1.0);
  b.contributors[1].source = "a";
  const double nominal = Evaluate(b).outputs[0].rms();
  for (const double fraction : {1.5, 0.9}) {
    b.outputs[0].rms_max = fraction * nominal;
    const OutputResult r = Evaluate(b).outputs[0];
    const Allocation joint = SourceAllocationFactor(r, {0, 1});
    REQUIRE(joint.factor.has_value());
    CHECK(*joint.factor == doctest::Approx(fraction * fraction).epsilon(1e-12));  // everything scales together
    CHECK(std::abs(RmsWithScaledSource(b, 0, *joint.factor) - *b.outputs[0].rms_max) / *b.outputs[0].rms_max < 1e-6);
    const Allocation own = AllocationFactor(r, 0);
    REQUIRE(own.factor.has_value());
    CHECK(std::abs(RmsWithScaledSource(b, 0, *own.factor) - *b.outputs[0].rms_max) / *b.outputs[0].rms_max > 1e-3);
  }
}

}  // namespace deb
