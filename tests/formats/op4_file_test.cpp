// Nastran OUTPUT4 files (deb/formats/op4_file.h) and the state_space paths
// that read them. The fixtures in tests/data/nastran were written by Nastran
// for pyNastran's tests (BSD-3, LICENSE-pyNastran.md there): the same nine
// matrices, real and complex, single and double precision, in text
// (mat_t_*) and binary (mat_b_*: little-endian, 4-byte words), each dense
// (*_dn) and in the two sparse layouts (*_s1: packed IS string headers,
// *_s2: bigmat, negative nrow). Every twin gives the same matrices, values
// checked by hand against the text, and every rule broken is an error that
// names the file, the line or byte, the matrix and the rule. Files with
// other byte orders and word sizes are made here by a writer that
// reproduces Nastran's bytes for a fixture's matrix.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/formats/op4_file.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/budget_errors.h"
#include "tests/support/contains.h"
#include "tests/support/contributor_of.h"
#include "tests/support/file_bytes.h"
#include "tests/support/op4_writer.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using formats::Op4File;
using formats::Op4Matrix;
using test::Contains;
using test::Replace;
using test::BinaryWriter;
using test::Matrices;
using test::TextOp4;

const std::string kData = std::string(DEB_TEST_DATA_DIR) + "/nastran/";

