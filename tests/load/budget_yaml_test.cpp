#include "deb/load/budget_yaml.h"

#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

// A valid budget; tests replace one line to break one rule at a time.
const char* kBudget = R"(name: unit_test
grid: {type: log, min_hz: 0.1, max_hz: 100, points: 200}
sources:
  - name: noise
    unit: um/s
    spectrum: {type: flat, level: 2}
paths:
  - name: lowpass
    type: transfer_function
    num: [1]
    den: [0.01, 1]
    input_unit: um/s
    output_unit: um/s
    outputs: [v]
contributors:
  - {name: sensor, source: noise, path: lowpass}
outputs:
  - {name: velocity, signal: v, unit: um/s}
bands:
  - [1, 10]
)";

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { LoadBudgetText(text, "b.yaml"); });
}

}  // namespace

TEST_CASE("a valid budget loads with every section") {
  const Budget b = LoadBudgetText(kBudget, "b.yaml");
  CHECK(b.name == "unit_test");
  CHECK(b.grid.kind == GridKind::kLog);
  CHECK(b.grid.points == 200);
  REQUIRE(b.sources.size() == 1);
  CHECK(b.sources[0].spectrum->Psd(3.0)(0) == 2.0);
  CHECK(b.paths[0].output_names[0] == "v");
  CHECK(b.paths[0].input_names[0] == "u");
  CHECK(b.bands.size() == 1);
}

TEST_CASE("a flat level without quantity: is read as a PSD and says so, as a measured file does") {
  const Budget b = LoadBudgetText(kBudget, "b.yaml");
  REQUIRE(b.sources[0].notes.size() == 1);
  CHECK(b.sources[0].notes[0] ==
        "the flat level 2 has no 'quantity:', so it is read as a PSD in (um/s)^2/Hz; if it is an ASD in "
        "(um/s)/sqrt(Hz), add 'quantity: asd' (or 'quantity: psd' to confirm)");
  const Budget confirmed = LoadBudgetText(Replace(kBudget, "level: 2}", "level: 2, quantity: psd}"), "b.yaml");
  CHECK(confirmed.sources[0].notes.empty());
  CHECK(confirmed.sources[0].spectrum->Psd(1.0)(0) == b.sources[0].spectrum->Psd(1.0)(0));
}

TEST_CASE("a two-sided level is doubled and an ASD level squared at load") {
  auto text = Replace(kBudget, "    unit: um/s\n    spectrum: {type: flat, level: 2}",
                      "    unit: um/s\n    convention: two-sided\n    spectrum: {type: flat, level: 3, quantity: asd}");
  const Budget b = LoadBudgetText(text, "b.yaml");
  CHECK(b.sources[0].spectrum->Psd(1.0)(0) == doctest::Approx(18.0).epsilon(1e-15));
}

TEST_CASE("an unknown key is rejected with its position and the allowed keys") {
  const std::string e = ErrorOf(Replace(kBudget, "    outputs: [v]", "    outputs: [v]\n    gain: 3"));
  CHECK(e.find("b.yaml:15:5: paths[0].gain: unknown key 'gain'; allowed here:") == 0);
  CHECK(e.find("num") != std::string::npos);
}

TEST_CASE("a negative PSD level names file, line, column, key and value") {
  CHECK(ErrorOf(Replace(kBudget, "level: 2", "level: -2")) ==
        "b.yaml:6:35: sources[0].spectrum.level: value -2 must be >= 0");
}

TEST_CASE("a non-numeric value is reported as such") {
  CHECK(ErrorOf(Replace(kBudget, "den: [0.01, 1]", "den: [0.01, one]")) ==
        "b.yaml:11:17: paths[0].den[1]: expected a number, got 'one': unknown name 'one' (no parameters are "
        "defined)");
}

TEST_CASE("a number outside the range of normal doubles says which end it is beyond") {
  CHECK(ErrorOf(Replace(kBudget, "level: 2", "level: 1e-320")) ==
        "b.yaml:6:35: sources[0].spectrum.level: value '1e-320' is below the smallest normal double, 2.2e-308: "
        "write 0, or check its unit");
  CHECK(ErrorOf(Replace(kBudget, "level: 2", "level: 1e400")) ==
        "b.yaml:6:35: sources[0].spectrum.level: value '1e400' is beyond the largest double, 1.8e308");
}

