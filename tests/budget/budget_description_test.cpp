#include "deb/budget/budget_description.h"

#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <vector>

#include "deb/spectra/flat_spectrum.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Source a (white, N) through a stable and an unstable first-order path, one output y.
Budget Example() {
  Budget b;
  b.name = "described";
  b.description = "two paths";
  b.grid.range_given = true;
  b.grid.auto_options.min_hz = 0.1;
  b.grid.auto_options.max_hz = 100.0;
  Source s;
  s.name = "a";
  s.unit = "N";
  s.channel_names = {"u"};
  s.spectrum = std::make_shared<FlatSpectrum>(1.0);
  b.sources = {s};
  const auto path = [](const std::string& name, double pole) {
    Path p;
    p.name = name;
    p.system = ToStateSpace(TransferFunction({1.0}, {1.0, pole}));
    p.input_names = {"u"};
    p.output_names = {"y"};
    p.input_units = {"N"};
    p.output_units = {"um"};
    return p;
  };
  b.paths = {path("lowpass", 10.0), path("runaway", -10.0), path("integrator", 0.0)};
  b.contributors = {{"ca", "a", "lowpass", ExactVariance::kAuto, {}, {}, false}};
  Output o;
  o.name = "y";
  o.signal = "y";
  o.unit = "um";
  o.rms_max = 2.0;
  b.outputs = {o};
  return b;
}

}  // namespace

TEST_CASE("a budget is described section by section: grid, sources, paths, contributors, outputs") {
  const Budget b = Example();
  const std::string text = DescribeBudget(b, PlanEvaluation(b));
  CHECK(text.rfind("budget described: valid\n  two paths\ngrid: ", 0) == 0);
  CHECK(Has(text, "\nsources:\n  a                    1 channel(s) in N: "));
  CHECK(Has(text, "\npaths:\n  lowpass              1 input(s) -> 1 output(s), 1 state(s), stable\n"));
  CHECK(
      Has(text, "  runaway              1 input(s) -> 1 output(s), 1 state(s), unstable: no contributor may use it\n"));
  CHECK(Has(text, "  integrator           1 input(s) -> 1 output(s), 1 state(s), marginally stable (integrator: 1 "
                  "pole(s) at 0; close a loop around it)\n"));
  CHECK(Has(text, "\ncontributors:\n  ca                   source a, path lowpass, exact variance: auto\n"));
  CHECK(Has(text, "\noutputs:\n  y                    signal y in um, rms_max 2\n"));
  CHECK_FALSE(Has(text, "feedback loops:"));
  CHECK(text.back() == '\n');
}

TEST_CASE("a sweep is described by its mode, variant count and each parameter's first and last value") {
  SweepSpec spec;
  SweepParameter h{"paths[0].h", {0, -100, -200}, {}, {}, {}, {}};
  h.label = "height";
  h.unit = "mm";
  spec.parameters = {h};
  const std::string text = DescribeSweep(spec, 3);
  CHECK(text.rfind("sweep: grid of 1 parameter(s), 3 variants, each valid:\n", 0) == 0);
  CHECK(Has(text, "  paths[0].h"));
  CHECK(Has(text, "3 value(s): 0 ... -200 ("));
}

}  // namespace deb
