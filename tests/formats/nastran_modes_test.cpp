// Nastran normal modes (deb/formats/nastran_modes.h) from files Nastran
// wrote (tests/data/nastran: a beam's SOL 103, from the pyNastran project's
// test models, BSD-3 licence beside them), checked against the solver's own
// printout of the same run (beam_modes.f06), and from files written here in
// every byte order and word size.
//
// What the f06 and the OP2 files hold is the same model solved twice, not
// byte for byte the same numbers: their frequencies differ in the 7th digit
// (mode 9: 1.111159E+04 printed, 1.111158E+04 in the OP2s), and the
// eigenvectors of the repeated pairs (modes 1-2, 3-4, 7-8, 9-10: the beam is
// symmetric) are another basis of the same plane, with other generalised
// masses (the modes are normalised to a largest component of 1). What every
// basis shares is each pair's mass-normalised projector
//   P = sum over the pair of phi_k phi_k^T / m_k,
// which is what a modal path's H is made of: that is compared for every
// mode, and the components themselves for the modes that are not repeated.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "deb/core/error.h"
#include "deb/formats/nastran_modes.h"
#include "tests/support/contains.h"
#include "tests/support/file_bytes.h"
#include "tests/support/op2_writer.h"
#include "tests/support/punch_writer.h"

namespace deb::formats {
namespace {

const std::string kData = std::string(DEB_TEST_DATA_DIR) + "/nastran/";

// The f06's REAL EIGENVALUES table and REAL EIGENVECTOR blocks.
struct F06 {
  std::vector<std::vector<double>> table;  // per mode: number, order, eigenvalue, rad/s, cycles, gen. mass, gen. stiffness
  std::vector<std::map<long long, std::vector<double>>> vectors;  // per mode: grid -> T1..R3
};

F06 ReadF06(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  F06 f;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find("R E A L   E I G E N V A L U E S") != std::string::npos) {
      for (std::size_t j = i + 3; j < lines.size(); ++j) {
        std::istringstream row(lines[j]);
        std::vector<double> v;
        for (double x; row >> x;) v.push_back(x);
        if (v.size() != 7) break;
        f.table.push_back(v);
      }
    }
    if (lines[i].find("R E A L   E I G E N V E C T O R   N O .") != std::string::npos) {
      f.vectors.emplace_back();
      for (std::size_t j = i + 1; j < lines.size(); ++j) {
        std::istringstream row(lines[j]);
        long long id;
        std::string type;
        std::vector<double> v;
        if (!(row >> id >> type) || type != "G") {
          if (!f.vectors.back().empty()) break;
          continue;
        }
        for (double x; row >> x;) v.push_back(x);
        if (v.size() == 6) f.vectors.back()[id] = v;
      }
    }
  }
  return f;
}

std::vector<NastranDof> AllDofs(const std::vector<long long>& grids) {
  std::vector<NastranDof> dofs;
  for (long long g : grids)
    for (int c = 1; c <= 6; ++c) dofs.push_back({g, c});
  return dofs;
}

double MaxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

const std::vector<std::vector<int>> kGroups = {{0, 1}, {2, 3}, {4}, {5}, {6, 7}, {8, 9}};

