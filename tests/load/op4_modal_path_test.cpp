// Modal paths from OP4 matrices (`type: modal`, `file: x.op4`, `matrices:
// {phi, lambda, mass}`, `rows:`; deb/load/nastran_modal_yaml.h): the beam
// of the shipped budget with its modes exported as OP4 matrices (every DOF
// of the OP2 Nastran wrote, in text and in big-endian 8-byte binary, modes
// out of order, masses as a diagonal or the shapes mass-normalised) gives
// the OP2 budget's numbers; a two-mass chain against its closed form
// H = (K - w^2 M + j w C)^-1; every rule as a located error.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/formats/nastran_modes.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/budget_errors.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/contains.h"
#include "tests/support/contributor_of.h"
#include "tests/support/op4_writer.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
const std::string kSource = DEB_SOURCE_DIR;
const std::string kBeam = kSource + "/budgets/nastran_beam.yaml";
const std::string kOp2 = kSource + "/budgets/nastran_beam/beam_modes_m1.op2";

// Each test's files, removed when it ends.
class Dir : public test::ScratchDir {
 public:
  Dir() : ScratchDir("op4_modal") {}
};

// The beam budget with its path's file and its OP4 keys in place of the OP2.
std::string BeamFromOp4(const std::string& file, const std::string& keys) {
  std::ifstream in(kBeam);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = test::Replace(text, "file: nastran_beam/beam_modes_m1.op2", "file: " + file + "\n    " + keys);
  return text;
}

TEST_CASE("the beam's modes as OP4 matrices give the OP2 budget's numbers") {
  const formats::NastranModeFile op2(kOp2);
  // Every DOF of the 11 grids, in grid order: the g-set of the beam.
  std::vector<formats::NastranDof> all;
  for (long long g = 1; g <= 11; ++g)
    for (int c = 1; c <= 6; ++c) all.push_back({g, c});
  const Eigen::MatrixXd phi = op2.Shapes(all, 10);
  // The modes in reverse order: deb sorts them by frequency.
  Eigen::MatrixXd phig(66, 10), lama(10, 1), mhh = Eigen::MatrixXd::Zero(10, 10), normalised(66, 10),
      khh = Eigen::MatrixXd::Zero(10, 10);
  for (int k = 0; k < 10; ++k) {
    const formats::NastranMode& m = op2.modes()[static_cast<std::size_t>(9 - k)];
    const double w = kTwoPi * m.f_hz;
    phig.col(k) = phi.col(9 - k);
    lama(k, 0) = w * w;
    mhh(k, k) = m.generalized_mass;
    normalised.col(k) = phi.col(9 - k) / std::sqrt(m.generalized_mass);
    khh(k, k) = w * w;
  }
  const Dir dir;
  dir.Write("beam_t.op4", test::TextOp4({{"PHIG", phig}, {"LAMA", lama}, {"MHH", mhh}}));
  dir.Write("beam_b.op4", test::BinaryWriter(false, 8).File({{"KHH", khh}, {"PHIGN", normalised}}));

  const BudgetResult reference = Evaluate(LoadBudgetFile(kBeam));
  const std::string rows = "rows: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]";
  const struct {
    const char* what;
    std::string yaml;
    std::vector<std::string> notes;
  } cases[] = {
      {"text, masses as a diagonal", BeamFromOp4("beam_t.op4", "matrices: {phi: PHIG, lambda: LAMA, mass: MHH}\n    " + rows),
       {"modes from beam_t.op4 (OP4, text; modes sorted by frequency; eigenvectors from matrix PHIG (66x10), "
        "eigenvalues LAMA, generalised masses MHH): 10 in the file, 456.66-11112 Hz",
        "mass-normalised: each eigenvector divided by the square root of its generalised mass (0.003668 to 0.02217 in "
        "the model's units)"}},
      {"binary big-endian 8-byte words, mass-normalised shapes, KHH as the eigenvalues",
       BeamFromOp4("beam_b.op4", "matrices: {phi: PHIGN, lambda: KHH}\n    " + rows),
       {"modes from beam_b.op4 (OP4, binary, big-endian, 8-byte words; modes sorted by frequency; eigenvectors from "
        "matrix PHIGN (66x10), eigenvalues KHH): 10 in the file, 456.66-11112 Hz",
        "the file holds no generalised masses (matrices: gives no mass): its eigenvectors are taken as "
        "mass-normalised"}},
  };
  for (const auto& c : cases) {
    CAPTURE(c.what);
    const Budget b = LoadBudgetFile(dir.Write("b.yaml", c.yaml));
    const ModalModel& m = *b.FindPath("arm").modal;
    REQUIRE(m.notes.size() >= 2);
    CHECK(m.notes[0] == c.notes[0]);
    CHECK(m.notes[1] == c.notes[1]);
    const BudgetResult r = Evaluate(b);
    for (std::size_t o = 0; o < 2; ++o) {
      CAPTURE(o);
      const ContributorResult& a = test::ContributorOf(reference.outputs[o], "actuator");
      const ContributorResult& x = test::ContributorOf(r.outputs[o], "actuator");
      REQUIRE(x.exact_variance.has_value());
      // The same numbers: only the eigenvalue's round trip sqrt((2 pi f)^2) / 2 pi differs.
      CHECK(std::abs(x.variance - a.variance) <= 1e-12 * a.variance);
      CHECK(std::abs(*x.exact_variance - *a.exact_variance) <= 1e-12 * *a.exact_variance);
    }
  }
}