TEST_CASE("a non-finite value is rejected") {
  CHECK(ErrorOf(Replace(kBudget, "level: 2", "level: .nan")).find("is not finite") != std::string::npos);
}

TEST_CASE("non-increasing explicit grid frequencies are rejected") {
  const std::string e =
      ErrorOf(Replace(kBudget, "{type: log, min_hz: 0.1, max_hz: 100, points: 200}", "{type: explicit, f_hz: [1, 3, 2]}"));
  CHECK(e == "b.yaml:2:30: grid.f_hz: frequency grid: frequencies must increase strictly, but [1] = 3 Hz >= [2] = 2 Hz");
}

TEST_CASE("a contributor naming an unknown source points at its key") {
  CHECK(ErrorOf(Replace(kBudget, "source: noise", "source: nois")) ==
        "b.yaml:16:28: contributors[0].source: no source named 'nois' (did you mean 'noise'?)");
}

TEST_CASE("a contributor may not be called total: that name is the sum in every table") {
  CHECK(ErrorOf(Replace(kBudget, "name: sensor,", "name: total,")) ==
        "b.yaml:16:12: contributors[0].name: contributor name 'total' is reserved for the sum of all contributors");
}

TEST_CASE("a source whose channel count differs from the path's inputs is rejected") {
  const std::string e = ErrorOf(Replace(kBudget, "    unit: um/s\n    spectrum", "    unit: um/s\n    channels: [a, b]\n    spectrum"));
  CHECK(e.find("contributors[0]: source 'noise' has 2 channel(s) but path 'lowpass' has 1 input(s)") !=
        std::string::npos);
  CHECK(e.find("b.yaml:17:5:") == 0);
}

TEST_CASE("incompatible units are an error naming both units") {
  const std::string e = ErrorOf(Replace(kBudget, "{name: velocity, signal: v, unit: um/s}", "{name: velocity, signal: v, unit: N}"));
  CHECK(e.find("outputs[0].unit:") != std::string::npos);
  CHECK(e.find("'um/s'") != std::string::npos);
  CHECK(e.find("'N'") != std::string::npos);
}

TEST_CASE("an unknown unit string is an error at the unit's position") {
  const std::string e = ErrorOf(Replace(kBudget, "    unit: um/s\n    spectrum", "    unit: umm/s\n    spectrum"));
  CHECK(e.find("b.yaml:5:11: sources[0].unit: unknown unit 'umm/s'") == 0);
}

TEST_CASE("an empty band is an error") {
  CHECK(ErrorOf(Replace(kBudget, "  - [1, 10]", "  - [10, 10]")) ==
        "b.yaml:20:5: bands[0]: band [10, 10] Hz is empty or invalid; need 0 < lo_hz < hi_hz");
}

TEST_CASE("an output reading a signal the path lacks is an error") {
  CHECK(ErrorOf(Replace(kBudget, "signal: v,", "signal: w,")).find(
            "outputs[0].signal: output 'velocity' reads signal 'w', which path 'lowpass'") != std::string::npos);
}

TEST_CASE("invalid YAML syntax is reported with its position") {
  CHECK(ErrorOf("name: [unclosed\n").find("b.yaml:") == 0);
}

TEST_CASE("an unknown enum value lists the allowed values") {
  CHECK(ErrorOf(Replace(kBudget, "type: flat", "type: pink")) ==
        "b.yaml:6:22: sources[0].spectrum.type: unknown spectrum type 'pink'; allowed: flat, vc, measured, "
        "timeseries, reference, tones");
  CHECK(ErrorOf(Replace(kBudget, "path: lowpass}", "path: lowpass, exact: always}")).find(
            "allowed: auto, required, off") != std::string::npos);
}

