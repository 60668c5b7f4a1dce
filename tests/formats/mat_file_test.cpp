// MATLAB .mat files (deb/formats/mat_file.h) and the budget paths that read them
// (state_space and modal with `file:`). The files are written here with
// matio itself, in version 5 (uncompressed and compressed) and 7.3 (HDF5):
// matrices, vectors and names read back exactly; a budget from a .mat gives
// the RMS of the same model inline or from CSV tables; every bad variable and
// hostile file is a clear error naming the file, the variable and its size.
#include <doctest/doctest.h>
#include <matio.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <regex>
#include <string>
#include <unistd.h>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/load/budget_yaml.h"
#include "deb/formats/mat_file.h"
#include "tests/support/budget_errors.h"
#include "tests/support/contains.h"
#include "tests/support/text_edit.h"
#include "tests/support/contributor_of.h"
#include "tests/support/file_bytes.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using formats::MatFile;

struct Format {
  const char* name;
  mat_ft version;
  matio_compression compression;
};
const Format kFormats[] = {{"v5", MAT_FT_MAT5, MAT_COMPRESSION_NONE},
                           {"v7 (v5, compressed)", MAT_FT_MAT5, MAT_COMPRESSION_ZLIB},
                           {"v7.3 (HDF5)", MAT_FT_MAT73, MAT_COMPRESSION_NONE}};

class TempDir {
 public:
  TempDir() : dir_(fs::temp_directory_path() / ("deb_mat_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~TempDir() { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  void WriteText(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }

 private:
  fs::path dir_;
};

// Writes one .mat file with matio; every call's result is checked.
class MatWriter {
 public:
  MatWriter(const std::string& path, const Format& format)
      : mat_(Mat_CreateVer(path.c_str(), nullptr, format.version)), compression_(format.compression),
        v73_(format.version == MAT_FT_MAT73) {
    REQUIRE(mat_ != nullptr);
  }
  ~MatWriter() { Close(); }
  void Close() {
    if (mat_) CHECK(Mat_Close(mat_) == 0);
    mat_ = nullptr;
  }

  void Matrix(const char* name, const Eigen::MatrixXd& m) {
    size_t dims[2] = {static_cast<size_t>(m.rows()), static_cast<size_t>(m.cols())};
    Write(Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, const_cast<double*>(m.data()), 0));
  }
  void Vector(const char* name, const std::vector<double>& v, bool column = false) {
    Eigen::MatrixXd m = Eigen::Map<const Eigen::MatrixXd>(v.data(), 1, static_cast<Eigen::Index>(v.size()));
    Matrix(name, column ? Eigen::MatrixXd(m.transpose()) : m);
  }
  // Any class: `data` as matio takes it for `rank` dimensions.
  void Array(const char* name, matio_classes c, matio_types t, std::vector<size_t> dims, void* data, int opt = 0) {
    Write(Mat_VarCreate(name, c, t, static_cast<int>(dims.size()), dims.data(), data, opt));
  }
  // A char row vector as MATLAB writes it (16-bit characters in v7.3).
  matvar_t* Char(const char* name, const std::string& s) {
    size_t dims[2] = {1, s.size()};
    if (v73_) {
      std::vector<std::uint16_t> u(s.begin(), s.end());
      return Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT16, 2, dims, u.data(), 0);
    }
    return Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UTF8, 2, dims, const_cast<char*>(s.data()), 0);
  }
  void Cell(const char* name, const std::vector<std::string>& names) {
    size_t dims[2] = {1, names.size()};
    matvar_t* cell = Mat_VarCreate(name, MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0);
    REQUIRE(cell != nullptr);
    for (std::size_t i = 0; i < names.size(); ++i) {
      matvar_t* e = Char(nullptr, names[i]);
      REQUIRE(e != nullptr);
      Mat_VarSetCell(cell, static_cast<int>(i), e);
    }
    Write(cell);
  }
  // A char matrix, one name per row, padded with blanks as char('F', 'Gy') does.
  void CharMatrix(const char* name, const std::vector<std::string>& rows) {
    std::size_t cols = 0;
    for (const auto& r : rows) cols = std::max(cols, r.size());
    std::vector<std::uint16_t> data(rows.size() * cols, ' ');
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (std::size_t c = 0; c < rows[r].size(); ++c) data[r + c * rows.size()] = static_cast<unsigned char>(rows[r][c]);
    std::vector<char> bytes(data.begin(), data.end());
    size_t dims[2] = {rows.size(), cols};
    Write(v73_ ? Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT16, 2, dims, data.data(), 0)
               : Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UTF8, 2, dims, bytes.data(), 0));
  }
  void Write(matvar_t* v) {
    REQUIRE(v != nullptr);
    CHECK(Mat_VarWrite(mat_, v, compression_) == 0);
    Mat_VarFree(v);
  }

 private:
  mat_t* mat_;
  matio_compression compression_;
  bool v73_;
};

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

using test::Contains;

#define CHECK_ERROR(expr, ...)                                        \
  do {                                                                \
    const std::string message_ = ErrorOf([&] { (void)(expr); });      \
    CAPTURE(message_);                                                \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__}) CHECK(Contains(message_, part_)); \
  } while (0)