// Two masses on springs, ground -k- m1 -k- m2, in the file as unnormalised
// modes (the first component 1) with their generalised masses.
struct Chain {
  double m = 2.0, k = 1000.0, zeta = 0.02;
  Eigen::Matrix2d K, M, phi, C;
  Eigen::Vector2d lambda, mass;
  Chain() {
    K << 2 * k, -k, -k, k;
    M = m * Eigen::Matrix2d::Identity();
    const double a = k / m, s5 = std::sqrt(5.0);
    lambda << a * (3 - s5) / 2, a * (3 + s5) / 2;
    const double r[2] = {(1 + s5) / 2, (1 - s5) / 2};  // v2 / v1 = 2 - lambda / a
    for (int i = 0; i < 2; ++i) {
      phi.col(i) << 1.0, r[i];
      mass(i) = m * (1 + r[i] * r[i]);
    }
    // Modal damping as a physical C = M Phi diag(2 zeta w / m_i) Phi^T M.
    Eigen::Matrix2d d = Eigen::Matrix2d::Zero();
    for (int i = 0; i < 2; ++i) d(i, i) = 2 * zeta * std::sqrt(lambda(i)) / mass(i);
    C = M * phi * d * phi.transpose() * M;
  }
  // Displacement per force, outputs x inputs, at f_hz.
  Eigen::Matrix2cd H(double f_hz) const {
    const double w = kTwoPi * f_hz;
    const Eigen::Matrix2cd z = K.cast<std::complex<double>>() - w * w * M.cast<std::complex<double>>() +
                               std::complex<double>(0, w) * C.cast<std::complex<double>>();
    return z.inverse();
  }
};

std::string ChainBudget(const std::string& path_keys) {
  return R"(name: chain
grid: {type: log, min_hz: 0.1, max_hz: 100, points: 400}
sources:
  - {name: force, unit: N, channels: [f1, f2], spectrum: {type: flat, level: 1}}
paths:
  - name: p
    type: modal
    file: chain.op4
    inputs: {f1: "1:T1", f2: "2:T1"}
    outputs: {x1: "1:T1", x2: "2:T1"}
    damping: 0.02
    length_unit: m
    input_unit: N
    output_unit: mm
)" + path_keys + R"(
contributors:
  - {name: c, source: force, path: p}
outputs:
  - {name: x2, signal: x2, unit: mm}
)";
}

TEST_CASE("a two-mass chain from OP4 matrices against its closed form (K - w^2 M + j w C)^-1") {
  const Chain chain;
  const Dir dir;
  // The rows as the g-set of two grids with one DOF each (T1), scalar
  // points written as GRID:COMPONENT.
  dir.Write("chain.op4", test::TextOp4({{"PHI", chain.phi}, {"EIGS", chain.lambda.transpose()}, {"GM", chain.mass}}));
  const Budget b = LoadBudgetFile(
      dir.Write("b.yaml", ChainBudget("    matrices: {phi: PHI, lambda: EIGS, mass: GM}\n    rows: [\"1:T1\", \"2:T1\"]")));
  const FrequencyModel h = b.FindPath("p").Model();
  double worst = 0.0;
  for (double f : {0.01, 1.0, 3.4, 3.5, 5.0, 9.1, 9.2, 30.0, 300.0}) {
    const Eigen::Matrix2cd expected = chain.H(f) * 1e3;  // mm per N
    const Eigen::MatrixXcd got = h.At(f);
    REQUIRE(got.rows() == 2);
    REQUIRE(got.cols() == 2);
    worst = std::max(worst, (got - expected).norm() / expected.norm());
  }
  MESSAGE("chain: largest relative difference from (K - w^2 M + j w C)^-1: " << worst);
  CHECK(worst <= 1e-12);
  // H(0) is K^-1 = [[1, 1], [1, 2]] / k.
  CHECK(std::abs(h.At(1e-6)(1, 1).real() - 2e3 / chain.k) <= 1e-9 * 2e3 / chain.k);
}