TEST_CASE("both OP2 files of the beam hold the f06's modes: frequencies, projectors, components and masses") {
  const F06 f06 = ReadF06(kData + "beam_modes.f06");
  REQUIRE(f06.table.size() == 10);
  REQUIRE(f06.vectors.size() == 10);
  std::vector<long long> grids;
  for (const auto& [g, v] : f06.vectors[0]) grids.push_back(g);
  REQUIRE(grids.size() == 12);
  const std::vector<NastranDof> dofs = AllDofs(grids);
  Eigen::MatrixXd first;
  for (const char* name : {"beam_modes_m1.op2", "beam_modes_m2.op2"}) {
    CAPTURE(name);
    const NastranModeFile file(kData + name);
    CHECK(file.format() == "OP2, little-endian, 32-bit words");
    CHECK(file.shape_table() == "OUGV1");
    REQUIRE(file.modes().size() == 10);
    const Eigen::MatrixXd phi = file.Shapes(dofs, 10);
    if (first.size() == 0) first = phi;
    CHECK((phi - first).cwiseAbs().maxCoeff() == 0.0);  // the two files' blocks are ordered differently
    for (int k = 0; k < 10; ++k) {
      const NastranMode& m = file.modes()[static_cast<std::size_t>(k)];
      const std::vector<double>& row = f06.table[static_cast<std::size_t>(k)];
      CHECK(m.number == static_cast<long long>(row[0]));
      // Frequencies and eigenvalues: within one unit of the 7th printed digit.
      CHECK(std::abs(m.f_hz - row[4]) <= 1e-6 * row[4]);
      CHECK(std::abs(m.eigenvalue - row[2]) <= 1e-6 * row[2]);
    }
    // The mass-normalised projector of every mode (pair): within 1e-6 of its
    // largest entry (the f06 prints 7 digits; measured at most 2.5e-7).
    for (const auto& group : kGroups) {
      Eigen::MatrixXd p_op2 = Eigen::MatrixXd::Zero(72, 72), p_f06 = p_op2;
      for (int k : group) {
        Eigen::VectorXd v(72);
        for (std::size_t g = 0; g < grids.size(); ++g)
          for (int c = 0; c < 6; ++c)
            v(static_cast<Eigen::Index>(6 * g) + c) = f06.vectors[static_cast<std::size_t>(k)].at(grids[g])[c];
        p_f06 += v * v.transpose() / f06.table[static_cast<std::size_t>(k)][5];
        p_op2 += phi.col(k) * phi.col(k).transpose() / file.modes()[static_cast<std::size_t>(k)].generalized_mass;
      }
      CAPTURE(group[0]);
      CHECK(MaxAbs(p_op2 - p_f06) <= 1e-6 * MaxAbs(p_f06));
    }
    // Modes 5 and 6 are single: their components equal the f06's to its
    // digits (within 1e-6 of the largest, which is the last digit printed of
    // a component near 1; the numerical zeros of 1e-15 are printed as such
    // by both runs and differ), and so do their generalised masses.
    for (int k : {4, 5}) {
      Eigen::VectorXd v(72);
      for (std::size_t g = 0; g < grids.size(); ++g)
        for (int c = 0; c < 6; ++c)
          v(static_cast<Eigen::Index>(6 * g) + c) = f06.vectors[static_cast<std::size_t>(k)].at(grids[g])[c];
      CHECK((phi.col(k) - v).cwiseAbs().maxCoeff() <= 1e-6 * v.cwiseAbs().maxCoeff());
      const double gm = f06.table[static_cast<std::size_t>(k)][5];
      CHECK(std::abs(file.modes()[static_cast<std::size_t>(k)].generalized_mass - gm) <= 0.5e-6 * gm);
    }
  }
}

TEST_CASE("an OP2 file in either byte order and word size reads back the values written") {
  std::vector<test::Op2Mode> modes;
  for (int k = 1; k <= 4; ++k)
    modes.push_back({k, std::pow(2 * M_PI * 10.0 * k, 2), 2 * M_PI * 10.0 * k, 10.0 * k, 0.5 + 0.125 * k, 0.0});
  const std::vector<long long> grids = {7, 101, 102, 2001};
  const auto shape = [](std::size_t k, std::size_t g, int c) {
    return std::ldexp(static_cast<double>(1 + k + 7 * g) * (c % 2 ? -1 : 1), -c) + 1.0 / 3.0;
  };
  const std::vector<NastranDof> dofs = {{2001, 1}, {101, 3}, {7, 6}, {102, 4}, {101, 3}};
  const std::string path = (std::filesystem::temp_directory_path() / "deb_nastran_layout.op2").string();
  for (bool big : {false, true})
    for (int word : {4, 8})
      for (bool header : {true, false}) {
        CAPTURE(big);
        CAPTURE(word);
        CAPTURE(header);
        test::Op2Layout layout;
        layout.big_endian = big;
        layout.word = word;
        layout.header = header;
        test::WriteModesOp2(path, layout, modes, grids, shape);
        const NastranModeFile file(path);
        CHECK(file.format() == std::string("OP2, ") + (big ? "big" : "little") + "-endian, " +
                                   (word == 4 ? "32" : "64") + "-bit words");
        REQUIRE(file.modes().size() == 4);
        const Eigen::MatrixXd phi = file.Shapes(dofs, 3);
        REQUIRE(phi.cols() == 3);
        for (std::size_t k = 0; k < 3; ++k) {
          const auto as_written = [&](double v) { return word == 4 ? static_cast<double>(static_cast<float>(v)) : v; };
          CHECK(file.modes()[k].f_hz == as_written(modes[k].cycles));
          CHECK(file.modes()[k].generalized_mass == as_written(modes[k].generalized_mass));
          for (std::size_t i = 0; i < dofs.size(); ++i) {
            const std::size_t g = static_cast<std::size_t>(
                std::find(grids.begin(), grids.end(), dofs[i].grid) - grids.begin());
            CHECK(phi(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) ==
                  as_written(shape(k, g, dofs[i].component - 1)));
          }
        }
      }
  std::filesystem::remove(path);
}