TEST_CASE("round trip: matrices, vectors and names in v5, compressed v5 and v7.3") {
  const TempDir dir;
  Eigen::MatrixXd a(3, 2);
  a << 1.5, -2.25, 1e-300, 3.0, 7.0, -0.1;
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    const std::string path = dir.Path("t.mat");
    {
      MatWriter w(path, format);
      w.Matrix("A", a);
      w.Vector("row", {1, 2, 3, 4});
      w.Vector("col", {5, 6, 7}, true);
      w.Vector("one", {0.25});
      float s[4] = {1.5f, 2.0f, -3.0f, 0.125f};
      w.Array("S", MAT_C_SINGLE, MAT_T_SINGLE, {2, 2}, s);
      std::int32_t i32[3] = {-7, 0, 2147483647};
      w.Array("I", MAT_C_INT32, MAT_T_INT32, {3, 1}, i32);
      std::uint8_t l[2] = {1, 0};
      w.Array("L", MAT_C_UINT8, MAT_T_UINT8, {1, 2}, l, MAT_F_LOGICAL);
      w.Cell("cell_names", {"Fx", "Fyy", "tip z"});
      w.CharMatrix("char_names", {"F", "Gy", "tip"});
    }
    const MatFile f(path);
    CHECK(f.Has("A"));
    CHECK_FALSE(f.Has("a"));
    CHECK(f.variables().size() == 9);
    CHECK(f.Matrix("A") == a);  // exact
    CHECK(f.Matrix("row").rows() == 1);
    CHECK(f.Vector("row") == std::vector<double>{1, 2, 3, 4});
    CHECK(f.Vector("col") == std::vector<double>{5, 6, 7});
    CHECK(f.Vector("one") == std::vector<double>{0.25});
    Eigen::MatrixXd s(2, 2);
    s << 1.5, -3.0, 2.0, 0.125;
    CHECK(f.Matrix("S") == s);
    CHECK(f.Vector("I") == std::vector<double>{-7, 0, 2147483647});
    CHECK(f.Vector("L") == std::vector<double>{1, 0});
    CHECK(f.Names("cell_names") == std::vector<std::string>{"Fx", "Fyy", "tip z"});
    CHECK(f.Names("char_names") == std::vector<std::string>{"F", "Gy", "tip"});
  }
}

TEST_CASE("bad variables: the message names the file, the variable, its class and its size") {
  const TempDir dir;
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    const std::string path = dir.Path("bad.mat");
    {
      MatWriter w(path, format);
      double re[4] = {1, 2, 3, 4}, im[4] = {0, 1, 0, 1};
      mat_complex_split_t z{re, im};
      w.Array("Z", MAT_C_DOUBLE, MAT_T_DOUBLE, {2, 2}, &z, MAT_F_COMPLEX);
      std::vector<double> cube(18, 1.0);
      w.Array("T", MAT_C_DOUBLE, MAT_T_DOUBLE, {3, 3, 2}, cube.data());
      w.Write(w.Char("txt", "hello"));
      w.Cell("names", {"a", "b"});
      const char* fields[] = {"k", nullptr};
      size_t one[2] = {1, 1};
      w.Write(Mat_VarCreateStruct2("St", 2, one, fields));
      Eigen::MatrixXd nan = Eigen::MatrixXd::Ones(2, 3);
      nan(1, 2) = std::nan("");
      w.Matrix("N", nan);
      w.Matrix("M", Eigen::MatrixXd::Ones(3, 4));
      w.Matrix("E", Eigen::MatrixXd(0, 0));
      double ir_data[2] = {1, 2};
      mat_uint32_t ir[2] = {0, 1}, jc[3] = {0, 1, 2};
      mat_sparse_t sp{2, ir, 2, jc, 3, 2, ir_data};
      w.Array("Sp", MAT_C_SPARSE, MAT_T_DOUBLE, {2, 2}, &sp);
      size_t dims[2] = {1, 2};
      matvar_t* mixed = Mat_VarCreate("mixed", MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0);
      Mat_VarSetCell(mixed, 0, w.Char(nullptr, "ok"));
      double x = 3;
      size_t d11[2] = {1, 1};
      Mat_VarSetCell(mixed, 1, Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, d11, &x, 0));
      w.Write(mixed);
      w.CharMatrix("blank_row", {"F", " "});
    }
    const MatFile f(path);
    CHECK_ERROR(f.Matrix("Z"), path + ": variable 'Z' is a 2x2 complex double array; expected a real 2-D matrix");
    CHECK_ERROR(f.Matrix("T"), path + ": variable 'T' is 3x3x2 (a 3-D array); expected a real 2-D matrix");
    CHECK_ERROR(f.Matrix("txt"), path + ": variable 'txt' is a 1x5 char array; expected a real 2-D matrix");
    CHECK_ERROR(f.Matrix("names"), path + ": variable 'names' is a 1x2 cell array");
    CHECK_ERROR(f.Matrix("St"), path + ": variable 'St' is a 1x1 struct array");
    CHECK_ERROR(f.Matrix("Sp"), path + ": variable 'Sp' is a 2x2 sparse matrix");
    CHECK_ERROR(f.Matrix("N"), path + ": N(2,3) = nan in the 2x3 double array; expected finite numbers");
    CHECK_ERROR(f.Matrix("nope"), path + ": no variable 'nope' in the MAT-file (it holds ", "Z, ", "txt");
    CHECK_ERROR(f.Vector("M"), path + ": variable 'M' is 3x4; expected a vector");
    CHECK_ERROR(f.Vector("E"), path + ": variable 'E' is empty (0x0)");
    CHECK_ERROR(f.Names("M"), path + ": variable 'M' is a 3x4 double array; expected names");
    CHECK_ERROR(f.Names("mixed"), path + ": mixed{2} is a 1x1 double array; expected one name");
    CHECK_ERROR(f.Names("blank_row"), path + ": variable 'blank_row' is a 2x1 char array whose row 2 is blank");
  }
}