TEST_CASE("a VC source by its band velocity: a class' velocity in any velocity unit is that class") {
  const auto rms = [](const std::string& spectrum, const std::string& unit) {
    const std::string text = Replace(Replace(kBudget, "{type: flat, level: 2}", spectrum), "unit: um/s\n    spectrum",
                                     "unit: " + unit + "\n    spectrum");
    // The path in the source's unit both sides (a unit gain); the output in um/s.
    const std::string path = Replace(Replace(text, "input_unit: um/s", "input_unit: " + unit), "output_unit: um/s",
                                     "output_unit: " + unit);
    return Evaluate(LoadBudgetText(path, "b.yaml")).outputs[0].rms();
  };
  const double by_class = rms("{type: vc, class: VC-C}", "um/s");
  CHECK(rms("{type: vc, velocity: 12.5 um/s}", "um/s") == by_class);
  CHECK(rms("{type: vc, velocity: 12.5}", "um/s") == by_class);  // a plain number in the source's unit
  CHECK(rms("{type: vc, velocity: 0.0125}", "mm/s") == doctest::Approx(by_class).epsilon(1e-14));
  CHECK(rms("{type: vc, velocity: 25 um/s}", "um/s") == doctest::Approx(2 * by_class).epsilon(1e-14));
  CHECK(ErrorOf(Replace(kBudget, "{type: flat, level: 2}", "{type: vc, class: VC-C, velocity: 12.5}")) ==
        "b.yaml:6:15: sources[0].spectrum: both 'class' and 'velocity': give the criterion as a class (class: VC-D) "
        "or as its band RMS velocity (velocity: 6.25 um/s)");
  CHECK(ErrorOf(Replace(kBudget, "{type: flat, level: 2}", "{type: vc}")).find("neither 'class' nor 'velocity'") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "{type: flat, level: 2}", "{type: vc, velocity: -1}"))
            .find("sources[0].spectrum.velocity") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "{type: flat, level: 2}", "{type: vc, velocity: 2 N}"))
            .find("sources[0].spectrum.velocity") != std::string::npos);
}

TEST_CASE("series paths chain units and scale between them") {
  auto text = Replace(kBudget, "contributors:", R"(  - name: to_mm
    type: gain
    gain: 1
    input_unit: mm/s
    output_unit: mm/s
  - name: chain
    type: series
    of: [lowpass, to_mm]
contributors:)");
  text = Replace(text, "path: lowpass}", "path: chain}");
  text = Replace(text, "signal: v,", "signal: y,");
  const Budget b = LoadBudgetText(text, "b.yaml");
  const Path& chain = b.FindPath("chain");
  CHECK(chain.output_units[0] == "mm/s");
  // um/s -> mm/s is a factor 1e-3 at DC.
  CHECK(chain.system.D()(0, 0) + (chain.system.C() * (-chain.system.A()).inverse() * chain.system.B())(0, 0) ==
        doctest::Approx(1e-3).epsilon(1e-12));
}

TEST_CASE("an output metric loads its type and window, and a bad one names its position and the allowed values") {
  const std::string ma = Replace(kBudget, "{name: velocity, signal: v, unit: um/s}",
                                 "{name: velocity, signal: v, unit: um/s, metric: {type: moving_std, window_s: 0.02}}");
  const Budget b = LoadBudgetText(ma, "b.yaml");
  REQUIRE(b.outputs[0].metric.has_value());
  CHECK(b.outputs[0].metric->type == MetricType::kMovingStd);
  CHECK(b.outputs[0].metric->window_s == 0.02);
  // No exact variance through the weighting, named as the moving std weights: 1 - sinc^2, not sinc^2.
  const BudgetResult r = Evaluate(b);
  CHECK(r.outputs[0].contributors[0].exact_note ==
        "the moving_std weighting 1 - |sinc(pi f T)|^2 is not rational in s: no Lyapunov form");
  const std::string bad_type = ErrorOf(Replace(ma, "moving_std", "moving_median"));
  CHECK(bad_type.rfind("b.yaml:18:60: outputs[0].metric.type: ", 0) == 0);
  CHECK(bad_type.find("outputs[0].metric.type") != std::string::npos);
  CHECK(bad_type.find("moving_average, moving_std") != std::string::npos);
  const std::string bad_window = ErrorOf(Replace(ma, "window_s: 0.02", "window_s: 0"));
  CHECK(bad_window.find("outputs[0].metric.window_s") != std::string::npos);
  CHECK(ErrorOf(Replace(ma, "window_s: 0.02", "window_s: 0.02, step: 1")).find("step") != std::string::npos);
}

