// Universal files (UFF dataset 58) in a budget (deb/load/uff_yaml.h): a PSD
// as a measured source, converted to the source's unit; FRFs as a measured
// path, chosen by their DOFs and converted to the path's units.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/formats/uff58_file.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/contains.h"
#include "tests/support/file_bytes.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using test::Contains;
using test::Replace;

constexpr double kPi = 3.141592653589793238462643383279502884;
constexpr double kGravity = 9.80665;  // m/s^2, exact by definition

const std::string kPsdFile = std::string(DEB_TEST_DATA_DIR) + "/uff/sample_dataset58_psd.uff";

class BudgetDir {
 public:
  BudgetDir() : dir_(fs::temp_directory_path() / ("deb_uff_load_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~BudgetDir() { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return (dir_ / name).string();
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

std::string ErrorOf(const std::string& budget) {
  try {
    Evaluate(LoadBudgetFile(budget));
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

const char* kSourceBudget = R"(name: uff_source
grid: {type: auto, min_hz: 1, max_hz: 3200}
sources:
  - name: table
    unit: m/s^2
    spectrum: {type: measured, file: psd.uff}
paths:
  - {name: g, type: gain, gain: 1, input_unit: m/s^2, output_unit: m/s^2, outputs: [a]}
contributors:
  - {name: table, source: table, path: g}
outputs:
  - {name: acceleration, signal: a, unit: m/s^2}
)";

// The integral of the PSD the fixture tabulates, interpolated log-log (a
// power law between two points, linear where an end is 0), from 1 Hz.
double LogLogIntegral(const std::vector<double>& f, const std::vector<double>& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < f.size(); ++i) {
    const double f1 = f[i], f2 = f[i + 1], s1 = s[i], s2 = s[i + 1];
    if (s1 <= 0.0 || s2 <= 0.0) {
      sum += 0.5 * (s1 + s2) * (f2 - f1);
      continue;
    }
    const double b = std::log(s2 / s1) / std::log(f2 / f1);
    sum += std::abs(b + 1.0) < 1e-12 ? s1 * f1 * std::log(f2 / f1)
                                     : s1 * f1 / (b + 1.0) * (std::pow(f2 / f1, b + 1.0) - 1.0);
  }
  return sum;
}

TEST_CASE("a PSD dataset in g^2/Hz is a measured source, converted to the source's unit") {
  const BudgetDir dir;
  dir.Write("psd.uff", test::ReadAll(kPsdFile));
  const Budget b = LoadBudgetFile(dir.Write("b.yaml", kSourceBudget));
  const Source& s = b.FindSource("table");
  CHECK(s.unit == "m/s^2");
  // The table is in the file's unit, the source in the budget's.
  CHECK_MESSAGE(Contains(s.spectrum->Describe(), "96.17038422249999 x [measured"), s.spectrum->Describe());
  CHECK_MESSAGE(Contains(s.spectrum->Describe(), "PSD in (gravity)^2/Hz]"), s.spectrum->Describe());
  CHECK(s.channel_names == std::vector<std::string>{"Pilot 1"});
  // Data lines 1 and 87 of the file: 1 Hz 1.255863E-06, 172 Hz 1.236371E-04 (g^2/Hz).
  const double g2 = kGravity * kGravity;
  CHECK(s.spectrum->Psd(1.0)(0) == doctest::Approx(1.255863E-06 * g2).epsilon(1e-15));
  CHECK(s.spectrum->Psd(172.0)(0) == doctest::Approx(1.236371E-04 * g2).epsilon(1e-15));
  CHECK(s.spectrum->Psd(3200.0)(0) == doctest::Approx(2.634827E-10 * g2).epsilon(1e-15));

  // Without a unit the source is in the file's: g, read as gravity.
  const Budget in_g = LoadBudgetFile(dir.Write("g.yaml", Replace(Replace(kSourceBudget, "    unit: m/s^2\n", ""),
                                                                  "input_unit: m/s^2", "input_unit: gravity")));
  CHECK(in_g.FindSource("table").unit == "gravity");
  CHECK(in_g.FindSource("table").spectrum->Psd(172.0)(0) == 1.236371E-04);

  // The variance is the integral of the interpolated table over 1-3200 Hz.
  const std::vector<formats::Uff58Record> records = formats::ReadUff58(kPsdFile);
  const std::vector<double> f(records[0].x.begin() + 1, records[0].x.end());
  std::vector<double> psd;
  for (std::size_t i = 1; i < records[0].points(); ++i) psd.push_back(records[0].y[i].real() * g2);
  const double expected = LogLogIntegral(f, psd);
  const double variance = Evaluate(b).outputs[0].variance;
  MESSAGE("variance " << variance << " (m/s^2)^2, the table's log-log integral " << expected << ", relative difference "
                      << std::abs(variance - expected) / expected);
  CHECK(variance == doctest::Approx(expected).epsilon(1e-12));
}

TEST_CASE("an ASD dataset is squared; an auto spectrum counts only as a density") {
  const BudgetDir dir;
  const std::string psd = test::ReadAll(kPsdFile);
  const std::string latin_label = "g\xB2/Hz               ";  // A20
  REQUIRE(latin_label.size() == 20);
  const std::string asd = Replace(Replace(psd, latin_label, "g/sqrt(Hz)          "), latin_label, "g/sqrt(Hz)          ");
  dir.Write("psd.uff", asd);
  const std::string budget = dir.Write("b.yaml", kSourceBudget);
  const Budget b = LoadBudgetFile(budget);
  const double g2 = kGravity * kGravity;
  CHECK(b.FindSource("table").spectrum->Psd(172.0)(0) == doctest::Approx(1.236371E-04 * 1.236371E-04 * g2).epsilon(1e-15));

  // Function type 2 (auto spectrum) in g^2/Hz: a density, read as the PSD.
  dir.Write("psd.uff", Replace(psd, "    9         0    0", "    2         0    0"));
  CHECK(LoadBudgetFile(budget).FindSource("table").spectrum->Psd(172.0)(0) ==
        doctest::Approx(1.236371E-04 * g2).epsilon(1e-15));
  // ... but in g^2 it is a power spectrum: refused.
  std::string power = Replace(psd, "    9         0    0", "    2         0    0");
  power = Replace(Replace(power, latin_label, "g^2                 "), latin_label, "g^2                 ");
  dir.Write("psd.uff", power);
  const std::string e = ErrorOf(budget);
  CHECK_MESSAGE(Contains(e, "b.yaml:6:"), e);
  CHECK_MESSAGE(Contains(e, "dataset #1 (auto spectrum, response 'Pilot 1' 0:scalar, reference 0:scalar) is in "
                            "'gravity^2' (records 9 and 10), which is no density"), e);
  CHECK_MESSAGE(Contains(e, "export it as a PSD"), e);
}

TEST_CASE("a source's datasets are chosen by response DOF or number, and a missing one is listed") {
  const BudgetDir dir;
  // Two PSDs: the fixture, and a copy of it named 'Top' at DOF 7:+Z.
  const std::string psd = test::ReadAll(kPsdFile);
  const std::string second = Replace(psd, "Pilot 1            0   0", "Top                7   3");
  dir.Write("psd.uff", psd + "\n" + second);
  const std::string both = dir.Write("b.yaml", kSourceBudget);
  const std::string e = ErrorOf(both);
  CHECK_MESSAGE(Contains(e, "holds 2 PSDs and auto spectra; choose with 'responses' (DOFs) or 'datasets' (numbers): "
                            "#1 (PSD, response 'Pilot 1' 0:scalar, reference 0:scalar), #2 (PSD, response 'Top' 7:+Z, "
                            "reference 0:scalar)"), e);
  const Budget by_dof = LoadBudgetFile(dir.Write("dof.yaml", Replace(kSourceBudget, "file: psd.uff}", "file: psd.uff, responses: ['7:+Z']}")));
  CHECK(by_dof.FindSource("table").channel_names == std::vector<std::string>{"Top"});
  const Budget by_number = LoadBudgetFile(dir.Write(
      "n.yaml", Replace(Replace(kSourceBudget, "file: psd.uff}", "file: psd.uff, datasets: [1, 2]}"), "gain: 1,", "gain: [[1, 1]],")));
  CHECK(by_number.FindSource("table").channel_names == std::vector<std::string>{"Pilot 1", "Top"});
  CHECK(by_number.FindSource("table").spectrum->channels() == 2);
  const std::string missing = ErrorOf(dir.Write("m.yaml", Replace(kSourceBudget, "file: psd.uff}", "file: psd.uff, responses: ['7:-Z']}")));
  CHECK_MESSAGE(Contains(missing, "m.yaml:6:"), missing);
  CHECK_MESSAGE(Contains(missing, "holds no PSD or auto spectrum of response 7:-Z; its PSDs and auto spectra: #1 (PSD, response 'Pilot 1'"), missing);
  const std::string table = ErrorOf(dir.Write("t.yaml", Replace(kSourceBudget, "file: psd.uff}", "file: psd.uff, columns: [x]}")));
  CHECK_MESSAGE(Contains(table, "a universal file has no columns"), table);
}

// FRFs of the mass-spring-damper 1/(s^2 + 2 s + 400) (m/N), measured as
// accelerance in m/s^2/N at 400 points per decade over 0.01-1000 Hz, with
// uneven spacing and complex double values printed with 17 digits: response
// 1:+Z from reference 3:+X, and 2:+Z twice as large.
std::string FrfFile() {
  std::string text;
  char line[200];
  for (int entry = 1; entry <= 2; ++entry) {
    text += "    -1\n    58\nAccelerance\nNONE\nNONE\nNONE\nNONE\n";
    std::snprintf(line, sizeof line, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n", 4, entry, 1, 0, "stage", entry, 3,
                  "shaker", 3, 1);
    text += line;
    std::snprintf(line, sizeof line, "%10d%10d%10d%13.5E%13.5E%13.5E\n", 6, 2001, 0, 0.0, 0.0, 0.0);
    text += line;
    text += "        18    0    0    0 Frequency            Hz                  \n";
    text += "        12    1    0    0 Acceleration         m/s^2               \n";
    text += "        13    0    1    0 Force                N                   \n";
    text += "         0    0    0    0 NONE                 NONE                \n";
    for (int i = 0; i <= 2000; ++i) {
      const double f = std::pow(10.0, -2.0 + i / 400.0), w = 2.0 * kPi * f;
      const std::complex<double> s(0.0, w);
      const std::complex<double> a = static_cast<double>(entry) * s * s / (s * s + 2.0 * s + 400.0);
      std::snprintf(line, sizeof line, "%25.17E%25.17E%25.17E\n", f, a.real(), a.imag());
      text += line;
    }
    text += "    -1\n";
  }
  return text;
}

const char* kPathBudget = R"(name: uff_path
grid: {type: auto, min_hz: 0.01, max_hz: 1000}
sources:
  - {name: force, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - {name: measured, type: frf, file: frf.uff, responses: ['1:+Z', '2:+Z'], references: ['3:+X'], outputs: [x, x2], output_unit: um, input_unit: N}
  - {name: model, type: transfer_function, num: [1e6], den: [1, 2, 400], inputs: [F], outputs: [x], input_unit: N, output_unit: um}
contributors:
  - {name: measured, source: force, path: measured}
  - {name: model, source: force, path: model}
outputs:
  - {name: x, signal: x, unit: um}
)";

TEST_CASE("FRF datasets in m/s^2/N are a measured path in um/N, chosen by their DOFs") {
  const BudgetDir dir;
  dir.Write("frf.uff", FrfFile());
  const Budget b = LoadBudgetFile(dir.Write("b.yaml", kPathBudget));
  const Path& p = b.FindPath("measured");
  CHECK(p.output_names == std::vector<std::string>{"x", "x2"});
  CHECK(p.input_names == std::vector<std::string>{"3:+X"});
  CHECK(p.output_units == std::vector<std::string>{"um", "um"});
  REQUIRE(p.measured);
  // At the data points: 1e6 / (j w)^2 times the accelerance is the compliance in um/N.
  double worst = 0.0;
  for (const int i : {0, 1, 400, 1000, 1203, 2000}) {
    const double f = std::pow(10.0, -2.0 + i / 400.0);
    const std::complex<double> s(0.0, 2.0 * kPi * f);
    const std::complex<double> x = 1e6 / (s * s + 2.0 * s + 400.0);
    const Eigen::MatrixXcd h = p.measured->At(f);
    worst = std::max({worst, std::abs(h(0, 0) - x) / std::abs(x), std::abs(h(1, 0) - 2.0 * x) / std::abs(x)});
  }
  MESSAGE("largest relative difference to the compliance at the data points: " << worst);
  CHECK(worst < 1e-14);
  const OutputResult x = Evaluate(b).outputs[0];
  double measured = 0.0, model = 0.0;
  for (const auto& c : x.contributors) (c.name == "measured" ? measured : model) = c.variance;
  MESSAGE("variance measured " << measured << ", model " << model << " um^2");
  CHECK(std::abs(measured - model) / model < 1e-3);

  // Without the units the path is in the file's; without the lists, every DOF.
  const Budget own = LoadBudgetFile(dir.Write("own.yaml", Replace(kPathBudget,
      "responses: ['1:+Z', '2:+Z'], references: ['3:+X'], outputs: [x, x2], output_unit: um, input_unit: N",
      "outputs: [x, a2]")));
  CHECK(own.FindPath("measured").output_units == std::vector<std::string>{"m/s^2", "m/s^2"});
  CHECK(own.FindPath("measured").input_units == std::vector<std::string>{"N"});
}

TEST_CASE("a missing FRF, a unit that does not convert, a file without FRFs: errors at the budget's key") {
  const BudgetDir dir;
  dir.Write("frf.uff", FrfFile());
  const std::string missing = ErrorOf(dir.Write("m.yaml", Replace(kPathBudget, "references: ['3:+X']", "references: ['4:+X']")));
  CHECK_MESSAGE(Contains(missing, "m.yaml:6:"), missing);
  CHECK_MESSAGE(Contains(missing, "holds no FRF with response 1:+Z and reference 4:+X; its FRFs: #1 (FRF, response "
                                  "'stage' 1:+Z, reference 'shaker' 3:+X), #2 (FRF, response 'stage' 2:+Z, reference "
                                  "'shaker' 3:+X)"), missing);
  const std::string unit = ErrorOf(dir.Write("u.yaml", Replace(kPathBudget, "output_unit: um, input_unit: N", "output_unit: V, input_unit: N")));
  CHECK_MESSAGE(Contains(unit, "u.yaml:6:"), unit);
  CHECK_MESSAGE(Contains(unit, "is in '(m/s^2)/(N)' (records 9 and 10), which does not convert to (V)/(N)"), unit);
  const std::string dof = ErrorOf(dir.Write("d.yaml", Replace(kPathBudget, "'1:+Z'", "'1+Z'")));
  CHECK_MESSAGE(Contains(dof, "d.yaml:6:"), dof);
  CHECK_MESSAGE(Contains(dof, "'1+Z' is not a DOF NODE:DIRECTION"), dof);
  dir.Write("psd.uff", test::ReadAll(kPsdFile));
  const std::string none = ErrorOf(dir.Write("n.yaml", Replace(kPathBudget, "file: frf.uff", "file: psd.uff")));
  CHECK_MESSAGE(Contains(none, "holds no FRF (function type 4) or transmissibility (5) dataset; its datasets 58: #1 (PSD"), none);
  dir.Write("t.csv", "f_hz, x/F.re, x/F.im\n1, 1, 0\n2, 1, 0\n");
  const std::string table = ErrorOf(dir.Write("t.yaml", Replace(kPathBudget, "file: frf.uff", "file: t.csv")));
  CHECK_MESSAGE(Contains(table, "'responses' chooses datasets of a universal file (UFF 58)"), table);
  // A damaged file: the reader's error, naming the file and line.
  dir.Write("frf.uff", Replace(FrfFile(), "      2001", "      2002"));
  const std::string cut = ErrorOf(dir.Write("b.yaml", kPathBudget));
  CHECK_MESSAGE(Contains(cut, dir.Path("frf.uff") + ":2015:1: dataset #1 (58), record 12: the data (lines 14-2014) holds 6003 values"), cut);
}

}  // namespace
}  // namespace deb