class TempDir {
 public:
  TempDir() : dir_(fs::temp_directory_path() / ("deb_op4_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~TempDir() { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return Path(name);
  }

 private:
  fs::path dir_;
};

// What the fixtures hold, in the text files' order (the binary ones hold
// the same matrices in another order).
struct Expected {
  const char* name;
  int rows, cols, form, type;
};
const Expected kFixture[] = {
    {"EYE10", 10, 10, 6, 2},  {"EYE5CD", 5, 5, 6, 4},  {"LOW", 5, 7, 2, 2},
    {"NULL", 3, 3, 6, 2},     {"RND1CD", 4, 4, 1, 4},  {"RND1CS", 4, 4, 1, 3},
    {"RND1RD", 4, 4, 1, 2},   {"RND1RS", 4, 4, 1, 1},  {"STRINGS", 30, 20, 2, 1}};
const char* const kBinaryOrder[] = {"EYE10", "LOW", "RND1RS", "RND1RD", "RND1CS", "RND1CD", "NULL", "STRINGS", "EYE5CD"};
const char* const kLayouts[] = {"dn", "s1", "s2"};

std::string Fixture(const char* encoding, const char* layout) {
  return kData + "mat_" + encoding + "_" + layout + ".op4";
}

// The message of the InputError that opening the file and reading all its
// matrices throws, or "(no error)".
std::string ErrorOfFile(const std::string& path) {
  return test::InputErrorOf([&] {
    const Op4File f(path);
    for (const Op4Matrix& m : f.matrices()) f.ComplexMatrix(m.name);
  });
}

TEST_CASE("the fixtures: nine matrices of every type, in text and binary, dense and in both sparse layouts") {
  for (const char* layout : kLayouts) {
    CAPTURE(layout);
    const Op4File text(Fixture("t", layout)), binary(Fixture("b", layout));
    CHECK(text.encoding() == Op4File::Encoding::kText);
    CHECK(text.EncodingText() == "text");
    CHECK(binary.encoding() == Op4File::Encoding::kBinary);
    CHECK(binary.EncodingText() == "binary, little-endian, 4-byte words");
    REQUIRE(text.matrices().size() == 9);
    REQUIRE(binary.matrices().size() == 9);
    for (std::size_t i = 0; i < 9; ++i) {
      const Op4Matrix& m = text.matrices()[i];
      CHECK(m.name == kFixture[i].name);
      CHECK(m.rows == kFixture[i].rows);
      CHECK(m.cols == kFixture[i].cols);
      CHECK(m.form == kFixture[i].form);
      CHECK(m.type == kFixture[i].type);
      CHECK(m.complex() == (m.type >= 3));
      CHECK(binary.matrices()[i].name == kBinaryOrder[i]);
    }
    CHECK(text.NamesText() == "EYE10, EYE5CD, LOW, NULL, RND1CD, RND1CS, RND1RD, RND1RS, STRINGS");
  }
}

// Agreement of the twins. The text prints each number with 1P,3E23.16 (17
// significant digits) or 1P,3E22.15 (16). 17 digits identify a double, and
// a single-precision value widened to double, exactly: those matrices must
// equal the binary ones bit for bit. 16 digits are within half a unit of
// the 16th (5e-16 relative); the matrices printed so (EYE5CD, NULL,
// STRINGS) hold small integers, exact in 16 digits. So the tolerance is
// zero for every matrix, and the measured difference is zero: the test
// fails on any difference at all. The three layouts of one encoding hold
// the same numbers and must agree exactly too.
TEST_CASE("text and binary twins, and the dense and both sparse layouts, give identical matrices") {
  for (const Expected& e : kFixture) {
    CAPTURE(e.name);
    Eigen::MatrixXcd first;
    for (const char* layout : kLayouts) {
      CAPTURE(layout);
      const Eigen::MatrixXcd t = Op4File(Fixture("t", layout)).ComplexMatrix(e.name);
      const Eigen::MatrixXcd b = Op4File(Fixture("b", layout)).ComplexMatrix(e.name);
      REQUIRE(t.rows() == e.rows);
      REQUIRE(t.cols() == e.cols);
      REQUIRE(b.rows() == e.rows);
      REQUIRE(b.cols() == e.cols);
      CHECK((t.array() == b.array()).all());
      CHECK((t - b).cwiseAbs().maxCoeff() == 0.0);
      if (first.size() == 0) first = t;
      CHECK((t.array() == first.array()).all());
      if (e.type <= 2) {
        // A real matrix: Matrix() gives the same values, no imaginary part.
        CHECK(Op4File(Fixture("t", layout)).Matrix(e.name) == t.real());
        CHECK(t.imag().isZero(0));
      }
    }
  }
}

TEST_CASE("values checked by hand against the text (mat_t_dn.op4)") {
  const Op4File f(Fixture("t", "dn"));
  CHECK(f.Matrix("EYE10") == Eigen::MatrixXd::Identity(10, 10));
  CHECK(f.Matrix("NULL") == Eigen::MatrixXd::Zero(3, 3));
  // LOW (lines 37-53): column j holds j from row j + 1 (columns 1-4) or
  // j - 4 (columns 6-7) down; column 5 is not written: zeros.
  Eigen::MatrixXd low(5, 7);
  low << 0, 0, 0, 0, 0, 0, 0,
         1, 0, 0, 0, 0, 6, 0,
         1, 2, 0, 0, 0, 6, 7,
         1, 2, 3, 0, 0, 6, 7,
         1, 2, 3, 4, 0, 6, 7;
  CHECK(f.Matrix("LOW") == low);
  // RND1RD column 1, lines 96-97; column 4, lines 105-106.
  const Eigen::MatrixXd rd = f.Matrix("RND1RD");
  CHECK(rd(0, 0) == 6.2432231292689266E-01);
  CHECK(rd(1, 0) == 5.4292828510256186E-02);
  CHECK(rd(3, 0) == 6.8313830743295512E-01);
  CHECK(rd(3, 3) == 8.9266183576313551E-02);
  // RND1RS: single precision, printed with 17 digits: exactly a float.
  const Eigen::MatrixXd rs = f.Matrix("RND1RS");
  CHECK(rs(0, 0) == 6.6822248697280884E-01);
  CHECK(rs(2, 2) == 6.3007399439811707E-03);
  for (Eigen::Index i = 0; i < rs.size(); ++i) CHECK(static_cast<double>(static_cast<float>(rs(i))) == rs(i));
  // RND1CD column 1 (lines 58-60): (re, im) pairs down the rows.
  const Eigen::MatrixXcd cd = f.ComplexMatrix("RND1CD");
  CHECK(cd(0, 0) == std::complex<double>(-6.2432231292689266E-01, 6.2432231292689266E-01));
  CHECK(cd(1, 0) == std::complex<double>(-5.4292828510256186E-02, 5.4292828510256186E-02));
  CHECK(cd(3, 0) == std::complex<double>(-6.8313830743295512E-01, 6.8313830743295512E-01));
  CHECK(f.ComplexMatrix("EYE5CD") == Eigen::MatrixXcd::Identity(5, 5) * std::complex<double>(-1, 1));
  // STRINGS: odd columns j hold j in rows 3-5, 9-11, 15-17, 21-23, 27-29;
  // even ones in rows 15-17, 21-23, 27-29.
  const Eigen::MatrixXd s = f.Matrix("STRINGS");
  Eigen::MatrixXd strings = Eigen::MatrixXd::Zero(30, 20);
  for (int j = 1; j <= 20; ++j)
    for (int first = j % 2 ? 3 : 15; first <= 27; first += 6) strings.block(first - 1, j - 1, 3, 1).setConstant(j);
  CHECK(s == strings);
  CHECK(s(2, 0) == 1);
  CHECK(s(14, 1) == 2);
  CHECK(s(28, 19) == 20);
  CHECK(s(5, 0) == 0);
}

TEST_CASE("asking for a matrix: a missing name lists those present, a complex one is refused as real") {
  const std::string path = Fixture("b", "s2");
  const Op4File f(path);
  CHECK(test::InputErrorOf([&] { f.Matrix("KAA"); }) ==
        path + ": no matrix 'KAA' in the OP4 file (it holds EYE10, LOW, RND1RS, RND1RD, RND1CS, RND1CD, NULL, "
               "STRINGS, EYE5CD)");
  CHECK(Contains(test::InputErrorOf([&] { f.Matrix("low"); }), "no matrix 'low' in the OP4 file (did you mean 'LOW'?)"));
  CHECK(test::InputErrorOf([&] { f.Matrix("RND1CD"); }) ==
        path + ": matrix 'RND1CD' is complex (type 4, complex double precision); a real matrix is expected here");
  CHECK(Contains(test::InputErrorOf([&] { f.Matrix("RND1CS"); }), "(type 3, complex single precision)"));
  CHECK(f.Has("STRINGS"));
  CHECK(!f.Has("strings"));
}

// ---------------------------------------------------------------------------
// Files made here: the writers follow Nastran's layout (checked against the
// fixture's bytes), in any byte order and word size.

TEST_CASE("the test's writers reproduce Nastran's text and bytes of LOW") {
  const Eigen::MatrixXd low = Op4File(Fixture("b", "dn")).Matrix("LOW");
  // Binary: LOW is the second matrix, bytes 340 to 656 of mat_b_dn.op4.
  const std::string bytes = test::ReadAll(Fixture("b", "dn"));
  CHECK(BinaryWriter(true, 4).File({{"LOW", low}}) == bytes.substr(340, 656 - 340));
  // Text: lines 37 to 53 of mat_t_dn.op4 (CRLF there).
  std::string text = test::ReadAll(Fixture("t", "dn"));
  text.erase(std::remove(text.begin(), text.end(), '\r'), text.end());
  const std::size_t from = text.find("       7       5       2       2LOW");
  const std::size_t to = text.find("       3       3       6       2NULL");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  CHECK(TextOp4({{"LOW", low}}) == text.substr(from, to - from));
}

// A small matrix of every kind of number: negative, tiny, large, zeros inside.
Eigen::MatrixXd Sample() {
  Eigen::MatrixXd m(4, 3);
  m << 1.5, 0, -2.25e-300, 0, 0, 1e300, 3.141592653589793, 0, 0, -0.1, 0, 7;
  return m;
}

TEST_CASE("binary files in both byte orders and word sizes, and text with Fortran's number forms") {
  const TempDir dir;
  const Eigen::MatrixXd m = Sample();
  for (const bool little : {true, false})
    for (const int word : {4, 8}) {
      CAPTURE(little);
      CAPTURE(word);
      const std::string path = dir.Write("m.op4", BinaryWriter(little, word).File({{"M", m}, {"T", m.transpose()}}));
      const Op4File f(path);
      CHECK(f.EncodingText() == std::string("binary, ") + (little ? "little" : "big") + "-endian, " +
                                    std::to_string(word) + "-byte words");
      CHECK(f.Matrix("M") == m);
      CHECK(f.Matrix("T") == m.transpose());
    }
  const std::string text = TextOp4({{"M", m}});
  CHECK(Op4File(dir.Write("m.op4", text)).Matrix("M") == m);
  // D exponents, Fortran's 3-digit exponent without its letter, CRLF line ends.
  const std::string fortran = "       1       3       2       2X       1P,3E23.16\r\n"
                              "       1       1       3\r\n"
                              " 1.5000000000000000D+00 2.5000000000000000-100-3.0000000000000000d-01\r\n"
                              "       2       1       1\r\n"
                              " 1.0000000000000000E+00\r\n";
  const Eigen::MatrixXd x = Op4File(dir.Write("x.op4", fortran)).Matrix("X");
  CHECK(x(0, 0) == 1.5);
  CHECK(x(1, 0) == 2.5e-100);
  CHECK(x(2, 0) == -0.3);
}

// ---------------------------------------------------------------------------
// Bad input: each an InputError naming the file, the line (text) or byte
// (binary), the matrix and the rule.

// `bytes` with the 4-byte little-endian word at `at` set to `v`.
std::string Patched(std::string bytes, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes[at + static_cast<std::size_t>(i)] = static_cast<char>(v >> (8 * i) & 0xFF);
  return bytes;
}

TEST_CASE("binary: truncated at any point, a wrong length marker, a column out of range, a value not finite") {
  const TempDir dir;
  const std::string good = test::ReadAll(Fixture("b", "dn"));
  REQUIRE(good.size() == 4220);
  const std::string path = dir.Path("b.op4");
  SUBCASE("truncated") {
    // Offsets: in the first length, inside the header, just after it, two
    // bytes into the next record's length, inside a column, inside the last
    // record's closing length.
    const struct {
      std::size_t size;
      const char* part;
    } cuts[] = {
        {4, ": byte 0: a record of 24 bytes starts here, but the file ends 0 bytes later"},
        {20, ": byte 0: a record of 24 bytes starts here, but the file ends 16 bytes later"},
        {32, ": byte 32: matrix 'EYE10': the file ends inside the matrix (a column number of ncol + 1 = 11 ends"},
        {34, ": byte 32: matrix 'EYE10': 2 bytes after the last record, too few for a record's length; is the file "
             "truncated?"},
        {100, ": byte 88: matrix 'EYE10': a record of 20 bytes starts here, but the file ends 8 bytes later"},
        {good.size() - 2, ": byte 4192: matrix 'EYE5CD': a record of 20 bytes starts here, but the file ends 22"}};
    for (const auto& cut : cuts) {
      CAPTURE(cut.size);
      dir.Write("b.op4", good.substr(0, cut.size));
      const std::string message = ErrorOfFile(path);
      CHECK(message.rfind(path + cut.part, 0) == 0);
      CHECK(Contains(message, "truncated"));
    }
  }
  SUBCASE("a record whose closing length marker differs") {
    // The first column record: its length at 32, 20 bytes, closing at 56.
    dir.Write("b.op4", Patched(good, 56, 21));
    CHECK(ErrorOfFile(path) == path + ": byte 56: matrix 'EYE10': the record at byte 32 of 20 bytes ends with the "
                                      "length 21 (a Fortran record starts and ends with its length in bytes)");
    dir.Write("b.op4", Patched(good, 32, 4000));
    CHECK(Contains(ErrorOfFile(path), ": matrix 'EYE10': the record at byte 32 of 4000 bytes ends with the length"));
    dir.Write("b.op4", Patched(good, 32, 5000));
    CHECK(Contains(ErrorOfFile(path), path + ": byte 32: matrix 'EYE10': a record of 5000 bytes starts here"));
  }
  SUBCASE("a column number out of range, columns out of order, a row range past nrow") {
    dir.Write("b.op4", Patched(good, 36, 12));
    CHECK(ErrorOfFile(path) == path + ": byte 36: matrix 'EYE10': column 12 is out of range: the matrix has 10 "
                                      "columns, and column 11 ends it");
    dir.Write("b.op4", Patched(good, 36, 0));
    CHECK(Contains(ErrorOfFile(path), ": byte 36: matrix 'EYE10': column 0 is out of range"));
    dir.Write("b.op4", Patched(good, 64, 1));  // the second column record says column 1
    CHECK(Contains(ErrorOfFile(path), ": byte 64: matrix 'EYE10': column 1 follows column 1: columns must come in "
                                      "increasing order"));
    dir.Write("b.op4", Patched(good, 40, 10));  // column 1 from row 10: one value, fits
    CHECK(ErrorOfFile(path) == "(no error)");
    dir.Write("b.op4", Patched(good, 40, 11));
    CHECK(Contains(ErrorOfFile(path), ": byte 40: matrix 'EYE10': column 1: 1 value from row 11 pass the last row: "
                                      "the matrix has 10 rows"));
  }
  SUBCASE("a word count that does not match the record, an unknown type, a value not finite") {
    dir.Write("b.op4", Patched(good, 44, 4));
    CHECK(ErrorOfFile(path) == path + ": byte 44: matrix 'EYE10': column 1: the word count 4 does not match the "
                                      "record, which holds 8 bytes of values (words of 4 bytes)");
    dir.Write("b.op4", Patched(good, 16, 5));
    CHECK(ErrorOfFile(path) == path + ": byte 4: matrix 1's header: unknown type 5 (1 real single, 2 real double, 3 "
                                      "complex single, 4 complex double precision)");
    dir.Write("b.op4", Patched(good, 52, 0x7FF80000));  // the high word of EYE10(1, 1): NaN
    CHECK(ErrorOfFile(path) == path + ": byte 48: matrix 'EYE10': column 1, row 1: the value is not finite (nan)");
  }
}

TEST_CASE("text: truncated, a column out of range, rows past nrow, strings, an unknown type, a number that does not parse") {
  const TempDir dir;
  const std::string path = dir.Path("t.op4");
  const std::string dense = test::ReadAll(Fixture("t", "dn"));
  const auto error_of = [&](const std::string& text) {
    dir.Write("t.op4", text);
    return ErrorOfFile(path);
  };
  SUBCASE("truncated after the header, inside a column's record, inside a number") {
    CHECK(error_of(dense.substr(0, dense.find('\n') + 1)) ==
          path + ":1: matrix 'EYE10': the file ends inside the matrix (a column number of ncol + 1 = 11 ends a "
                 "matrix); is it truncated?");
    CHECK(error_of(dense.substr(0, dense.find("       3       3       1"))) ==
          path + ":5: matrix 'EYE10': the file ends inside the matrix, in or after column 2 (a column number of ncol "
                 "+ 1 = 11 ends a matrix); is it truncated?");
    CHECK(error_of(dense.substr(0, dense.find("       3       3       1") + 20)) ==
          path + ":6:17: matrix 'EYE10': a column record holds its column number, first row and word count in three "
                 "8-character fields; columns 17-24 should hold its word count, not '    '");
    CHECK(error_of(dense.substr(0, dense.find("       3       3       1") + 24 + 2 + 10)) ==
          path + ":7:1: matrix 'EYE10': the line holds 0 numbers of the 1 expected here (the header's format: 3 "
                 "numbers of 23 characters a line)");
  }
  SUBCASE("a column number out of range, out of order; a row range past nrow") {
    CHECK(error_of(Replace(dense, "       1       1       1\r\n", "      12       1       1\r\n")) ==
          path + ":2:1: matrix 'EYE10': column 12 is out of range: the matrix has 10 columns, and column 11 ends it");
    CHECK(error_of(Replace(dense, "       2       2       1\r\n", "       1       2       1\r\n")) ==
          path + ":4:1: matrix 'EYE10': column 1 follows column 1: columns must come in increasing order");
    CHECK(error_of(Replace(dense, "       1       2       4\r\n", "       1       3       4\r\n")) ==
          path + ":38:9: matrix 'LOW': column 1: 4 values from row 3 pass the last row: the matrix has 5 rows");
    CHECK(error_of(Replace(dense, "       1       1       2\r\n", "       1       1       3\r\n")) ==
          path + ":25:9: matrix 'EYE5CD': column 1: 3 numbers for a complex matrix, whose values are (real, "
                 "imaginary) pairs");
  }
  SUBCASE("sparse strings: a row past nrow, more words than the column's count") {
    const std::string s1 = test::ReadAll(Fixture("t", "s1")), s2 = test::ReadAll(Fixture("t", "s2"));
    // IS = 196609 = 1 + 65536 * 3: row 1, 2 words; row 11 of 10 instead.
    CHECK(error_of(Replace(s1, "  196609\r\n", "  196619\r\n")) ==
          path + ":3:1: matrix 'EYE10': column 1: 1 value from row 11 pass the last row: the matrix has 10 rows");
    CHECK(error_of(Replace(s2, "       3       1\r\n", "       3      11\r\n")) ==
          path + ":3:1: matrix 'EYE10': column 1: 1 value from row 11 pass the last row: the matrix has 10 rows");
    CHECK(error_of(Replace(s2, "       1       0       4\r\n", "       1       0       3\r\n")) ==
          path + ":3:1: matrix 'EYE10': column 1: its strings hold more words than the 3 its record gives");
    CHECK(error_of(Replace(s2, "       3       1\r\n", "       2       1\r\n")) ==
          path + ":3:1: matrix 'EYE10': column 1: a string of 1 word is no whole number of double precision values "
                 "(2 words each)");
  }
  SUBCASE("a header's unknown type, its number format; a number that does not parse or is not finite") {
    CHECK(error_of(Replace(dense, "       2EYE10", "       7EYE10")) ==
          path + ":1:1: matrix 1's header: unknown type 7 (1 real single, 2 real double, 3 complex single, 4 complex "
                 "double precision)");
    CHECK(Contains(error_of(Replace(dense, "EYE10   1P,3E23.16", "EYE10   1P,3X23.16")),
                   path + ":1:41: matrix 'EYE10': the header's number format '1P,3X23.16' (from column 41) is not a "
                          "Fortran format"));
    CHECK(error_of(Replace(dense, " 1.0000000000000000E+00", " 1.000000000000x000E+00")) ==
          path + ":3:1: matrix 'EYE10': column 1, row 1: ' 1.000000000000x000E+00' is not a number (a Fortran E or "
                 "D field of 23 characters)");
    CHECK(error_of(Replace(dense, " 1.0000000000000000E+00", "                    NaN")) ==
          path + ":3:1: matrix 'EYE10': column 1, row 1: '                    NaN' is not finite");
  }
  SUBCASE("not an OP4 file, an empty file, a name given twice") {
    CHECK(error_of("f_hz, psd\n1, 2\n") ==
          path + ":1:1: matrix 1's header: a header holds ncol, nrow, form and type in four 8-character fields, the "
                 "name in columns 33-40 and the format of the numbers (e.g. 1P,3E23.16); this line holds 9 characters: "
                 "'f_hz, psd'; is this an OP4 file?");
    CHECK(error_of("") == path + ": the OP4 file holds no matrix (it is empty or blank)");
    dir.Write("t.op4", TextOp4({{"M", Sample()}, {"M", Sample()}}));
    CHECK(test::InputErrorOf([&] { Op4File(path).Matrix("M"); }) ==
          path + ": the OP4 file holds 2 matrices named 'M' (numbers 1 and 2); which one is meant is not clear");
  }
}

TEST_CASE("a matrix's size is checked against the bound before it is allocated, a complex value counting twice") {
  const TempDir dir;
  // 100000 x 100000 with no column written: a valid file, but 1e10 values.
  const std::string path = dir.Write("big.op4", "  100000  100000       2       2BIG     1P,3E23.16\n"
                                                "  100001       1       1\n"
                                                " 1.0000000000000000E+00\n");
  const Op4File f(path);
  CHECK(f.matrices()[0].rows == 100000);
  CHECK(test::InputErrorOf([&] { f.Matrix("BIG"); }) ==
        path + ": matrix 'BIG' is 100000x100000, 10000000000 values, more than the " +
            std::to_string(limits::kMaxMatElements) + " deb reads of one matrix");
  // A complex value is two numbers: 30 000 000 of them pass the bound, as
  // complex, and a real matrix of that size does not. (A fuzzed file of
  // 49.5 million complex values took 800 MB and timed out.)
  const std::string complex = dir.Write("complex.op4", "    3000   10000       2       4Z       1P,3E23.16\n"
                                                       "    3001       1       1\n"
                                                       " 1.0000000000000000E+00\n");
  CHECK(test::InputErrorOf([&] { Op4File(complex).ComplexMatrix("Z"); }) ==
        complex + ": matrix 'Z' is 10000x3000, 30000000 complex values, 60000000 numbers, more than the " +
            std::to_string(limits::kMaxMatElements) + " deb reads of one matrix");
  const std::string real = dir.Write("real.op4", "    3000   10000       2       2R       1P,3E23.16\n"
                                                 "    3001       1       1\n"
                                                 " 1.0000000000000000E+00\n");
  CHECK(Op4File(real).Matrix("R").isZero(0));
}

// ---------------------------------------------------------------------------
// Budgets: a state_space path from an OP4 file.

using test::CheckLocated;
using test::ErrorOfBudget;
using test::MatrixYaml;

// Two resonances (12 Hz, 70 Hz), two force inputs, one displacement output:
// the plant of tests/formats/mat_file_test.cpp.
struct Plant {
  Eigen::MatrixXd a, b, c, d;
  Plant() : a(4, 4), b(4, 2), c(1, 4), d(1, 2) {
    constexpr double kTwoPi = 6.283185307179586476925286766559;
    const double w1 = kTwoPi * 12, w2 = kTwoPi * 70;
    a << 0, 1, 0, 0, -w1 * w1, -2 * 0.03 * w1, 0, 0, 0, 0, 0, 1, 0, 0, -w2 * w2, -2 * 0.01 * w2;
    b << 0, 0, 1.3, 0.2, 0, 0, -0.4, 0.9;
    c << 0.8, 0, 0.5, 0.001;
    d << 0, 0;  // white forces: a feedthrough would make the variance infinite
  }
  Matrices Named(bool with_d = true) const {
    Matrices m = {{"AMAT", a}, {"BMAT", b}, {"CMAT", c}};
    if (with_d) m.push_back({"DMAT", d});
    return m;
  }
};

const char* kBudget = R"(name: ss
grid: {type: auto, min_hz: 0.01, max_hz: 10000}
sources:
  - {name: force, unit: N, channels: [F1, F2], spectrum: {type: flat, level: 2.5}}
paths:
  - name: inline
    type: state_space
    A: AAA
    B: BBB
    C: CCC
    D: DDD
    inputs: [F1, F2]
    outputs: [z]
    input_unit: N
    output_unit: m
  - name: op4
    type: state_space
    file: plant.dat
    matrices: {A: AMAT, B: BMAT, C: CMAT, D: DMAT}
    inputs: [F1, F2]
    outputs: [z]
    input_unit: N
    output_unit: m
contributors:
  - {name: inline, source: force, path: inline, exact: required}
  - {name: op4, source: force, path: op4, exact: required}
outputs:
  - {name: z, signal: z, unit: um}
)";