TEST_CASE("the loader records the position of every node of the budget, once, with the budget") {
  const Budget b = LoadBudgetText(kBudget, "b.yaml");
  REQUIRE(b.positions != nullptr);
  CHECK(b.positions->file() == "b.yaml");
  // Also the nodes no rule looked at during the load: every element of den.
  const InputLocation den1 = b.positions->Locate("paths[0].den[1]");
  CHECK(den1.line == 11);
  CHECK(den1.column == 17);
  CHECK(b.positions->Locate("bands[0]").line == 20);
}

TEST_CASE("an error the engine finds after loading is located from the positions kept with the budget") {
  // The file is gone before the engine runs: nothing is read a second time.
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("deb_budget_yaml_" + std::to_string(::getpid()) + ".yaml");
  const std::string text = Replace(Replace(kBudget, "den: [0.01, 1]", "den: [0.01, -1]"), "path: lowpass}",
                                   "path: lowpass, exact: required}");
  std::ofstream(file) << text;
  const Budget b = LoadBudgetFile(file.string());
  std::filesystem::remove(file);
  std::string what = "(no error)";
  InputLocation where;
  try {
    Evaluate(b);
  } catch (const InputError& e) {
    what = e.what();
    where = e.location();
  }
  const auto line_start = text.find("  - {name: sensor");
  const int column = static_cast<int>(text.find("lowpass, exact", line_start) - line_start) + 1;
  CHECK(where.file == file.string());
  CHECK(where.line == 16);
  CHECK(where.column == column);
  CHECK(where.key_path == "contributors[0].path");
  CHECK(what.rfind(file.string() + ":16:" + std::to_string(column) + ": contributors[0].path: ", 0) == 0);
  CHECK(what.find("unstable") != std::string::npos);
}

TEST_CASE("a changed copy of a budget is located in the original, its message saying which copy") {
  const Budget original = LoadBudgetText(kBudget, "b.yaml");
  // The copy as a sweep writes it: another layout, the same key paths.
  const std::string copy = Replace(Replace(kBudget, "level: 2}", "level: -2}"), "name: unit_test\n",
                                   "name: unit_test\ndescription: a copy\n");
  std::string what = "(no error)";
  try {
    LoadBudgetVariant(copy, original.positions, "sweep variant 2: sources[0].spectrum.level = -2", ".");
  } catch (const InputError& e) {
    what = e.what();
  }
  CHECK(what.rfind("b.yaml:6:35: sources[0].spectrum.level: sweep variant 2: sources[0].spectrum.level = -2: ", 0) ==
        0);
  const Budget ok = LoadBudgetVariant(Replace(kBudget, "level: 2}", "level: 3}"), original.positions, "x", ".");
  CHECK(ok.positions == original.positions);
}

TEST_CASE("an unknown key is answered with the nearest allowed one, if any is near") {
  const std::string e = ErrorOf(Replace(kBudget, "source: noise", "sorce: noise"));
  CHECK(e.rfind("b.yaml:16:20: contributors[0].sorce: unknown key 'sorce' (did you mean 'source'?); allowed here: ",
                0) == 0);
  CHECK(ErrorOf(Replace(kBudget, "source: noise", "source: nosie"))
            .find("no source named 'nosie' (did you mean 'noise'?)") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "path: lowpass}", "path: lowpas}"))
            .find("no path named 'lowpas' (did you mean 'lowpass'?)") != std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "signal: v,", "signal: vv,")).find("reads signal 'vv' (did you mean 'v'?)") !=
        std::string::npos);
  CHECK(ErrorOf(Replace(kBudget, "source: noise", "zzzzzz: noise")).find("did you mean") == std::string::npos);
}

}  // namespace deb

