// deb/io/hdf5_file.h: every kind of dataset written and read back exactly
// (HDF5 stores the doubles and the UTF-8 text as given), the groups above a
// dataset created on the way, and a located InputError for what a reader
// must refuse: a missing object, another class or rank, a value that is not
// finite, a file that is not HDF5.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <iterator>
#include <thread>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

#include "deb/core/error.h"
#include "deb/io/hdf5_file.h"
#include <hdf5.h>
#include "tests/support/contains.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using test::Contains;

class TempDir {
 public:
  TempDir() : dir_(fs::temp_directory_path() / ("deb_hdf5_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~TempDir() { fs::remove_all(dir_); }
  std::string File(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST_CASE("an HDF5 file holds numbers, integers, text, vectors and matrices exactly") {
  const TempDir dir;
  const std::string file = dir.File("a.h5");
  const double tiny = 5.9e-300, third = 1.0 / 3.0;
  {
    io::Hdf5Writer w(file);
    w.Number("scalar", third);
    w.Number("absent", std::numeric_limits<double>::quiet_NaN());
    w.Integer("version", -42);
    w.Text("unit", "µm/s, '\"quoted\"'");
    w.Text("empty", "");
    w.Numbers("deep/group/f_hz", {0.1, tiny, 1e300});
    w.Numbers("deep/group/none", {});
    w.Texts("deep/names", {"x", "β", ""});
    w.Rows("deep/matrix", {{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}});
    w.Rows("deep/no_rows", {});
    CHECK_THROWS_AS(w.Number("scalar", 1.0), WriteError);  // exists already
    w.Close();
  }
  const io::Hdf5Reader r(file);
  CHECK(r.Has("deep/group"));
  CHECK(r.Has("deep/group/f_hz"));
  CHECK_FALSE(r.Has("deep/other"));
  CHECK_FALSE(r.Has("nothing/at/all"));
  CHECK(r.Number("scalar") == third);
  CHECK(std::isnan(r.Number("absent", true)));
  CHECK(r.Integer("version") == -42);
  CHECK(r.Text("unit") == "µm/s, '\"quoted\"'");
  CHECK(r.Text("empty").empty());
  CHECK(r.Numbers("deep/group/f_hz") == std::vector<double>{0.1, tiny, 1e300});
  CHECK(r.Numbers("deep/group/none").empty());
  CHECK(r.Texts("deep/names") == std::vector<std::string>{"x", "β", ""});
  CHECK(r.Rows("deep/matrix") == std::vector<std::vector<double>>{{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}});
  CHECK(r.Rows("deep/no_rows").empty());
  CHECK(r.Number("version") == -42.0);  // an integer reads as a number
}

TEST_CASE("an HDF5 reader refuses what it was not asked for, naming the file and the object") {
  const TempDir dir;
  const std::string file = dir.File("b.h5");
  {
    io::Hdf5Writer w(file);
    w.Numbers("v", {1.0, std::numeric_limits<double>::quiet_NaN()});
    w.Numbers("inf", {std::numeric_limits<double>::infinity()});
    w.Text("t", "text");
    w.Close();
  }
  const io::Hdf5Reader r(file);
  const std::string missing = ErrorOf([&] { r.Numbers("w"); });
  CHECK(Contains(missing, file));
  CHECK(Contains(missing, "object 'w' is missing"));
  CHECK(Contains(ErrorOf([&] { r.Text("v"); }), "object 'v' holds numbers, not text"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("t"); }), "object 't' holds text, not numbers"));
  CHECK(Contains(ErrorOf([&] { r.Number("v"); }), "object 'v' has 1 dimensions, not 0"));
  CHECK(Contains(ErrorOf([&] { r.Rows("v"); }), "has 1 dimensions, not 2"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("v"); }), "not finite at element 1"));
  CHECK(std::isnan(r.Numbers("v", true)[1]));
  CHECK(Contains(ErrorOf([&] { r.Numbers("inf", true); }), "not finite at element 0"));
  CHECK(Contains(ErrorOf([&] { r.Integer("v"); }), "not an integer"));

  const std::string text = dir.File("not.h5");
  std::ofstream(text) << "frequency_hz,psd\n1,2\n";
  CHECK(Contains(ErrorOf([&] { io::Hdf5Reader bad(text); }), "not an HDF5 file"));
  CHECK(Contains(ErrorOf([&] { io::Hdf5Reader none(dir.File("absent.h5")); }), "absent.h5"));
}

TEST_CASE("a compressed dataset is refused: a small file could expand beyond any bound") {
  const TempDir dir;
  const std::string file = dir.File("compressed.h5");
  {
    const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(f >= 0);
    const hsize_t n = 100000;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(create, 1, &n);
    H5Pset_deflate(create, 9);
    const hid_t set = H5Dcreate2(f, "zeros", H5T_IEEE_F64LE, space, H5P_DEFAULT, create, H5P_DEFAULT);
    REQUIRE(set >= 0);
    const std::vector<double> zeros(n, 0.0);
    REQUIRE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data()) >= 0);
    H5Dclose(set);
    H5Pclose(create);
    H5Sclose(space);
    H5Fclose(f);
  }
  CHECK(fs::file_size(file) < 100000);  // 800 kB of zeros in a few kB
  const std::string e = ErrorOf([&] { io::Hdf5Reader(file).Numbers("zeros"); });
  CHECK(Contains(e, "object 'zeros' is compressed or filtered"));
}

TEST_CASE("the same values written a second later give the same file (no times in the objects)") {
  const TempDir dir;
  const auto write = [&](const std::string& name) {
    io::Hdf5Writer w(dir.File(name));
    w.Text("schema", "x");
    w.Numbers("a/b/c", {1.0, 2.0});
    w.Rows("a/m", {{1.0, 2.0}, {3.0, 4.0}});
    w.Close();
    std::ifstream in(dir.File(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const std::string first = write("first.h5");
  // HDF5 stores times in whole seconds.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  const std::string second = write("second.h5");
  CHECK(first.size() > 100);
  const bool same = first == second;
  CHECK(same);
}

}  // namespace
}  // namespace deb