std::string BudgetText(const Plant& p) {
  std::string text = Replace(kBudget, "AAA", MatrixYaml(p.a));
  text = Replace(text, "BBB", MatrixYaml(p.b));
  text = Replace(text, "CCC", MatrixYaml(p.c));
  return Replace(text, "DDD", MatrixYaml(p.d));
}

TEST_CASE("state_space from an OP4 file, text or binary, found by its content: the RMS of the same matrices inline") {
  const TempDir dir;
  const Plant plant;
  const std::string budget = dir.Write("b.yaml", BudgetText(plant));
  const std::pair<const char*, std::string> files[] = {
      {"text", TextOp4(plant.Named())},
      {"binary little-endian", BinaryWriter(true, 4).File(plant.Named())},
      {"binary big-endian, 8-byte words", BinaryWriter(false, 8).File(plant.Named())}};
  for (const auto& file : files) {
    CAPTURE(file.first);
    dir.Write("plant.dat", file.second);  // not named .op4: found by its content
    const Budget b = LoadBudgetFile(budget);
    const Path& op4 = b.FindPath("op4");
    CHECK(op4.system.A() == plant.a);  // 17 digits in text: exact
    CHECK(op4.system.B() == plant.b);
    CHECK(op4.system.C() == plant.c);
    CHECK(op4.system.D() == plant.d);
    const BudgetResult r = Evaluate(b);
    const ContributorResult& inline_c = test::ContributorOf(r.outputs[0], "inline");
    const ContributorResult& op4_c = test::ContributorOf(r.outputs[0], "op4");
    REQUIRE(inline_c.variance > 0);
    CHECK(op4_c.variance == inline_c.variance);
    REQUIRE(op4_c.exact_variance.has_value());
    CHECK(*op4_c.exact_variance == *inline_c.exact_variance);
  }
  SUBCASE("D not mapped: zeros; no 'matrices': the names A, B, C and D") {
    dir.Write("plant.dat", TextOp4(plant.Named()));
    dir.Write("b.yaml", Replace(BudgetText(plant), ", D: DMAT}", "}"));
    CHECK(LoadBudgetFile(budget).FindPath("op4").system.D() == Eigen::MatrixXd::Zero(1, 2));
    dir.Write("plant.dat", TextOp4({{"A", plant.a}, {"B", plant.b}, {"C", plant.c}}));
    dir.Write("b.yaml", Replace(BudgetText(plant), "    matrices: {A: AMAT, B: BMAT, C: CMAT, D: DMAT}\n", ""));
    const Budget b = LoadBudgetFile(budget);
    CHECK(b.FindPath("op4").system.A() == plant.a);
    CHECK(b.FindPath("op4").system.D() == Eigen::MatrixXd::Zero(1, 2));
  }
}