TEST_CASE("a punch file of the f06's eigenvectors reads as printed; complex ones are refused with their line") {
  const F06 f06 = ReadF06(kData + "beam_modes.f06");
  const std::string path = (std::filesystem::temp_directory_path() / "deb_beam_modes.pch").string();
  std::vector<double> eigenvalues;
  for (const auto& row : f06.table) eigenvalues.push_back(row[2]);
  test::WritePunchModes(path, eigenvalues, f06.vectors);
  const NastranModeFile file(path);
  CHECK(file.format() == "punch");
  CHECK(file.shape_table() == "$EIGENVECTOR");
  REQUIRE(file.modes().size() == 10);
  CHECK(std::isnan(file.modes()[0].generalized_mass));
  std::vector<long long> grids;
  for (const auto& [g, v] : f06.vectors[0]) grids.push_back(g);
  const Eigen::MatrixXd phi = file.Shapes(AllDofs(grids), 10);
  for (int k = 0; k < 10; ++k) {
    // The eigenvalue as printed; the frequency from it within the 7 digits of the cycles column.
    CHECK(file.modes()[static_cast<std::size_t>(k)].eigenvalue == f06.table[static_cast<std::size_t>(k)][2]);
    CHECK(std::abs(file.modes()[static_cast<std::size_t>(k)].f_hz - f06.table[static_cast<std::size_t>(k)][4]) <=
          1e-6 * f06.table[static_cast<std::size_t>(k)][4]);
    for (std::size_t g = 0; g < grids.size(); ++g)
      for (int c = 0; c < 6; ++c)
        CHECK(phi(static_cast<Eigen::Index>(6 * g) + c, k) ==
              f06.vectors[static_cast<std::size_t>(k)].at(grids[g])[c]);  // the same text parsed
  }
  std::filesystem::remove(path);

  try {
    NastranModeFile complex(kData + "fsi.pch");
    FAIL("complex eigenvectors were read");
  } catch (const InputError& e) {
    CHECK(test::Contains(e.what(), "fsi.pch:5: complex eigenvectors ($REAL-IMAGINARY OUTPUT"));
  }
}

