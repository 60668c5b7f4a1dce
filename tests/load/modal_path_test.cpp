// Budget paths of `type: modal`: finite-element modes from CSV tables and
// inline, against the closed form of one mass-normalised mode under a white
// force, and every bad input as a located error.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/budget_errors.h"
#include "tests/support/text_edit.h"
#include "tests/support/contributor_of.h"

namespace deb {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// One mode at 42 Hz, zeta 0.02, phi_in = 0.31, phi_out = -0.7 1/sqrt(kg), white
// force S0 = 2.5 N^2/Hz (one-sided): sigma^2 = S0 phi_in^2 phi_out^2 / (8 zeta w^3)
// in m^2, and S0 phi^2 / (8 zeta w) in (m/s)^2 for the velocity.
constexpr double kS0 = 2.5, kZeta = 0.02, kPhi2 = 0.31 * 0.31 * 0.7 * 0.7;
const double kW = kTwoPi * 42.0;
const double kDisplacementUm2 = 1e12 * kS0 * kPhi2 / (8 * kZeta * kW * kW * kW);
const double kVelocityUm2 = 1e12 * kS0 * kPhi2 / (8 * kZeta * kW);

class ModalDir {
 public:
  ModalDir() : dir_(std::filesystem::temp_directory_path() / ("deb_modal_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    // Two modes; max_frequency_hz: 500 keeps the first only.
    WriteFile("modes.csv", "# frame, from the FE model\nmode, f_hz, zeta\n1, 42, 0.02\n2, 2000, 0.01\n");
    WriteFile("phi_in.csv", "dof, mode1, mode2\nF, 0.31, 5.0\nG, 1.0, 1.0\n");
    WriteFile("phi_out.csv", "dof, mode1, mode2\nz, -0.7, 3.0\n");
  }
  ~ModalDir() { std::filesystem::remove_all(dir_); }
  void WriteFile(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  std::string Write(const std::string& budget) const {
    WriteFile("b.yaml", budget);
    return (dir_ / "b.yaml").string();
  }

 private:
  std::filesystem::path dir_;
};

// paths[0] from the tables, paths[1] the same mode inline (the input G of the
// tables is not driven: the source has one channel, the path two inputs, so
// the contributor drives F only through a selection path).
const char* kBudget = R"(name: modal
grid: {type: auto, min_hz: 0.001, max_hz: 100000}
sources:
  - {name: force, unit: N, spectrum: {type: flat, level: 2.5}}
paths:
  - name: tables
    type: modal
    modes: modes.csv
    input_shapes: phi_in.csv
    output_shapes: phi_out.csv
    max_frequency_hz: 500
    input_unit: N
    output_unit: m
  - name: inline
    type: modal
    frequencies_hz: [42]
    damping: 0.02
    input_shapes: {F: [0.31]}
    output_shapes: {z: [-0.7]}
    output_quantity: displacement
    input_unit: N
    output_unit: m
  - {name: only_F, type: gain, gain: [[1], [0]], input_unit: N, output_unit: N, outputs: [F, G]}
  - {name: csv, type: series, of: [only_F, tables]}
contributors:
  - {name: csv, source: force, path: csv, exact: required}
  - {name: inline, source: force, path: inline, exact: required}
outputs:
  - {name: z, signal: z, unit: um}
)";

using test::Replace;

// The message as the CLI prints it: an engine error (a key path, no
// position) located in the budget file.
std::string ErrorOf(const std::string& file) { return test::ErrorOfBudget(file); }

using test::ContributorOf;

using test::CheckLocated;

TEST_CASE("one mode from tables and inline: RMS and exact variance equal the closed form") {
  const ModalDir dir;
  const Budget b = LoadBudgetFile(dir.Write(kBudget));
  const Path& tables = b.FindPath("tables");
  REQUIRE(tables.IsModal());
  CHECK(tables.modal->modes() == 1);  // the 2000 Hz mode is dropped
  CHECK(tables.input_names == std::vector<std::string>{"F", "G"});
  CHECK(tables.output_names == std::vector<std::string>{"z"});
  CHECK(tables.output_units == std::vector<std::string>{"m"});
  const BudgetResult r = Evaluate(b);
  for (const std::string name : {"csv", "inline"}) {
    CAPTURE(name);
    const ContributorResult& c = ContributorOf(r.outputs[0], name);
    REQUIRE(c.exact_variance.has_value());
    // Lyapunov against the closed form: 1e-9.
    CHECK(*c.exact_variance == doctest::Approx(kDisplacementUm2).epsilon(1e-9));
    // The grid (0.001-1e5 Hz, automatic refinement at the mode): observed
    // relative difference 3.8e-5 (the band below 0.001 Hz is 6e-7 of it,
    // the rest the quadrature of the resonance); asserted to 1e-4.
    const double rel = std::abs(c.variance - kDisplacementUm2) / kDisplacementUm2;
    MESSAGE(name << ": grid variance " << c.variance << " um^2, closed form " << kDisplacementUm2
                 << ", relative difference " << rel);
    CHECK(rel < 1e-4);
  }
  CHECK(r.outputs[0].rms() == doctest::Approx(std::sqrt(2 * kDisplacementUm2)).epsilon(1e-4));
}

TEST_CASE("velocity outputs are in output_unit/s and give S0 phi^2 / (8 zeta w)") {
  const ModalDir dir;
  std::string text = Replace(kBudget, "output_quantity: displacement", "output_quantity: velocity");
  text = Replace(text, "output_shapes: phi_out.csv", "output_shapes: phi_out.csv\n    output_quantity: velocity");
  text = Replace(text, "unit: um}", "unit: um/s}");
  const Budget b = LoadBudgetFile(dir.Write(text));
  CHECK(b.FindPath("inline").output_units == std::vector<std::string>{"m/s"});
  const BudgetResult r = Evaluate(b);
  for (const char* name : {"csv", "inline"}) {
    const ContributorResult& c = ContributorOf(r.outputs[0], name);
    REQUIRE(c.exact_variance.has_value());
    CHECK(*c.exact_variance == doctest::Approx(kVelocityUm2).epsilon(1e-9));
    CHECK(c.variance == doctest::Approx(kVelocityUm2).epsilon(1e-4));
  }
}

TEST_CASE("acceleration outputs are in output_unit/s^2; their white-force variance has no exact value, and deb says why") {
  const ModalDir dir;
  std::string text = Replace(kBudget, "output_quantity: displacement", "output_quantity: acceleration");
  text = Replace(text, "output_unit: m\n  - {name: only_F", "output_unit: mm\n  - {name: only_F");
  text = Replace(text, "exact: required}\n  - {name: inline, source: force, path: inline, exact: required}",
                 "exact: required}\n  - {name: inline, source: force, path: inline}");
  text = Replace(text, "  - {name: csv, source: force, path: csv, exact: required}\n", "");
  text = Replace(text, "grid: {type: auto, min_hz: 0.001, max_hz: 100000}", "grid: {type: auto, min_hz: 1, max_hz: 100}");
  text = Replace(text, "unit: um}", "unit: m/s^2}");
  const Budget b = LoadBudgetFile(dir.Write(text));
  CHECK(b.FindPath("inline").output_units == std::vector<std::string>{"mm/s^2"});
  const BudgetResult r = Evaluate(b);
  const ContributorResult& c = ContributorOf(r.outputs[0], "inline");
  CHECK_FALSE(c.exact_variance.has_value());
  CHECK(c.exact_note.find("feedthrough") != std::string::npos);
}

TEST_CASE("a rigid-body mode: the grid starts above 0 Hz, and the exact variance is absent with the reason") {
  const ModalDir dir;
  std::string text = Replace(kBudget, "frequencies_hz: [42]", "frequencies_hz: [0, 42]");
  text = Replace(text, "damping: 0.02", "damping: [0, 0.02]");
  text = Replace(text, "input_shapes: {F: [0.31]}", "input_shapes: {F: [0.1, 0.31]}");
  text = Replace(text, "output_shapes: {z: [-0.7]}", "output_shapes: {z: [1, -0.7]}");
  text = Replace(text, "path: inline, exact: required}", "path: inline}");
  const BudgetResult r = Evaluate(LoadBudgetFile(dir.Write(text)));
  const ContributorResult& c = ContributorOf(r.outputs[0], "inline");
  CHECK_FALSE(c.exact_variance.has_value());
  CHECK(c.exact_note == "the path has poles on the imaginary axis");
  bool warned = false;
  for (const auto& w : r.warnings) warned |= w.find("path 'inline' has pole(s) on the imaginary axis") != std::string::npos;
  CHECK(warned);
  // Asked for, it is a located error naming the reason.
  const std::string m = ErrorOf(dir.Write(Replace(text, "path: inline}", "path: inline, exact: required}")));
  CheckLocated(m, "contributors[1].exact", "the path has poles on the imaginary axis");
}

TEST_CASE("bad modal tables are errors at the budget key and at the table's file:line:col") {
  const ModalDir dir;
  dir.WriteFile("phi3.csv", "dof, a, b, c\nF, 1, 2, 3\nG, 1, 2, 3\n");
  std::string m = ErrorOf(dir.Write(Replace(kBudget, "input_shapes: phi_in.csv", "input_shapes: phi3.csv")));
  CheckLocated(m, "paths[0].input_shapes",
               "phi3.csv:1:12: 3 mode column(s), but the mode table 'modes.csv' has 2 mode(s)");
  dir.WriteFile("dup.csv", "dof, a, b\nz, 1, 2\nz, 3, 4\n");
  m = ErrorOf(dir.Write(Replace(kBudget, "output_shapes: phi_out.csv", "output_shapes: dup.csv")));
  CheckLocated(m, "paths[0].output_shapes", "dup.csv:3:1: DOF 'z' is given twice (also on line 2)");
  dir.WriteFile("noname.csv", "dof, a, b\n, 1, 2\n");
  m = ErrorOf(dir.Write(Replace(kBudget, "output_shapes: phi_out.csv", "output_shapes: noname.csv")));
  CheckLocated(m, "paths[0].output_shapes", "noname.csv:2:1: DOF name: empty cell");
  dir.WriteFile("neg.csv", "f_hz, zeta\n42, 0.02\n-1, 0.02\n");
  m = ErrorOf(dir.Write(Replace(kBudget, "modes: modes.csv", "modes: neg.csv")));
  CheckLocated(m, "paths[0].modes", "neg.csv:3:1: natural frequency -1 Hz is negative");
  dir.WriteFile("zeta1.csv", "f_hz, zeta\n42, 1\n2000, 0.01\n");
  m = ErrorOf(dir.Write(Replace(kBudget, "modes: modes.csv", "modes: zeta1.csv")));
  CheckLocated(m, "paths[0].modes", "zeta1.csv:2:5: damping ratio 1 is >= 1");
  dir.WriteFile("inf.csv", "f_hz, zeta\ninf, 0.02\n2000, 0.01\n");
  m = ErrorOf(dir.Write(Replace(kBudget, "modes: modes.csv", "modes: inf.csv")));
  CheckLocated(m, "paths[0].modes", "inf.csv:2:1: first column: 'inf' is not finite");
  m = ErrorOf(dir.Write(Replace(kBudget, "modes: modes.csv", "modes: nowhere.csv")));
  CheckLocated(m, "paths[0].modes", "nowhere.csv");
  m = ErrorOf(dir.Write(Replace(kBudget, "max_frequency_hz: 500", "max_frequency_hz: 10")));
  CheckLocated(m, "paths[0].max_frequency_hz", "no mode at or below 10 Hz (the lowest is at 42 Hz)");
  m = ErrorOf(dir.Write(Replace(kBudget, "max_frequency_hz: 500", "max_frequency_hz: 500\n    residual: both")));
  CheckLocated(m, "paths[0].residual", "residual must be 'static' or 'none', got 'both'");
  m = ErrorOf(dir.Write(Replace(kBudget, "max_frequency_hz: 500", "residual: static")));
  CheckLocated(m, "paths[0].residual", "give max_frequency_hz");
}

TEST_CASE("residual: static from YAML: the dropped 2000 Hz mode's compliance as a feedthrough, no exact variance") {
  const ModalDir dir;
  std::string text = Replace(kBudget, "max_frequency_hz: 500", "max_frequency_hz: 500\n    residual: static");
  // The tables' path directly (one input driven, the other not reached by a
  // one-channel source would not fit): a two-channel force.
  text = Replace(text, "  - {name: force, unit: N, spectrum: {type: flat, level: 2.5}}",
                 "  - {name: force, unit: N, spectrum: {type: flat, level: 2.5}}\n"
                 "  - {name: forces, unit: N, channels: [F, G], spectrum: {type: flat, level: 2.5}}");
  text = Replace(text, "  - {name: csv, source: force, path: csv, exact: required}",
                 "  - {name: csv, source: forces, path: tables}");
  const Budget b = LoadBudgetFile(dir.Write(text));
  const Path& tables = b.FindPath("tables");
  REQUIRE(tables.modal->residual.rows() == 1);
  REQUIRE(tables.modal->residual.cols() == 2);
  const double w = kTwoPi * 2000.0;
  CHECK(tables.modal->residual(0, 0) == doctest::Approx(3.0 * 5.0 / (w * w)).epsilon(1e-15));  // z from F
  CHECK(tables.modal->residual(0, 1) == doctest::Approx(3.0 * 1.0 / (w * w)).epsilon(1e-15));  // z from G
  const BudgetResult r = Evaluate(b);
  const ContributorResult& c = ContributorOf(r.outputs[0], "csv");
  CHECK(!c.exact_variance.has_value());
  CHECK(c.exact_note.find("static residual") != std::string::npos);
}

TEST_CASE("bad inline modes are errors at their key") {
  const ModalDir dir;
  auto error = [&](const std::string& from, const std::string& to) { return ErrorOf(dir.Write(Replace(kBudget, from, to))); };
  CheckLocated(error("input_shapes: {F: [0.31]}", "input_shapes: {F: [0.31, 1]}"), "paths[1].input_shapes.F",
               "2 value(s), but frequencies_hz has 1 mode(s)");
  CheckLocated(error("output_shapes: {z: [-0.7]}", "output_shapes: {}"), "paths[1].output_shapes", "no DOFs");
  CheckLocated(error("output_shapes: {z: [-0.7]}", "output_shapes: {z: [-0.7], z: [1]}"), "paths[1].output_shapes.z",
               "key 'z' is given twice");
  CheckLocated(error("output_shapes: {z: [-0.7]}", "output_shapes: [-0.7]"), "paths[1].output_shapes",
               "expected a shape table file, or a map of DOF names");
  CheckLocated(error("frequencies_hz: [42]", "frequencies_hz: [-42]"), "paths[1].frequencies_hz[0]",
               "natural frequency -42 Hz is negative");
  CheckLocated(error("frequencies_hz: [42]", "frequencies_hz: [.inf]"), "paths[1].frequencies_hz[0]", "not finite");
  CheckLocated(error("damping: 0.02", "damping: 0"), "paths[1].damping",
               "damping ratio 0 of a mode at 42 Hz must be > 0");
  CheckLocated(error("damping: 0.02", "damping: [0.02, 0.1]"), "paths[1].damping",
               "2 damping ratio(s) for 1 mode(s)");
  CheckLocated(error("damping: 0.02", "damping: [1.5]"), "paths[1].damping[0]", "damping ratio 1.5 is >= 1");
  CheckLocated(error("    damping: 0.02\n", ""), "paths[1]", "missing 'damping'");
  CheckLocated(error("frequencies_hz: [42]", "modes: modes.csv\n    frequencies_hz: [42]"), "paths[1].frequencies_hz",
               "give 'modes' (a mode table file) or 'frequencies_hz' and 'damping', not both");
  CheckLocated(error("output_quantity: displacement", "output_quantity: jerk"), "paths[1].output_quantity",
               "unknown output quantity 'jerk'; allowed: displacement, velocity, acceleration");
  CheckLocated(error("output_quantity: displacement", "outputs: [y]"), "paths[1].outputs", "'outputs' belongs to a modal path from a Nastran file");
  CheckLocated(error("    output_unit: m\n  - {name: only_F", "    output_unit: furlong_x\n  - {name: only_F"),
               "paths[1].output_unit", "furlong_x");
}

// Three modes (two of them 3 % apart) seen by two outputs through two inputs,
// as inline modal paths: `full` has all three; `only_k` mode k alone and
// `rest_k` the other two, for the independent check below.
std::string ThreeModeBudget(const std::string& spectrum, const std::string& unit = "N") {
  const char* f[] = {"10", "10.3", "31"};
  const char* in_f[] = {"1.0", "0.8", "-0.5"};
  const char* in_g[] = {"0.3", "-1.0", "0.7"};
  const char* out_z[] = {"1.0", "-0.6", "0.9"};
  const char* out_w[] = {"0.2", "1.0", "1.0"};
  const auto path = [&](const std::string& name, const std::vector<int>& modes) {
    std::string fs, fi, gi, zo, wo;
    for (std::size_t i = 0; i < modes.size(); ++i) {
      const std::string sep = i ? ", " : "";
      fs += sep + f[modes[i]];
      fi += sep + in_f[modes[i]];
      gi += sep + in_g[modes[i]];
      zo += sep + out_z[modes[i]];
      wo += sep + out_w[modes[i]];
    }
    return "  - {name: " + name + ", type: modal, frequencies_hz: [" + fs + "], damping: 0.01, input_shapes: {F: [" +
           fi + "], G: [" + gi + "]}, output_shapes: {z: [" + zo + "], w: [" + wo +
           "]}, input_unit: " + unit + ", output_unit: m}\n";
  };
  std::string b = "name: three\ngrid: {type: auto, min_hz: 0.001, max_hz: 100000}\nsources:\n"
                  "  - {name: force, unit: " + unit + ", channels: 2, spectrum: " + spectrum + "}\npaths:\n";
  b += path("full", {0, 1, 2});
  for (int k = 0; k < 3; ++k) {
    std::vector<int> rest;
    for (int l = 0; l < 3; ++l)
      if (l != k) rest.push_back(l);
    b += path("only_" + std::to_string(k + 1), {k});
    b += path("rest_" + std::to_string(k + 1), rest);
  }
  b += "contributors:\n  - {name: full, source: force, path: full}\n";
  for (int k = 1; k <= 3; ++k)
    for (const std::string p : {"only_", "rest_"})
      b += "  - {name: " + p + std::to_string(k) + ", source: force, path: " + p + std::to_string(k) + "}\n";
  b += "outputs:\n  - {name: z, signal: z, unit: um}\n  - {name: w, signal: w, unit: um}\n";
  return b;
}

const ModeShare& ModeOf(const ContributorResult& c, int mode) {
  for (const ModeShare& m : c.top_modes)
    if (m.mode == mode) return m;
  FAIL("mode " << mode << " is not among the top modes of " << c.name);
  return c.top_modes.front();
}

TEST_CASE("per-mode shares under a source that is not white: the grid split, checked by superposition") {
  // Mode k's part is Re S_{y_k y} = (S_y + S_{y_k} - S_{y - y_k}) / 2, so its
  // variance must equal (var(full) + var(only_k) - var(rest_k)) / 2 on the
  // same grid: three variances the split never sees. VC-D floor (not white):
  // the split is of the grid variance.
  const ModalDir dir;
  const BudgetResult r = Evaluate(LoadBudgetFile(dir.Write(ThreeModeBudget("{type: vc, class: VC-D}", "um/s"))));
  double worst = 0.0;  // largest |part - superposition| / variance
  for (const OutputResult& o : r.outputs) {
    CAPTURE(o.name);
    const ContributorResult& full = ContributorOf(o, "full");
    CHECK(full.top_modes_of == ModeSplit::kGridVariance);
    REQUIRE(full.top_modes.size() == 3);
    double sum = 0.0;
    for (const ModeShare& m : full.top_modes) sum += m.share;
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));  // the parts add up (no residual)
    for (int k = 1; k <= 3; ++k) {
      CAPTURE(k);
      const double expected = 0.5 * (full.variance + ContributorOf(o, "only_" + std::to_string(k)).variance -
                                     ContributorOf(o, "rest_" + std::to_string(k)).variance);
      // The grid is all Lobatto panels (linear in the PSD) but for the
      // 1e-9-wide steps at the VC band edges: observed 2.3e-13.
      CHECK(ModeOf(full, k).variance == doctest::Approx(expected).epsilon(1e-10).scale(full.variance));
      worst = std::max(worst, std::abs(ModeOf(full, k).variance - expected) / full.variance);
    }
    // Largest first.
    for (std::size_t i = 1; i < full.top_modes.size(); ++i)
      CHECK(std::abs(full.top_modes[i - 1].share) >= std::abs(full.top_modes[i].share));
  }
  MESSAGE("mode parts against superposition: " << worst << " of the variance at worst");
}