TEST_CASE("state_space OP4 errors: a missing name lists those present, at its key; shapes with the file's names") {
  const TempDir dir;
  const Plant plant;
  const std::string budget = dir.Write("b.yaml", BudgetText(plant));
  const std::string op4 = dir.Write("plant.dat", TextOp4(plant.Named()));
  SUBCASE("a name the file does not hold") {
    dir.Write("b.yaml", Replace(BudgetText(plant), "B: BMAT", "B: BHH"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].matrices.B",
                 op4 + ": no matrix 'BHH' in the OP4 file (it holds AMAT, BMAT, CMAT, DMAT)");
  }
  SUBCASE("without 'matrices', a file without A") {
    dir.Write("b.yaml", Replace(BudgetText(plant), "    matrices: {A: AMAT, B: BMAT, C: CMAT, D: DMAT}\n", ""));
    CheckLocated(ErrorOfBudget(budget), "paths[1].file",
                 op4 + ": no matrix 'A' in the OP4 file (it holds AMAT, BMAT, CMAT, DMAT)");
  }
  SUBCASE("shapes: the message names deb's matrix and the file's") {
    dir.Write("b.yaml", Replace(BudgetText(plant), "B: BMAT", "B: CMAT"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].file", op4 + ": B ('CMAT') is 1x4 but A ('AMAT') is 4x4: B needs 4 rows");
  }
  SUBCASE("a complex matrix, a damaged file") {
    const std::string fixture = Fixture("t", "dn");
    dir.Write("b.yaml", Replace(Replace(BudgetText(plant), "file: plant.dat", "file: " + fixture), "A: AMAT", "A: RND1CD"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].matrices.A",
                 fixture + ": matrix 'RND1CD' is complex (type 4, complex double precision); a real matrix is expected");
    dir.Write("b.yaml", BudgetText(plant));
    dir.Write("plant.dat", Replace(TextOp4(plant.Named()), "       2AMAT", "       9AMAT"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].file", op4 + ":1:1: matrix 1's header: unknown type 9");
  }
  SUBCASE("'matrices' without 'file', with a key other than A, B, C, D") {
    dir.Write("b.yaml", Replace(BudgetText(plant), "    type: state_space\n    A: ", "    type: state_space\n    matrices: {A: AMAT}\n    A: "));
    CheckLocated(ErrorOfBudget(budget), "paths[0].matrices", "'matrices' names the matrices of a 'file'");
    dir.Write("b.yaml", Replace(BudgetText(plant), "D: DMAT}", "E: DMAT}"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].matrices.E", "unknown key 'E'");
  }
}

}  // namespace
}  // namespace deb