TEST_CASE("bad files: a located error naming the byte or line, the table and what the file holds") {
  const std::string m1 = kData + "beam_modes_m1.op2";
  const std::string bytes = test::ReadAll(m1);
  const std::string path = (std::filesystem::temp_directory_path() / "deb_bad.op2").string();
  const auto write = [&](const std::string& content) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << content;
  };
  const auto error_of = [&](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const auto read_all = [&] {
    const NastranModeFile file(path);
    file.Shapes({{11, 3}}, static_cast<int>(file.modes().size()));
  };

  SUBCASE("truncated anywhere") {
    // Every cut inside the blocks read, and a spread of others.
    int cuts = 0;
    for (std::size_t cut = 13; cut < bytes.size(); cut += (cut > 10000 && cut < 21000) ? 7 : 997) {
      write(bytes.substr(0, cut));
      const std::string e = error_of(read_all);
      CAPTURE(cut);
      CHECK(test::Contains(e, path + ": byte "));
      ++cuts;
    }
    CHECK(cuts > 1400);
  }
  SUBCASE("a record whose length markers disagree") {
    std::string b = bytes;
    b[10400] = static_cast<char>(b[10400] + 1);  // the length of LAMA's identification record
    write(b);
    CHECK(test::Contains(error_of(read_all), ": byte "));
  }
  SUBCASE("the LAMA record is not 7 words per mode") {
    // LAMA's eigenvalue record: key 70 at byte 11028, its 280 bytes at 11040.
    std::string b = bytes;
    const unsigned char key69[4] = {69, 0, 0, 0}, len276[4] = {20, 1, 0, 0};
    b.replace(11028 + 4, 4, reinterpret_cast<const char*>(key69), 4);
    b.replace(11040, 4, reinterpret_cast<const char*>(len276), 4);
    b.replace(11040 + 4 + 276, 4, reinterpret_cast<const char*>(len276), 4);
    b.erase(11040 + 4 + 276 + 4, 4);
    write(b);
    CHECK(test::Contains(error_of(read_all), "LAMA: the eigenvalue record holds 276 bytes, not a multiple of 7 words"));
  }
  SUBCASE("no eigenvectors, no eigenvalues") {
    std::string b = bytes;
    b.replace(b.find("OUGV1   "), 8, "OUGX1   ");
    write(b);
    const std::string e = error_of(read_all);
    CHECK(test::Contains(e, "no eigenvectors (OUGV1 or BOUGV1)"));
    CHECK(test::Contains(e, "The file holds PVT0, CASECC"));
    CHECK(test::Contains(e, "OUGX1"));
    b = bytes;
    b.replace(b.find("LAMA    "), 8, "XAMA    ");
    write(b);
    CHECK(test::Contains(error_of(read_all), "no eigenvalue table (LAMA)"));
  }
  SUBCASE("a grid that is not in the file, a component a scalar point has not") {
    write(bytes);
    const NastranModeFile file(path);
    CHECK(error_of([&] { file.Shapes({{11, 3}, {2001, 1}}, 3); }) ==
          path + ": grid 2001 (of 2001:T1) is not in OUGV1, which holds 12 grid(s): 1-12 (the grids of the solver's "
                 "DISP output request)");
    test::Op2Layout layout;
    WriteModesOp2(path, layout, {{1, 1.0, 1.0, 1.0, 1.0, 1.0}}, {5, 6}, [](std::size_t, std::size_t, int) { return 1.0; },
                  {6});
    const NastranModeFile scalar(path);
    CHECK(scalar.Shapes({{6, 1}}, 1)(0, 0) == 1.0);
    CHECK(test::Contains(error_of([&] { scalar.Shapes({{6, 2}}, 1); }), "6:T2: point 6 is a scalar or extra point"));
  }
  SUBCASE("complex modes, or files with only one of the tables") {
    test::Op2Layout layout;
    layout.approach_code = 9;
    layout.num_wide = 14;
    const auto one = [](std::size_t, std::size_t, int) { return 1.0; };
    WriteModesOp2(path, layout, {{1, 1.0, 1.0, 1.0, 1.0, 1.0}}, {5}, one);
    CHECK(test::Contains(error_of(read_all), "OUGV1 (mode 1): complex eigenvectors (approach code 9"));
    layout = {};
    layout.eigenvectors = false;
    WriteModesOp2(path, layout, {{1, 1.0, 1.0, 1.0, 1.0, 1.0}}, {5}, one);
    CHECK(test::Contains(error_of(read_all), "no eigenvectors (OUGV1 or BOUGV1): request them with DISP(PLOT)=ALL"));
  }
  SUBCASE("neither format") {
    write("MATLAB 5.0 MAT-file");
    CHECK(test::Contains(error_of(read_all), "neither a Nastran OP2 file"));
  }
  std::filesystem::remove(path);
}

TEST_CASE("the files the fuzzer found: refused with their line") {
  const std::string corpus = std::string(DEB_SOURCE_DIR) + "/tests/fuzz/corpus/nastran_modes/";
  // A subcase number of 130 digits (converted to an integer out of range).
  CHECK_THROWS_WITH_AS(NastranModeFile(corpus + "subcase_overflow.pch"),
                       doctest::Contains("subcase_overflow.pch:2: subcase '4444"), InputError);
}

TEST_CASE("DOF names: GRID:COMPONENT") {
  CHECK(NastranDofText(ParseNastranDof("101:T3")) == "101:T3");
  CHECK(NastranDofText(ParseNastranDof("7:r2")) == "7:R2");
  for (const char* bad : {"101", "101:T7", ":T1", "x:T1", "0:T1", "-5:T1", "101:T3 "})
    CHECK_THROWS_WITH_AS(ParseNastranDof(bad), doctest::Contains("is not a Nastran DOF"), InputError);
}

}  // namespace
}  // namespace deb::formats