TEST_CASE("per-mode shares: the grid split of a flat band equals the closed-form split of the same white level") {
  // The same level, once white (exact variance, closed-form split over
  // 0..infinity) and once a band 0.001-1e5 Hz (grid split over the grid).
  // They differ by the tails beyond the grid and the grid's quadrature error:
  // observed 1.2e-7 in a share, asserted to 1e-6.
  const ModalDir dir;
  const BudgetResult white = Evaluate(LoadBudgetFile(dir.Write(ThreeModeBudget("{type: flat, level: 2.5}"))));
  const BudgetResult band =
      Evaluate(LoadBudgetFile(dir.Write(ThreeModeBudget("{type: flat, level: 2.5, lo_hz: 0.001, hi_hz: 100000}"))));
  double worst = 0.0;  // largest |share difference|
  for (std::size_t o = 0; o < 2; ++o) {
    const ContributorResult& a = ContributorOf(white.outputs[o], "full");
    const ContributorResult& b = ContributorOf(band.outputs[o], "full");
    CAPTURE(white.outputs[o].name);
    CHECK(a.top_modes_of == ModeSplit::kExactVariance);
    CHECK(b.top_modes_of == ModeSplit::kGridVariance);
    REQUIRE(a.exact_variance.has_value());
    for (int k = 1; k <= 3; ++k) {
      CAPTURE(k);
      CHECK(ModeOf(b, k).share == doctest::Approx(ModeOf(a, k).share).epsilon(1e-6));
      CHECK(ModeOf(b, k).variance == doctest::Approx(ModeOf(a, k).variance).epsilon(1e-6).scale(*a.exact_variance));
      worst = std::max(worst, std::abs(ModeOf(b, k).share - ModeOf(a, k).share));
    }
  }
  MESSAGE("grid split against the closed-form split: shares differ by " << worst << " at worst");
}

}  // namespace
}  // namespace deb