// A version 5 file by hand: the 128-byte header, then one variable `name` of
// class double with the given dimensions whose data element claims
// `data_bytes` bytes and holds `held` of them.
std::string HandMadeV5(const std::vector<std::uint32_t>& dims, std::uint32_t data_bytes, std::uint32_t held) {
  std::string header = "MATLAB 5.0 MAT-file, written by hand";
  header.resize(116, ' ');
  header += std::string(8, '\0');
  header += std::string("\x00\x01", 2) + "IM";
  auto u32 = [](std::uint32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[i] = static_cast<char>((v >> (8 * i)) & 0xFF);
    return s;
  };
  std::string body = u32(6) + u32(8) + u32(6) + u32(0);  // array flags: class double
  std::string d;
  for (std::uint32_t n : dims) d += u32(n);
  while (d.size() % 8) d += '\0';
  body += u32(5) + u32(static_cast<std::uint32_t>(4 * dims.size())) + d;
  body += u32(1) + u32(1) + std::string("A") + std::string(7, '\0');  // name 'A'
  body += u32(9) + u32(data_bytes) + std::string(held, '\0');
  return header + u32(14) + u32(static_cast<std::uint32_t>(body.size() - held + data_bytes)) + body;
}

TEST_CASE("hostile files: a clear error naming the file, no crash") {
  const TempDir dir;
  dir.WriteText("text.mat", "A = [1 2; 3 4];\n");
  CHECK_ERROR(MatFile(dir.Path("text.mat")), dir.Path("text.mat") + ": the file holds 16 bytes, too few for a MAT-file");
  dir.WriteText("long_text.mat", std::string(300, 'x'));
  CHECK_ERROR(MatFile(dir.Path("long_text.mat")), dir.Path("long_text.mat") + ": not a MAT-file of version 5, 7 or 7.3");
  dir.WriteText("empty.mat", "");
  CHECK_ERROR(MatFile(dir.Path("empty.mat")), dir.Path("empty.mat") + ": the file holds 0 bytes");
  CHECK_ERROR(MatFile(dir.Path("")), "is a directory; deb reads regular files only");
  CHECK_ERROR(MatFile(dir.Path("missing.mat")), dir.Path("missing.mat") + ": cannot open MAT-file");

  // Truncated copies of a valid file, in every format.
  Eigen::MatrixXd big(100, 100);
  for (Eigen::Index k = 0; k < big.size(); ++k) big.data()[k] = 0.37 * static_cast<double>(k) + 1;
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    const std::string path = dir.Path("full.mat");
    {
      MatWriter w(path, format);
      w.Matrix("A", big);
      w.Matrix("B", Eigen::MatrixXd::Ones(100, 1));
    }
    REQUIRE(MatFile(path).Matrix("A") == big);
    const std::string bytes = test::ReadAll(path);
    for (const double fraction : {0.3, 0.6, 0.99}) {
      CAPTURE(fraction);
      dir.WriteText("cut.mat", bytes.substr(0, static_cast<std::size_t>(fraction * static_cast<double>(bytes.size()))));
      const std::string cut = dir.Path("cut.mat");
      const std::string message = ErrorOf([&] {
        const MatFile f(cut);
        (void)f.Matrix("A");
        (void)f.Matrix("B");
      });
      CAPTURE(message);
      CHECK(message.rfind(cut + ": ", 0) == 0);
      if (format.version == MAT_FT_MAT5) CHECK(Contains(message, "the file is truncated or damaged"));
    }
  }

  // A header asking for 10^10 values is refused before any is read.
  dir.WriteText("huge.mat", HandMadeV5({100000, 100000}, 0, 0));
  CHECK_ERROR(MatFile(dir.Path("huge.mat")).Matrix("A"),
              dir.Path("huge.mat") + ": variable 'A' is a 100000x100000 double array: more than the " +
                  std::to_string(limits::kMaxMatElements) + " values deb reads");
  dir.WriteText("overflow.mat", HandMadeV5({4000000000u, 4000000000u, 4000000000u}, 0, 0));
  CHECK_ERROR(MatFile(dir.Path("overflow.mat")).Matrix("A"), "4000000000x4000000000x4000000000 (a 3-D array)");
  // A data element shorter than the dimensions ask for.
  dir.WriteText("short.mat", HandMadeV5({3, 3}, 16, 16));
  CHECK_ERROR(MatFile(dir.Path("short.mat")), dir.Path("short.mat") +
                                                  ": the file is damaged: its variable 1 (at byte 128): its dimensions "
                                                  "ask for 9 values, its data holds 2");
  // The hand-made layout itself is read: 2x1 with both values.
  dir.WriteText("ok.mat", HandMadeV5({2, 1}, 16, 16));
  CHECK(MatFile(dir.Path("ok.mat")).Vector("A") == std::vector<double>{0, 0});
}

