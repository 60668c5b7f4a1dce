// Modal paths from Nastran result files (deb/load/nastran_modal_yaml.h): the
// shipped beam budget (budgets/nastran_beam.yaml, modes from an OP2 file
// Nastran wrote) against the same modes as CSV tables and as a punch file,
// against the closed form of its first mode pair, and every rule of the keys
// as a located error. Selection, rigid-body modes, damping tables and the
// static correction on OP2 files written here.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/formats/nastran_modes.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/budget_errors.h"
#include "tests/support/contributor_of.h"
#include "tests/support/op2_writer.h"
#include "tests/support/punch_writer.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kInchM = 0.0254, kLbfN = 4.4482216152605;  // exact by definition
const std::string kSource = DEB_SOURCE_DIR;
const std::string kBeam = kSource + "/budgets/nastran_beam.yaml";
const std::string kOp2 = kSource + "/budgets/nastran_beam/beam_modes_m1.op2";

class Dir {
 public:
  Dir() : dir_(std::filesystem::temp_directory_path() / ("deb_nastran_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~Dir() { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return Path(name);
  }

 private:
  std::filesystem::path dir_;
};

using test::CheckLocated;
std::string ErrorOf(const std::string& file) { return test::ErrorOfBudget(file); }

// The beam budget with its path replaced by `path` (YAML of one path entry
// named arm).
std::string BeamWithPath(const std::string& path) {
  std::ifstream in(kBeam);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t from = text.find("paths:\n"), to = text.find("\ncontributors:");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  return text.substr(0, from) + "paths:\n" + path + text.substr(to);
}

// The tip's DOFs in the order of the budget's channels: z = 11:T3, y = 11:T2.
const std::vector<formats::NastranDof> kTip = {{11, 3}, {11, 2}};

TEST_CASE("the beam through its OP2 file, CSV tables of the same modes and a punch file: one budget") {
  const Budget op2 = LoadBudgetFile(kBeam);
  const BudgetResult r_op2 = Evaluate(op2);
  const Path& arm = op2.FindPath("arm");
  REQUIRE(arm.IsModal());
  CHECK(arm.input_names == std::vector<std::string>{"force_z", "force_y"});
  CHECK(arm.output_names == std::vector<std::string>{"tip_z", "tip_y"});
  CHECK(arm.modal->modes() == 10);

  // CSV tables of the modes, mass-normalised and in N and nm by hand.
  const formats::NastranModeFile file(kOp2);
  const Eigen::MatrixXd phi = file.Shapes(kTip, 10);
  const Dir dir;
  std::string modes = "mode, f_hz, zeta\n", in = "dof", out = "dof";
  for (int k = 0; k < 10; ++k) {
    in += ", m" + std::to_string(k + 1);
    out += ", m" + std::to_string(k + 1);
  }
  in += "\n";
  out += "\n";
  char cell[64];
  for (int k = 0; k < 10; ++k) {
    std::snprintf(cell, sizeof(cell), "%d, %.17g, 0.005\n", k + 1, file.modes()[static_cast<std::size_t>(k)].f_hz);
    modes += cell;
  }
  for (int i = 0; i < 2; ++i) {
    in += i == 0 ? "force_z" : "force_y";
    out += i == 0 ? "tip_z" : "tip_y";
    for (int k = 0; k < 10; ++k) {
      const double norm = 1.0 / std::sqrt(file.modes()[static_cast<std::size_t>(k)].generalized_mass);
      std::snprintf(cell, sizeof(cell), ", %.17g", phi(i, k) * norm / kLbfN);  // per N
      in += cell;
      std::snprintf(cell, sizeof(cell), ", %.17g", phi(i, k) * norm * kInchM * 1e9);  // nm
      out += cell;
    }
    in += "\n";
    out += "\n";
  }
  dir.Write("modes.csv", modes);
  dir.Write("phi_in.csv", in);
  dir.Write("phi_out.csv", out);
  const Budget csv = LoadBudgetFile(dir.Write("b.yaml", BeamWithPath(R"(  - name: arm
    type: modal
    modes: modes.csv
    input_shapes: phi_in.csv
    output_shapes: phi_out.csv
    input_unit: N
    output_unit: nm
)")));
  const BudgetResult r_csv = Evaluate(csv);

  // A punch file of the f06's eigenvectors, mass-normalised by its
  // generalised masses and printed to its 7 digits (the punch holds no
  // masses), of the grids the budget uses.
  {
    std::ifstream f06(kSource + "/tests/data/nastran/beam_modes.f06");
    std::vector<std::string> lines;
    for (std::string l; std::getline(f06, l);) lines.push_back(l);
    std::vector<double> eig, gm;
    std::vector<std::vector<double>> tip;  // per mode: T1..R3 at grid 11
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (lines[i].find("R E A L   E I G E N V A L U E S") != std::string::npos)
        for (std::size_t j = i + 3; j < i + 13; ++j) {
          double v[7];
          REQUIRE(std::sscanf(lines[j].c_str(), "%lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4],
                              &v[5], &v[6]) == 7);
          eig.push_back(v[2]);
          gm.push_back(v[5]);
        }
      long long id;
      char type[4];
      double v[6];
      if (std::sscanf(lines[i].c_str(), "%lld %3s %lf %lf %lf %lf %lf %lf", &id, type, &v[0], &v[1], &v[2], &v[3],
                      &v[4], &v[5]) == 8 &&
          id == 11 && std::string(type) == "G")
        tip.emplace_back(v, v + 6);
    }
    REQUIRE(eig.size() == 10);
    REQUIRE(tip.size() == 10);
    // Of grid 11 only, mass-normalised.
    std::vector<std::map<long long, std::vector<double>>> shapes(10);
    for (std::size_t k = 0; k < 10; ++k) {
      shapes[k][11] = tip[k];
      for (double& v : shapes[k][11]) v /= std::sqrt(gm[k]);
    }
    test::WritePunchModes(dir.Path("beam.pch"), eig, shapes);
  }
  std::string punch_path = BeamWithPath(R"(  - name: arm
    type: modal
    file: beam.pch
    inputs: {force_z: "11:T3", force_y: "11:T2"}
    outputs: {tip_z: "11:T3", tip_y: "11:T2"}
    damping: 0.005
    length_unit: in
    force_unit: lbf
    input_unit: N
    output_unit: nm
)");
  const Budget punch = LoadBudgetFile(dir.Write("b.yaml", punch_path));
  const BudgetResult r_punch = Evaluate(punch);

  for (std::size_t o = 0; o < 2; ++o) {
    CAPTURE(o);
    const ContributorResult& a = test::ContributorOf(r_op2.outputs[o], "actuator");
    const ContributorResult& b = test::ContributorOf(r_csv.outputs[o], "actuator");
    const ContributorResult& c = test::ContributorOf(r_punch.outputs[o], "actuator");
    REQUIRE(a.exact_variance.has_value());
    REQUIRE(b.exact_variance.has_value());
    // OP2 and CSV: the same numbers by two routes (units converted by
    // UDUNITS-2 and by hand): 1e-12.
    CHECK(std::abs(a.variance - b.variance) <= 1e-12 * a.variance);
    CHECK(std::abs(*a.exact_variance - *b.exact_variance) <= 1e-12 * *a.exact_variance);
    // The punch file: the f06's 7 digits of another run (its repeated pairs
    // in another basis, masses 1e-6 apart): 1e-5 (measured 1.1e-6).
    MESSAGE("output " << o << ": OP2 " << std::sqrt(a.variance) << " nm, punch " << std::sqrt(c.variance)
                      << " nm, relative difference of the variances " << std::abs(a.variance - c.variance) / a.variance);
    CHECK(std::abs(a.variance - c.variance) <= 1e-5 * a.variance);
  }
}

TEST_CASE("the beam's first mode pair against its closed form; the notes deb check prints") {
  // Modes 1 and 2 share one frequency (the section is square): under a
  // white force S0 at the tip in z, the tip's z motion has the variance of
  // one mode with the pair's projector P = sum phi_z^2 / m:
  //   sigma^2 = S0 P^2 / (8 zeta w^3)   (P_zy = 0: the y force does not reach z).
  const Dir dir;
  const std::string text = test::Replace(test::Replace(BeamWithPath(R"(  - name: arm
    type: modal
    file: OP2
    inputs: {force_z: "11:T3", force_y: "11:T2"}
    outputs: {tip_z: "11:T3", tip_y: "11:T2"}
    modes: {count: 2}
    damping: 0.005
    length_unit: in
    force_unit: lbf
    input_unit: N
    output_unit: nm
)"), "file: OP2", "file: " + kOp2), "rms_max: 5", "rms_max: 50");
  const Budget b = LoadBudgetFile(dir.Write("b.yaml", text));
  const Path& arm = b.FindPath("arm");
  REQUIRE(arm.modal->modes() == 2);
  REQUIRE(arm.modal->notes.size() == 4);
  CHECK(arm.modal->notes[0] ==
        "modes from beam_modes_m1.op2 (OP2, little-endian, 32-bit words; eigenvectors from OUGV1): 10 in the file, "
        "456.66-11112 Hz");
  CHECK(arm.modal->notes[1] ==
        "mass-normalised: each eigenvector divided by the square root of its generalised mass (0.008719 in the model's "
        "units)");
  CHECK(arm.modal->notes[2] == "kept 2 of 10 modes (count 2)");
  CHECK(arm.modal->notes[3] == "the model's units (in, lbf, rad) converted to the path's");

  const formats::NastranModeFile file(kOp2);
  const Eigen::MatrixXd phi = file.Shapes(kTip, 2);
  double p = 0.0;
  for (int k = 0; k < 2; ++k) p += phi(0, k) * phi(0, k) / file.modes()[static_cast<std::size_t>(k)].generalized_mass;
  REQUIRE(file.modes()[0].f_hz == file.modes()[1].f_hz);
  const double w = kTwoPi * file.modes()[0].f_hz, s0 = 1e-6;  // N^2/Hz
  const double p_si = p * kInchM / kLbfN;                     // m/N per (rad/s)^2
  const double expected_nm2 = 1e18 * s0 * p_si * p_si / (8 * 0.005 * w * w * w);
  const BudgetResult r = Evaluate(b);
  const ContributorResult& c = test::ContributorOf(r.outputs[0], "actuator");
  REQUIRE(c.exact_variance.has_value());
  MESSAGE("tip_z: closed form " << std::sqrt(expected_nm2) << " nm, exact " << std::sqrt(*c.exact_variance)
                                << " nm, grid " << std::sqrt(c.variance) << " nm");
  CHECK(std::abs(*c.exact_variance - expected_nm2) <= 1e-9 * expected_nm2);
  CHECK(std::abs(c.variance - expected_nm2) <= 1e-3 * expected_nm2);
}

TEST_CASE("selection, rigid-body modes, damping tables and the static correction") {
  // Modes: a rigid-body mode (the solver's numerical zero), 10, 20 and 40 Hz;
  // generalised mass 4 (the shapes are halved by the normalisation).
  const Dir dir;
  std::vector<test::Op2Mode> modes;
  const double f[4] = {2e-4, 10.0, 20.0, 40.0};
  for (int k = 0; k < 4; ++k) {
    const double w = kTwoPi * f[k];
    modes.push_back({k + 1, k == 0 ? -1.6e-6 : w * w, w, f[k], 4.0, 0.0});
  }
  const auto shape = [](std::size_t k, std::size_t g, int c) { return (1.0 + static_cast<double>(k)) * (g + 1) + c; };
  test::Op2Layout layout;
  layout.word = 8;
  test::WriteModesOp2(dir.Path("m.op2"), layout, modes, {1, 2}, shape);
  const auto budget = [&](const std::string& extra) {
    return dir.Write("b.yaml", R"(name: b
grid: {type: log, min_hz: 1, max_hz: 1000, points: 200}
sources:
  - {name: force, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - name: p
    type: modal
    file: m.op2
    inputs: ["1:T1"]
    outputs: ["2:T2"]
    length_unit: m
    input_unit: N
    output_unit: m
)" + extra + R"(
contributors:
  - {name: c, source: force, path: p}
outputs:
  - {name: y, signal: "2:T2", unit: m}
)");
  };
  SUBCASE("rigid-body mode kept at 0 Hz, damping by frequency") {
    const Budget b = LoadBudgetFile(budget("    damping: {f_hz: [10, 40], zeta: [0.01, 0.04]}"));
    const ModalModel& m = *b.FindPath("p").modal;
    REQUIRE(m.modes() == 4);
    CHECK(m.f_hz[0] == 0.0);
    CHECK(m.zeta[0] == 0.0);
    CHECK(m.zeta[1] == 0.01);
    CHECK(m.zeta[2] == doctest::Approx(0.02).epsilon(1e-15));
    CHECK(m.zeta[3] == 0.04);
    CHECK(m.phi_in(0, 1) == 0.5 * shape(1, 0, 0));  // / sqrt(4)
    CHECK(m.phi_out(0, 2) == 0.5 * shape(2, 1, 1));
    CHECK(m.notes[2] == "1 rigid-body mode(s) (below 0.01 Hz) kept as rigid modes at 0 Hz (force to displacement "
                        "1/(-w^2 m))");
  }
  SUBCASE("rigid-body mode excluded; max_hz with the static correction of the dropped mode") {
    const Budget b = LoadBudgetFile(
        budget("    damping: 0.02\n    rigid_modes: exclude\n    modes: {max_hz: 25}\n    residual: static"));
    const ModalModel& m = *b.FindPath("p").modal;
    REQUIRE(m.modes() == 2);
    CHECK(m.f_hz == std::vector<double>{10.0, 20.0});
    const double w = kTwoPi * 40.0;
    REQUIRE(m.residual.size() == 1);
    CHECK(m.residual(0, 0) == doctest::Approx(0.25 * shape(3, 1, 1) * shape(3, 0, 0) / (w * w)).epsilon(1e-14));
    CHECK(m.notes[2] == "1 rigid-body mode(s) (below 0.01 Hz) excluded (rigid_modes: exclude)");
    CHECK(m.notes[3] == "kept 2 of 3 modes (max_hz 25), with the static correction of the 1 dropped");
  }
  SUBCASE("a negative eigenvalue above the rigid-body range is an unstable model") {
    modes[1].eigenvalue = -modes[1].eigenvalue;
    test::WriteModesOp2(dir.Path("m.op2"), layout, modes, {1, 2}, shape);
    CheckLocated(ErrorOf(budget("    damping: 0.02")), "paths[0].file",
                 "m.op2: mode 2 has a negative eigenvalue -3947.8417604357433 at 10 Hz: the model is unstable");
  }
}

TEST_CASE("bad keys of a Nastran modal path: located errors naming the rule and what the file holds") {
  const Dir dir;
  std::filesystem::copy_file(kOp2, dir.Path("beam.op2"));
  std::filesystem::copy_file(kSource + "/tests/data/nastran/fsi.pch", dir.Path("fsi.pch"));
  const std::string good = R"(  - name: arm
    type: modal
    file: beam.op2
    inputs: {force_z: "11:T3", force_y: "11:T2"}
    outputs: {tip_z: "11:T3", tip_y: "11:T2"}
    damping: 0.005
    length_unit: in
    force_unit: lbf
    input_unit: N
    output_unit: nm
)";
  const auto error = [&](const std::string& from, const std::string& to) {
    return ErrorOf(dir.Write("b.yaml", BeamWithPath(test::Replace(good, from, to))));
  };
  CHECK(ErrorOf(dir.Write("b.yaml", BeamWithPath(good))) == "(no InputError)");
  CheckLocated(error("force_z: \"11:T3\"", "force_z: \"11:T7\""), "paths[0].inputs.force_z",
               "'11:T7' is not a Nastran DOF: write GRID:COMPONENT");
  CheckLocated(error("tip_y: \"11:T2\"", "tip_y: \"99:T2\""), "paths[0].file",
               "grid 99 (of 99:T2) is not in OUGV1, which holds 12 grid(s): 1-12");
  CheckLocated(error("tip_y: \"11:T2\"", "tip_y: \"11:T3\""), "paths[0].outputs.tip_y",
               "11:T3 is given twice (also as 'tip_z')");
  CheckLocated(error("length_unit: in", "length_unit: kg"), "paths[0].length_unit", "'kg' is not a length unit");
  CheckLocated(error("damping: 0.005", "damping: [0.005, 0.01]"), "paths[0].damping",
               "2 damping ratio(s) for the 10 mode(s) kept");
  CheckLocated(error("damping: 0.005", "damping: 0.005\n    modes: {count: 0}"), "paths[0].modes.count",
               "count must be at least 1");
  CheckLocated(error("damping: 0.005", "damping: 0.005\n    modes: {count: 11}"), "paths[0].modes.count",
               "count 11, but beam.op2 holds 10 mode(s) (456.66-11112 Hz)");
  CheckLocated(error("damping: 0.005", "damping: 0.005\n    modes: modes.csv"), "paths[0].modes",
               "with a Nastran file, 'modes' chooses the modes: {max_hz: F} or {count: N}");
  CheckLocated(error("damping: 0.005", "damping: 0.005\n    max_frequency_hz: 100"), "paths[0].max_frequency_hz",
               "not with a Nastran file");
  CheckLocated(error("damping: 0.005", "damping: 0.005\n    modes: {max_hz: 100}"), "paths[0].modes.max_hz",
               "no mode at or below 100 Hz (the lowest is at 456.7 Hz)");
  CheckLocated(error("damping: 0.005", "damping: 0.005\n    residual: static"), "paths[0].residual",
               "residual: static corrects for the modes that 'modes' leaves out");
  CheckLocated(error("output_unit: nm", "output_unit: rad"), "paths[0].output_unit",
               "output 'tip_z' is in in: 'rad' is not the same quantity");
  CheckLocated(error("file: beam.op2", "file: fsi.pch"), "paths[0].file",
               "fsi.pch:5: complex eigenvectors ($REAL-IMAGINARY OUTPUT");
  // The keys of a Nastran file on a path of tables.
  CheckLocated(ErrorOf(dir.Write("b.yaml", BeamWithPath(R"(  - name: arm
    type: modal
    frequencies_hz: [10]
    damping: 0.01
    input_shapes: {force_z: [1], force_y: [1]}
    output_shapes: {tip_z: [1], tip_y: [1]}
    length_unit: in
    input_unit: N
    output_unit: nm
)"))),
               "paths[0].length_unit", "'length_unit' belongs to a modal path from a Nastran file");
}

}  // namespace
}  // namespace deb