TEST_CASE("bad OP4 modal keys: located errors naming the rule and what the file holds") {
  const Chain chain;
  const Dir dir;
  Eigen::MatrixXd coupled = chain.mass.asDiagonal();
  coupled(0, 1) = 0.5;
  Eigen::Vector2d negative = chain.mass;
  negative(1) = -1.0;
  dir.Write("chain.op4", test::TextOp4({{"PHI", chain.phi},
                                        {"EIGS", chain.lambda},
                                        {"GM", chain.mass},
                                        {"THREE", Eigen::Vector3d(1, 2, 3)},
                                        {"COUPLED", coupled},
                                        {"NEG", negative}}));
  const std::string good = "    matrices: {phi: PHI, lambda: EIGS, mass: GM}\n    rows: [\"1:T1\", \"2:T1\"]";
  const auto error = [&](const std::string& from, const std::string& to) {
    return test::ErrorOfBudget(dir.Write("b.yaml", ChainBudget(test::Replace(good, from, to))));
  };
  REQUIRE(test::ErrorOfBudget(dir.Write("b.yaml", ChainBudget(good))) == "(no InputError)");
  using test::CheckLocated;
  CheckLocated(error("phi: PHI", "phi: PHIG"), "paths[0].matrices",
               "chain.op4: no matrix 'PHIG'");
  CHECK(test::Contains(error("phi: PHI", "phi: PHIG"), "PHI, EIGS, GM"));
  CheckLocated(error("lambda: EIGS", "lambda: THREE"), "paths[0].matrices",
               "matrix 'THREE' is 3x1 but 'PHI' has 2 column(s) (modes): the eigenvalues need one per mode");
  CheckLocated(error("mass: GM", "mass: COUPLED"), "paths[0].matrices",
               "matrix 'COUPLED' is not diagonal (row 1, column 2 is 0.5)");
  CheckLocated(error("mass: GM", "mass: NEG"), "paths[0].matrices",
               "matrix 'NEG': mode 2 has the generalised mass -1; a mass must be > 0");
  CheckLocated(error("rows: [\"1:T1\", \"2:T1\"]", "rows: [1]"), "paths[0].matrices",
               "6 row DOF(s) given (rows:) but 'PHI' has 2 rows");
  CheckLocated(error("\"2:T1\"]", "\"1:T1\"]"), "paths[0].matrices",
               "rows: 1:T1 is given for row 2 and for row 1");
  CheckLocated(error("\"2:T1\"]", "\"2:T9\"]"), "paths[0].rows[1]", "'2:T9' is not a Nastran DOF");
  CheckLocated(error("\"2:T1\"]", "two]"), "paths[0].rows[1]",
               "'two' is neither a grid id (a positive integer: its 6 rows T1..R3) nor a DOF GRID:COMPONENT");
  CheckLocated(error("rows: [\"1:T1\", \"2:T1\"]", "rows: []"), "paths[0].rows",
               "expected a list of the eigenvector rows' DOFs");
  CheckLocated(error("\n    rows: [\"1:T1\", \"2:T1\"]", ""), "paths[0]", "missing 'rows': the DOF of each row of the eigenvectors");
  CheckLocated(error("    matrices: {phi: PHI, lambda: EIGS, mass: GM}\n", ""), "paths[0]",
               "missing 'matrices': which matrices of the OP4 file chain.op4 hold the modes");
  CheckLocated(error("mass: GM", "mass: GM, damping: DHH"), "paths[0].matrices.damping",
               "unknown key 'damping'; allowed here: lambda, mass, phi");
  // A DOF the rows do not have: named with the grids they hold.
  {
    const std::string e = test::ErrorOfBudget(
        dir.Write("b.yaml", test::Replace(ChainBudget(good), "x2: \"2:T1\"", "x2: \"2:T3\"")));
    CheckLocated(e, "paths[0].file", "2:T3 is not among the rows of 'PHI', which are the DOFs of 2 grid(s): 1, 2");
  }
  // `matrices` with a file that is not OP4.
  {
    std::filesystem::copy_file(kOp2, dir.Path("beam.op2"), std::filesystem::copy_options::overwrite_existing);
    const std::string e =
        test::ErrorOfBudget(dir.Write("b.yaml", test::Replace(ChainBudget(good), "file: chain.op4", "file: beam.op2")));
    CheckLocated(e, "paths[0].matrices", "'matrices' names the matrices of an OP4 file, and beam.op2 is not one");
  }
}

}  // namespace
}  // namespace deb