// A hand-made file (HandMadeV5) with its variable compressed (miCOMPRESSED,
// as save -v7 writes it); `tag_bytes` replaces the size in the inflated
// matrix's tag where given.
std::string Compressed(const std::string& plain, std::optional<std::uint32_t> tag_bytes = std::nullopt) {
  std::string element = plain.substr(128);
  if (tag_bytes)
    for (int i = 0; i < 4; ++i) element[4 + i] = static_cast<char>((*tag_bytes >> (8 * i)) & 0xFF);
  uLongf n = compressBound(static_cast<uLong>(element.size()));
  std::string z(n, '\0');
  REQUIRE(compress(reinterpret_cast<Bytef*>(z.data()), &n, reinterpret_cast<const Bytef*>(element.data()),
                   static_cast<uLong>(element.size())) == Z_OK);
  z.resize(n);
  std::string tag(8, '\0');
  tag[0] = 15;  // miCOMPRESSED
  for (int i = 0; i < 4; ++i) tag[4 + i] = static_cast<char>((n >> (8 * i)) & 0xFF);
  return plain.substr(0, 128) + tag + z;
}

TEST_CASE("compressed variables are checked as plain ones before matio reads them") {
  // A fuzzed 17 KB file whose compressed variable was damaged made matio
  // allocate 10 GB; each claim inside the inflated matrix is now checked.
  const TempDir dir;
  dir.WriteText("ok.mat", Compressed(HandMadeV5({2, 1}, 16, 16)));
  CHECK(MatFile(dir.Path("ok.mat")).Vector("A") == std::vector<double>{0, 0});
  dir.WriteText("short.mat", Compressed(HandMadeV5({3, 3}, 16, 16)));
  CHECK_ERROR(MatFile(dir.Path("short.mat")), dir.Path("short.mat") +
                                                  ": the file is damaged: its variable 1 (at byte 128): its dimensions "
                                                  "ask for 9 values, its data holds 2");
  // The real part claims 10^9 bytes of the 80 the matrix holds.
  dir.WriteText("part.mat", Compressed(HandMadeV5({2, 1}, 1000000000u, 16), 80));
  CHECK_ERROR(MatFile(dir.Path("part.mat")), "claims 1000000000 bytes, more than the variable holds");
  // The matrix claims 4 GB from a few dozen bytes of zlib data.
  dir.WriteText("ratio.mat", Compressed(HandMadeV5({2, 1}, 16, 16), 4000000000u));
  CHECK_ERROR(MatFile(dir.Path("ratio.mat")), "more than zlib data of that size can inflate to");
  // Bytes that are not zlib data.
  std::string garbage = Compressed(HandMadeV5({2, 1}, 16, 16));
  for (std::size_t k = 136; k < garbage.size(); ++k) garbage[k] = static_cast<char>(0xA5);
  dir.WriteText("garbage.mat", garbage);
  CHECK_ERROR(MatFile(dir.Path("garbage.mat")), "its compressed data cannot be inflated");
}

TEST_CASE("the files the fuzzer found: refused before matio or libhdf5 allocates 4, 10 and 15 GB or reads 33 million values") {
  const std::string corpus = std::string(DEB_SOURCE_DIR) + "/tests/fuzz/corpus/mat_file/";
  // A byte changed in a compressed variable's zlib stream (17 KB; matio asked for 10 GB).
  CHECK_ERROR(MatFile(corpus + "damaged_compressed.mat"),
              "its variable 6 (at byte 1886): its compressed data is damaged (it inflates to 30733 of the 30752 bytes");
  // Version 7.3: a dataset's HDF5 datatype of 4294966792 bytes (matio asked for 4 GB).
  CHECK_ERROR(MatFile(corpus + "huge_value_v73.mat"),
              "object 'C' stores values of 4294966792 bytes each; the values of a MAT-file are 1 to 16 bytes");
  // Version 7.3: an object header continued at 1 MB for 4 GB, in a 7.6 KB file (libhdf5 asked
  // for 4.3 GB before it read a byte of it).
  CHECK_ERROR(MatFile(corpus + "header_continuation_v73.mat"),
              "object 'output_names[1]' has a header continuation of 4295491589 bytes at address 1048576, "
              "which the file (7760 bytes) does not hold");
  // Version 7.3: the root group's local heap keeps a free list that leads back into itself
  // (13 KB; libhdf5 followed it until the process held 24 GB).
  CHECK_ERROR(MatFile(corpus + "heap_free_list_v73.mat"),
              "object '/' has a damaged group index: a local heap whose free list is not a list inside it at "
              "address 680");
  // Version 7.3: an attribute whose name has no terminating zero inside its message (8.6 KB;
  // libhdf5 copied the name past the end of the header, a heap read out of bounds).
  CHECK_ERROR(MatFile(corpus + "attribute_name_v73.mat"),
              "object 'output_Mames[1]' has a damaged attribute (its name does not end inside it)");
  // Version 7.3: an attribute's dataspace of 2048 bytes in a 48-byte message (libhdf5 copied
  // past the end of a buffer).
  CHECK_ERROR(MatFile(corpus + "attribute_parts_v73.mat"),
              "object 'C' has a damaged attribute (its parts do not fit in it)");
  // A real version 7.3 file whose root group's B-tree (one leaf node at byte 648, address 136)
  // is changed to name its symbol table node twice, or to claim a level above its leaves.
  {
    const std::string whole = test::ReadAll(corpus + "ss_v73.mat");
    REQUIRE(whole.substr(648, 8) == std::string("TREE\x00\x00\x01\x00", 8));
    const TempDir dir;
    std::string twice = whole;
    twice[654] = 2;                            // two entries used
    twice.replace(648 + 48, 8, whole.substr(648 + 32, 8));  // child 1 = child 0
    twice.replace(648 + 56, 8, whole.substr(648 + 40, 8));  // and a last key
    dir.WriteText("twice.mat", twice);
    CHECK_ERROR(MatFile(dir.Path("twice.mat")),
                "object '/' has a damaged group index: a node reached twice at address 1072");
    std::string level = whole;
    level[653] = 1;
    dir.WriteText("level.mat", level);
    CHECK_ERROR(MatFile(dir.Path("level.mat")),
                "object '/' has a damaged group index: no group B-tree node at address 1072");
  }
  // The same file with that object's first header chunk claiming 2 GB.
  {
    std::string bytes = test::ReadAll(corpus + "header_continuation_v73.mat");
    const std::size_t size_at = 512 + 6240 + 8;  // the user block, the header's address, its size field
    REQUIRE(bytes.substr(size_at - 8, 8) == std::string("\x01\x00\x07\x00\x01\x00\x00\x00", 8));
    bytes.replace(size_at, 4, "\xff\xff\xff\x7f", 4);
    const TempDir dir;
    dir.WriteText("header.mat", bytes);
    CHECK_ERROR(MatFile(dir.Path("header.mat")),
                "has a header of 2147483647 bytes at address 6240, which the file (7760 bytes) does not hold");
  }
  // Dimensions stored as data type 1280 instead of int32 (840 bytes; matio asked for 4.3 GB).
  CHECK_ERROR(MatFile(corpus + "dims_type.mat"),
              "its variable 2 (at byte 200): its dimensions are stored as data type 1280 of 8 bytes, not as MAT-files "
              "store them");
  // A numeric variable's values stored as data type 0, for 2 x 16449538 values (840 bytes).
  CHECK_ERROR(MatFile(corpus + "unknown_type.mat"),
              "its variable 3 (at byte 264): its values are stored as data type 0, which is no numeric type");
  // The name of a 360-byte file's first variable missing, the next one's array flags tagged as
  // type 251 (matio read 4.2 GB: 15 s and 4.1 GB of memory).
  CHECK_ERROR(MatFile(corpus + "matrix_header.mat"), "its variable 1 (at byte 128): its name is missing");
  // A cell array's dimensions changed to 2 x 973078529 (840 bytes; matio asked for 15.5 GB). The
  // same file stores variable 3's values as type 0 too, which is refused first; with that part's
  // type set back to miDOUBLE (9) the cell array is what is refused.
  CHECK_ERROR(MatFile(corpus + "huge_cell.mat"), "its variable 3 (at byte 264): its values are stored as data type 0");
  std::string bytes = test::ReadAll(corpus + "huge_cell.mat");
  REQUIRE(bytes.size() == 840);
  bytes[320] = 9;
  // ... and a cell of variable 5 has its (empty) name tagged as type 0x1001: set back to miINT8.
  REQUIRE(bytes[561] == 0x10);
  bytes[561] = 0;
  const TempDir dir;
  dir.WriteText("cell.mat", bytes);
  CHECK_ERROR(MatFile(dir.Path("cell.mat")),
              "its variable 6 (at byte 648): its dimensions ask for more cells than its 184 bytes can hold (at most 23)");
}

// ---------------------------------------------------------------------------
// Budgets.

using test::Replace;

// A budget of one path (a flow mapping) with two force inputs and the output `signal`.
std::string OnePathBudget(const std::string& path, const std::string& signal) {
  return "name: one\ngrid: {type: log, min_hz: 1, max_hz: 100, points: 10}\nsources:\n"
         "  - {name: force, unit: N, channels: 2, spectrum: {type: flat, level: 1}}\npaths:\n  - " +
         path + "\ncontributors:\n  - {name: c, source: force, path: p}\noutputs:\n  - {name: o, signal: " + signal +
         ", unit: um}\n";
}

using test::CheckLocated;
using test::ErrorOfBudget;
using test::MatrixYaml;
using test::ContributorOf;

// Two resonances (12 Hz, 70 Hz), two force inputs, one displacement output.
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
};

const char* kStateSpaceBudget = R"(name: ss
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
  - name: mat
    type: state_space
    file: plant.mat
    input_unit: N
    output_unit: m
contributors:
  - {name: inline, source: force, path: inline, exact: required}
  - {name: mat, source: force, path: mat, exact: required}
outputs:
  - {name: z, signal: z, unit: um}
)";

std::string StateSpaceBudget(const Plant& p) {
  std::string text = Replace(kStateSpaceBudget, "AAA", MatrixYaml(p.a));
  text = Replace(text, "BBB", MatrixYaml(p.b));
  text = Replace(text, "CCC", MatrixYaml(p.c));
  return Replace(text, "DDD", MatrixYaml(p.d));
}

void WritePlant(const std::string& path, const Format& format, const Plant& p, bool with_names = true) {
  MatWriter w(path, format);
  w.Matrix("A", p.a);
  w.Matrix("B", p.b);
  w.Matrix("C", p.c);
  w.Matrix("D", p.d);
  if (with_names) {
    w.Cell("input_names", {"F1", "F2"});
    w.CharMatrix("output_names", {"z"});
  }
}

TEST_CASE("state_space from a .mat: the RMS of the same matrices inline, names from the file") {
  const TempDir dir;
  const Plant plant;
  dir.WriteText("b.yaml", StateSpaceBudget(plant));
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    WritePlant(dir.Path("plant.mat"), format, plant);
    const Budget b = LoadBudgetFile(dir.Path("b.yaml"));
    const Path& mat = b.FindPath("mat");
    CHECK(mat.input_names == std::vector<std::string>{"F1", "F2"});
    CHECK(mat.output_names == std::vector<std::string>{"z"});
    CHECK(mat.system.A() == plant.a);
    const BudgetResult r = Evaluate(b);
    const ContributorResult& inline_c = ContributorOf(r.outputs[0], "inline");
    const ContributorResult& mat_c = ContributorOf(r.outputs[0], "mat");
    REQUIRE(inline_c.variance > 0);
    CHECK(std::abs(mat_c.variance - inline_c.variance) <= 1e-12 * inline_c.variance);
    REQUIRE(mat_c.exact_variance.has_value());
    CHECK(std::abs(*mat_c.exact_variance - *inline_c.exact_variance) <= 1e-12 * *inline_c.exact_variance);
  }
  SUBCASE("D optional (zeros); default names u1, u2, y; inputs/outputs in the YAML win over the file's") {
    Plant no_d = plant;
    no_d.d.setZero();
    {
      MatWriter w(dir.Path("plant.mat"), kFormats[0]);
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b);
      w.Matrix("C", plant.c);
    }
    const std::string path = "{name: p, type: state_space, file: plant.mat, input_unit: N, output_unit: m";
    const Budget b = LoadBudgetText(OnePathBudget(path + "}", "y"), "b.yaml", dir.Path(""));
    CHECK(b.FindPath("p").system.D() == Eigen::MatrixXd::Zero(1, 2));
    CHECK(b.FindPath("p").input_names == std::vector<std::string>{"u1", "u2"});
    CHECK(b.FindPath("p").output_names == std::vector<std::string>{"y"});
    WritePlant(dir.Path("plant.mat"), kFormats[0], plant);
    const Budget named = LoadBudgetText(OnePathBudget(path + ", outputs: [q]}", "q"), "b.yaml", dir.Path(""));
    CHECK(named.FindPath("p").output_names == std::vector<std::string>{"q"});
    CHECK(named.FindPath("p").input_names == std::vector<std::string>{"F1", "F2"});
  }
}

TEST_CASE("state_space from a .mat with 'matrices': deb's A, B, C (and D) by the file's variable names") {
  const TempDir dir;
  const Plant plant;
  {
    MatWriter w(dir.Path("plant.mat"), kFormats[1]);
    w.Matrix("Ahat", plant.a);
    w.Matrix("Bhat", plant.b);
    w.Matrix("Chat", plant.c);
    w.Matrix("D", Eigen::MatrixXd::Ones(1, 2));  // not mapped: not read
  }
  const std::string path = "{name: p, type: state_space, file: plant.mat, matrices: {A: Ahat, B: Bhat, C: Chat}, "
                           "input_unit: N, output_unit: m}";
  const Budget b = LoadBudgetText(OnePathBudget(path, "y"), "b.yaml", dir.Path(""));
  CHECK(b.FindPath("p").system.A() == plant.a);
  CHECK(b.FindPath("p").system.B() == plant.b);
  CHECK(b.FindPath("p").system.C() == plant.c);
  CHECK(b.FindPath("p").system.D() == Eigen::MatrixXd::Zero(1, 2));
  CHECK(Contains(test::InputErrorOf([&] {
                   LoadBudgetText(OnePathBudget(Replace(path, "B: Bhat", "B: B"), "y"), "b.yaml", dir.Path(""));
                 }),
                 "paths[0].matrices.B: " + dir.Path("plant.mat") + ": no variable 'B' in the MAT-file (it holds Ahat, "
                 "Bhat, Chat, D)"));
}

TEST_CASE("state_space .mat errors are located at file: and name the variable and its size") {
  const TempDir dir;
  const Plant plant;
  const std::string budget = dir.Path("b.yaml");
  dir.WriteText("b.yaml", StateSpaceBudget(plant));
  const std::string mat = dir.Path("plant.mat");
  auto write = [&](const std::function<void(MatWriter&)>& fill) {
    MatWriter w(mat, kFormats[1]);
    fill(w);
  };
  const std::string key = "paths[1].file";
  SUBCASE("missing B") {
    write([&](MatWriter& w) {
      w.Matrix("A", plant.a);
      w.Matrix("C", plant.c);
    });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": no variable 'B' in the MAT-file (it holds A, C)");
  }
  SUBCASE("B with too few rows") {
    write([&](MatWriter& w) {
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b.topRows(3));
      w.Matrix("C", plant.c);
    });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": B is 3x2 but A is 4x4: B needs 4 rows");
  }
  SUBCASE("C with too many columns, D of the wrong size, A not square") {
    write([&](MatWriter& w) {
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b);
      w.Matrix("C", Eigen::MatrixXd::Ones(1, 5));
    });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": C is 1x5 but A is 4x4: C needs 4 columns");
    write([&](MatWriter& w) {
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b);
      w.Matrix("C", plant.c);
      w.Matrix("D", Eigen::MatrixXd::Ones(2, 2));
    });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": D is 2x2 but B is 4x2 and C is 1x4: D needs to be 1x2");
    write([&](MatWriter& w) { w.Matrix("A", Eigen::MatrixXd::Ones(4, 3)); });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": A is 4x3; the state matrix A must be square");
  }
  SUBCASE("complex A, 3-D A, char A") {
    double re[4] = {-1, 0, 0, -2}, im[4] = {0, 1, 0, 0};
    mat_complex_split_t z{re, im};
    write([&](MatWriter& w) { w.Array("A", MAT_C_DOUBLE, MAT_T_DOUBLE, {2, 2}, &z, MAT_F_COMPLEX); });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": variable 'A' is a 2x2 complex double array");
    std::vector<double> cube(32, 0.0);
    write([&](MatWriter& w) { w.Array("A", MAT_C_DOUBLE, MAT_T_DOUBLE, {4, 4, 2}, cube.data()); });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": variable 'A' is 4x4x2 (a 3-D array); expected a real 2-D matrix");
    write([&](MatWriter& w) { w.Write(w.Char("A", "plant")); });
    CheckLocated(ErrorOfBudget(budget), key, mat + ": variable 'A' is a 1x5 char array; expected a real 2-D matrix");
  }
  SUBCASE("names: wrong count, repeated, numbers") {
    {
      MatWriter w(mat, kFormats[0]);
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b);
      w.Matrix("C", plant.c);
      w.Cell("input_names", {"F1", "F2", "F3"});
    }
    CheckLocated(ErrorOfBudget(budget), key, mat + ": input_names holds 3 name(s) but B has 2 column(s) (inputs)");
    {
      MatWriter w(mat, kFormats[0]);
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b);
      w.Matrix("C", plant.c);
      w.Cell("input_names", {"F1", "F1"});
    }
    CheckLocated(ErrorOfBudget(budget), key, mat + ": input_names{2} 'F1' is given twice");
    {
      MatWriter w(mat, kFormats[0]);
      w.Matrix("A", plant.a);
      w.Matrix("B", plant.b);
      w.Matrix("C", plant.c);
      w.Vector("output_names", {1});
    }
    CheckLocated(ErrorOfBudget(budget), key, mat + ": variable 'output_names' is a 1x1 double array; expected names");
  }
  SUBCASE("not a .mat file, a directory, a missing file") {
    dir.WriteText("plant.mat", std::string(200, 'x'));
    CheckLocated(ErrorOfBudget(budget), key, mat + ": not a MAT-file of version 5, 7 or 7.3");
    fs::remove(mat);
    CheckLocated(ErrorOfBudget(budget), key, mat + ": cannot open MAT-file");
    fs::create_directory(mat);
    CheckLocated(ErrorOfBudget(budget), key, mat + ": MAT-file is a directory; deb reads regular files only");
    fs::remove(mat);
  }
  SUBCASE("file: together with A") {
    WritePlant(mat, kFormats[0], plant);
    dir.WriteText("b.yaml", Replace(StateSpaceBudget(plant), "file: plant.mat\n", "file: plant.mat\n    A: [[1]]\n"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].A", "give 'file' (a MAT-file or an OP4 file with A, B, C and D) or the matrices inline, not both");
  }
}

// The modal budget of tests/load/modal_path_test.cpp: two modes (42 Hz and
// 2000 Hz; max_frequency_hz: 500 keeps the first), inputs F and G, output z,
// from CSV tables and from a .mat.
const char* kModalBudget = R"(name: modal
grid: {type: auto, min_hz: 0.001, max_hz: 100000}
sources:
  - {name: force, unit: N, channels: [F, G], spectrum: {type: flat, level: 2.5}}
paths:
  - name: tables
    type: modal
    modes: modes.csv
    input_shapes: phi_in.csv
    output_shapes: phi_out.csv
    max_frequency_hz: 500
    input_unit: N
    output_unit: m
  - name: mat
    type: modal
    file: frame.mat
    max_frequency_hz: 500
    input_unit: N
    output_unit: m
contributors:
  - {name: tables, source: force, path: tables, exact: required}
  - {name: mat, source: force, path: mat, exact: required}
outputs:
  - {name: z, signal: z, unit: um}
)";

void WriteFrame(const std::string& path, const Format& format, const std::vector<double>& f_hz,
                const std::vector<double>& zeta, const Eigen::MatrixXd& phi_in, const Eigen::MatrixXd& phi_out,
                bool names = true) {
  MatWriter w(path, format);
  w.Vector("f_hz", f_hz, true);  // a column, as FE tools export it
  w.Vector("zeta", zeta);
  w.Matrix("phi_in", phi_in);
  w.Matrix("phi_out", phi_out);
  if (names) {
    w.CharMatrix("input_names", {"F", "G"});
    w.Cell("output_names", {"z"});
  }
}

struct Frame {
  std::vector<double> f_hz = {42, 2000}, zeta = {0.02, 0.01};
  Eigen::MatrixXd phi_in = (Eigen::MatrixXd(2, 2) << 0.31, 5.0, 1.0, 1.0).finished();
  Eigen::MatrixXd phi_out = (Eigen::MatrixXd(1, 2) << -0.7, 3.0).finished();
};

class ModalDir : public TempDir {
 public:
  ModalDir() {
    WriteText("modes.csv", "mode, f_hz, zeta\n1, 42, 0.02\n2, 2000, 0.01\n");
    WriteText("phi_in.csv", "dof, mode1, mode2\nF, 0.31, 5.0\nG, 1.0, 1.0\n");
    WriteText("phi_out.csv", "dof, mode1, mode2\nz, -0.7, 3.0\n");
    WriteText("b.yaml", kModalBudget);
  }
};

TEST_CASE("modal from a .mat: the modes of the CSV tables, the same RMS") {
  const ModalDir dir;
  const Frame fr;
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    WriteFrame(dir.Path("frame.mat"), format, fr.f_hz, fr.zeta, fr.phi_in, fr.phi_out);
    const Budget b = LoadBudgetFile(dir.Path("b.yaml"));
    const Path& mat = b.FindPath("mat");
    REQUIRE(mat.IsModal());
    CHECK(mat.modal->modes() == 1);  // the 2000 Hz mode is dropped
    CHECK(mat.input_names == std::vector<std::string>{"F", "G"});
    CHECK(mat.output_names == std::vector<std::string>{"z"});
    CHECK(mat.modal->f_hz == b.FindPath("tables").modal->f_hz);
    CHECK(mat.modal->zeta == b.FindPath("tables").modal->zeta);
    CHECK(mat.modal->phi_in == b.FindPath("tables").modal->phi_in);
    CHECK(mat.modal->phi_out == b.FindPath("tables").modal->phi_out);
    const BudgetResult r = Evaluate(b);
    const ContributorResult& t = ContributorOf(r.outputs[0], "tables");
    const ContributorResult& m = ContributorOf(r.outputs[0], "mat");
    CHECK(std::abs(m.variance - t.variance) <= 1e-12 * t.variance);
    REQUIRE(m.exact_variance.has_value());
    CHECK(std::abs(*m.exact_variance - *t.exact_variance) <= 1e-12 * *t.exact_variance);
  }
  SUBCASE("one zeta for all modes; default names u1, u2, y") {
    WriteFrame(dir.Path("frame.mat"), kFormats[0], fr.f_hz, {0.02}, fr.phi_in, fr.phi_out, false);
    const Budget b = LoadBudgetText(
        OnePathBudget("{name: p, type: modal, file: frame.mat, input_unit: N, output_unit: m}", "y"), "b.yaml",
        dir.Path(""));
    CHECK(b.FindPath("p").input_names == std::vector<std::string>{"u1", "u2"});
    CHECK(b.FindPath("p").output_names == std::vector<std::string>{"y"});
  }
}

TEST_CASE("modal .mat errors are located at file: and name the variable, its index and its size") {
  const ModalDir dir;
  const Frame fr;
  const std::string mat = dir.Path("frame.mat");
  const std::string budget = dir.Path("b.yaml");
  const std::string key = "paths[1].file";
  SUBCASE("zeta >= 1 at index k") {
    WriteFrame(mat, kFormats[2], fr.f_hz, {0.02, 1.2}, fr.phi_in, fr.phi_out);
    CheckLocated(ErrorOfBudget(budget), key, mat + ": zeta(2) = 1.2: damping ratio 1.2 is >= 1");
  }
  SUBCASE("negative f_hz") {
    WriteFrame(mat, kFormats[0], {42, -3}, fr.zeta, fr.phi_in, fr.phi_out);
    CheckLocated(ErrorOfBudget(budget), key, mat + ": f_hz(2) = -3: natural frequency -3 Hz is negative");
  }
  SUBCASE("one zeta of 0 for all modes") {
    WriteFrame(mat, kFormats[0], fr.f_hz, {0}, fr.phi_in, fr.phi_out);
    CheckLocated(ErrorOfBudget(budget), key, mat + ": zeta = 0 (for mode 1 at 42 Hz): damping ratio 0");
  }
  SUBCASE("zeta count, shape columns, names count") {
    WriteFrame(mat, kFormats[0], fr.f_hz, {0.1, 0.1, 0.1}, fr.phi_in, fr.phi_out);
    CheckLocated(ErrorOfBudget(budget), key, mat + ": zeta has 3 value(s) but f_hz has 2 mode(s)");
    WriteFrame(mat, kFormats[0], fr.f_hz, fr.zeta, Eigen::MatrixXd::Ones(2, 3), fr.phi_out);
    CheckLocated(ErrorOfBudget(budget), key,
                 mat + ": phi_in is 2x3 but f_hz has 2 mode(s): phi_in needs one column per mode (inputs x modes)");
    WriteFrame(mat, kFormats[0], fr.f_hz, fr.zeta, fr.phi_in, Eigen::MatrixXd::Ones(2, 2));
    CheckLocated(ErrorOfBudget(budget), key, mat + ": output_names holds 1 name(s) but phi_out has 2 row(s)");
  }
  SUBCASE("a missing variable, f_hz a matrix") {
    {
      MatWriter w(mat, kFormats[0]);
      w.Vector("f_hz", fr.f_hz);
      w.Vector("zeta", fr.zeta);
      w.Matrix("phi_in", fr.phi_in);
    }
    CheckLocated(ErrorOfBudget(budget), key, mat + ": no variable 'phi_out' in the MAT-file (it holds f_hz, zeta, phi_in)");
    {
      MatWriter w(mat, kFormats[0]);
      w.Matrix("f_hz", Eigen::MatrixXd::Ones(2, 2));
    }
    CheckLocated(ErrorOfBudget(budget), key, mat + ": variable 'f_hz' is 2x2; expected a vector");
  }
  SUBCASE("file: together with modes") {
    WriteFrame(mat, kFormats[0], fr.f_hz, fr.zeta, fr.phi_in, fr.phi_out);
    dir.WriteText("b.yaml", Replace(kModalBudget, "file: frame.mat\n", "file: frame.mat\n    modes: modes.csv\n"));
    CheckLocated(ErrorOfBudget(budget), "paths[1].modes",
                 "give 'file' (a MAT-file with f_hz, zeta, phi_in and phi_out) or 'modes', not both");
  }
}

}  // namespace
}  // namespace deb
