// deb/formats/hdf5_file.h: every kind of dataset written and read back exactly
// (HDF5 stores the doubles and the UTF-8 text as given), the groups above a
// dataset created on the way, and a located InputError for what a reader
// must refuse: a missing object, another class or rank, a value that is not
// finite, a file that is not HDF5.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iterator>
#include <thread>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "deb/core/error.h"
#include "deb/formats/hdf5_file.h"
#include <hdf5.h>
#include <zlib.h>
#include "tests/support/contains.h"
#include "tests/support/file_bytes.h"

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
    formats::Hdf5Writer w(file);
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
  const formats::Hdf5Reader r(file);
  CHECK(r.Has("deep/group"));
  CHECK(r.Has("deep/group/f_hz"));
  CHECK_FALSE(r.Has("deep/other"));
  CHECK_FALSE(r.Has("nothing/at/all"));
  CHECK(r.Number("scalar") == third);
  CHECK(std::isnan(r.Number("absent", true)));
  CHECK(r.Integer("version") == -42);
  CHECK(r.Text("unit") == "µm/s, '\"quoted\"'");
  CHECK(r.Text("empty").empty());
  CHECK(r.Numbers("deep/group/f_hz", formats::AtMost(3)) == std::vector<double>{0.1, tiny, 1e300});
  CHECK(r.Numbers("deep/group/none", formats::AtMost(0)).empty());
  CHECK(r.Texts("deep/names", formats::AtMost(3)) == std::vector<std::string>{"x", "β", ""});
  CHECK(r.Rows("deep/matrix", formats::AtMost(2), 3) == std::vector<std::vector<double>>{{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}});
  CHECK(r.Rows("deep/no_rows", formats::AtMost(0), 5).empty());
  CHECK(r.Number("version") == -42.0);  // an integer reads as a number
}

TEST_CASE("an HDF5 reader refuses what it was not asked for, naming the file and the object") {
  const TempDir dir;
  const std::string file = dir.File("b.h5");
  {
    formats::Hdf5Writer w(file);
    w.Numbers("v", {1.0, std::numeric_limits<double>::quiet_NaN()});
    w.Numbers("inf", {std::numeric_limits<double>::infinity()});
    w.Text("t", "text");
    w.Close();
  }
  const formats::Hdf5Reader r(file);
  const std::string missing = ErrorOf([&] { r.Numbers("w", formats::AtMost(9)); });
  CHECK(Contains(missing, file));
  CHECK(Contains(missing, "object 'w' is missing"));
  CHECK(Contains(ErrorOf([&] { r.Text("v"); }), "object 'v' holds numbers, not text"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("t", formats::AtMost(9)); }), "object 't' holds text, not numbers"));
  CHECK(Contains(ErrorOf([&] { r.Number("v"); }), "object 'v' has 1 dimensions, not 0"));
  CHECK(Contains(ErrorOf([&] { r.Rows("v", formats::AtMost(9), 2); }), "has 1 dimensions, not 2"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("v", formats::AtMost(9)); }), "not finite at element 1"));
  CHECK(std::isnan(r.Numbers("v", formats::AtMost(2), true)[1]));
  CHECK(Contains(ErrorOf([&] { r.Numbers("inf", formats::AtMost(1), true); }), "not finite at element 0"));
  CHECK(Contains(ErrorOf([&] { r.Integer("v"); }), "not an integer"));

  const std::string text = dir.File("not.h5");
  std::ofstream(text) << "frequency_hz,psd\n1,2\n";
  CHECK(Contains(ErrorOf([&] { formats::Hdf5Reader bad(text); }), "not an HDF5 file"));
  CHECK(Contains(ErrorOf([&] { formats::Hdf5Reader none(dir.File("absent.h5")); }), "absent.h5"));
}

// Rows one after the other.
std::vector<double> Flat(const std::vector<std::vector<double>>& rows) {
  std::vector<double> flat;
  for (const std::vector<double>& r : rows) flat.insert(flat.end(), r.begin(), r.end());
  return flat;
}

TEST_CASE("numbers are written compressed in chunks and read back exactly, whatever the chunks' edges") {
  const TempDir dir;
  const std::string file = dir.File("compressed.h5");
  // A smooth spectrum (compresses), a vector not a multiple of the chunk,
  // rows split across chunks by columns and by rows, and a short vector
  // that stays contiguous.
  std::vector<double> spectrum(100003);
  for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] = 1e-18 / (1.0 + 1e-6 * double(i) * double(i));
  std::vector<std::vector<double>> wide(3, std::vector<double>(40000)), tall(5000, std::vector<double>(7));
  for (std::size_t r = 0; r < wide.size(); ++r)
    for (std::size_t c = 0; c < wide[r].size(); ++c) wide[r][c] = std::sin(0.001 * double(c)) + double(r);
  for (std::size_t r = 0; r < tall.size(); ++r)
    for (std::size_t c = 0; c < 7; ++c) tall[r][c] = std::exp(-1e-3 * double(r)) * double(c + 1);
  const std::vector<double> few = {1.0, 2.0, 3.0};
  // Packing::kRuns: values whose low bytes are noise (a response's gains:
  // random numbers over 12 decades), in a file of their own to measure it.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> decades(-12.0, 0.0);
  std::vector<std::vector<double>> noisy(4, std::vector<double>(30000));
  for (auto& row : noisy)
    for (double& v : row) v = std::pow(10.0, decades(rng));
  // And values whose byte planes alternate between noise and runs (bytes 1
  // and 3 zero, 7 constant, the rest random; in [1, 2)), and a row of
  // zeros: planes stored and planes run-length deflated within one chunk.
  std::uniform_int_distribution<std::uint64_t> bits;
  std::vector<std::vector<double>> mixed(3, std::vector<double>(20000, 0.0));
  for (std::size_t r = 0; r < 2; ++r)
    for (double& v : mixed[r]) {
      const std::uint64_t u = (bits(rng) & 0x000FFFFF00FF00FFull) | 0x3FF0000000000000ull;
      std::memcpy(&v, &u, sizeof v);
    }
  const std::string runs_file = dir.File("runs.h5"), mixed_file = dir.File("mixed.h5");
  {
    formats::Hdf5Writer w(file);
    w.Numbers("a/spectrum", spectrum);
    w.Rows("a/wide", wide);
    w.Rows("a/tall", tall);
    w.Numbers("a/few", few);
    w.Close();
    formats::Hdf5Writer runs(runs_file);
    runs.Rows("a/noisy", noisy, formats::Packing::kRuns);
    runs.Close();
    formats::Hdf5Writer planes(mixed_file);
    planes.Rows("a/mixed", mixed, formats::Packing::kRuns);
    planes.Close();
  }
  const std::uintmax_t raw = (spectrum.size() + 3 * 40000 + 5000 * 7) * sizeof(double);
  CHECK(fs::file_size(file) < raw * 7 / 10);  // deflate level 1: 0.67 of it
  MESSAGE("compressed " << raw << " bytes of doubles into a file of " << fs::file_size(file));
  // Only the exponent bytes compress: about 1 - 1/8 of the raw size is left
  // (observed 0.91, the file's own structure included).
  const std::uintmax_t noisy_raw = 4 * 30000 * sizeof(double);
  CHECK(fs::file_size(runs_file) < noisy_raw * 95 / 100);
  MESSAGE("kRuns: " << noisy_raw << " bytes of noisy doubles into a file of " << fs::file_size(runs_file));
  // Of the mixed values 5 planes in 8 are noise, stored as they are; the
  // others and the row of zeros deflate to almost nothing: about 0.42.
  const std::uintmax_t mixed_raw = 3 * 20000 * sizeof(double);
  CHECK(fs::file_size(mixed_file) < mixed_raw / 2);
  MESSAGE("kRuns, mixed planes: " << mixed_raw << " bytes into a file of " << fs::file_size(mixed_file));
  const formats::Hdf5Reader r(file);
  CHECK(r.Numbers("a/spectrum", formats::AtMost(200000)) == spectrum);
  CHECK(r.Rows("a/wide", formats::AtMost(3), 40000) == wide);
  CHECK(r.Rows("a/tall", formats::AtMost(5000), 7) == tall);
  CHECK(r.Numbers("a/few", formats::AtMost(3)) == few);
  CHECK(formats::Hdf5Reader(runs_file).Rows("a/noisy", formats::AtMost(4), 30000) == noisy);
  CHECK(formats::Hdf5Reader(mixed_file).Rows("a/mixed", formats::AtMost(3), 20000) == mixed);
  // Each compressed dataset is chunked, shuffled and deflated, as h5py sees
  // it, and HDF5's own filters give back every value (deb compresses the
  // chunks itself, edge chunks padded: hdf5_file.cpp).
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const std::vector<std::pair<const char*, std::vector<double>>> expected = {
      {"a/spectrum", spectrum}, {"a/wide", Flat(wide)}, {"a/tall", Flat(tall)}};
  for (const auto& [name, values] : expected) {
    const hid_t set = H5Dopen2(f, name, H5P_DEFAULT);
    const hid_t create = H5Dget_create_plist(set);
    CHECK(H5Pget_layout(create) == H5D_CHUNKED);
    CHECK(H5Pget_nfilters(create) == 2);
    std::vector<double> read(values.size());
    CHECK(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, read.data()) >= 0);
    CHECK(read == values);
    H5Pclose(create);
    H5Dclose(set);
  }
  H5Fclose(f);
  // The same for the run-length deflated dataset.
  const hid_t g = H5Fopen(runs_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(g >= 0);
  const hid_t set = H5Dopen2(g, "a/noisy", H5P_DEFAULT);
  const hid_t create = H5Dget_create_plist(set);
  CHECK(H5Pget_nfilters(create) == 2);
  std::vector<double> read(4 * 30000);
  CHECK(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, read.data()) >= 0);
  CHECK(read == Flat(noisy));
  H5Pclose(create);
  H5Dclose(set);
  H5Fclose(g);
  const hid_t h = H5Fopen(mixed_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(h >= 0);
  const hid_t mixed_set = H5Dopen2(h, "a/mixed", H5P_DEFAULT);
  std::vector<double> mixed_read(3 * 20000);
  CHECK(H5Dread(mixed_set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, mixed_read.data()) >= 0);
  CHECK(mixed_read == Flat(mixed));
  H5Dclose(mixed_set);
  H5Fclose(h);
}

// A dataset of `n` doubles in chunks of `chunk`, shuffled and deflated as deb
// writes them, whose chunks are written raw: (offset, filter mask, bytes).
struct RawChunk {
  hsize_t offset;
  std::uint32_t mask;
  std::vector<unsigned char> bytes;
};
void WriteRawChunks(const std::string& file, hsize_t n, hsize_t chunk, const std::vector<RawChunk>& chunks,
                    bool shuffle = true) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(create, 1, &chunk);
  if (shuffle) H5Pset_shuffle(create);
  H5Pset_deflate(create, 4);
  const hid_t set = H5Dcreate2(f, "x", H5T_IEEE_F64LE, space, H5P_DEFAULT, create, H5P_DEFAULT);
  REQUIRE(set >= 0);
  for (const RawChunk& c : chunks)
    REQUIRE(H5Dwrite_chunk(set, H5P_DEFAULT, c.mask, &c.offset, c.bytes.size(), c.bytes.data()) >= 0);
  H5Dclose(set);
  H5Pclose(create);
  H5Sclose(space);
  H5Fclose(f);
}

std::vector<unsigned char> Deflated(std::size_t zero_bytes) {
  const std::vector<unsigned char> zeros(zero_bytes, 0);
  uLongf size = compressBound(static_cast<uLong>(zero_bytes));
  std::vector<unsigned char> out(size);
  REQUIRE(compress2(out.data(), &size, zeros.data(), static_cast<uLong>(zero_bytes), 9) == Z_OK);
  out.resize(size);
  return out;
}

TEST_CASE("a compressed dataset is read only as deb writes it, and no chunk expands beyond its size") {
  const TempDir dir;
  const std::string file = dir.File("hostile.h5");
  const auto error = [&](hsize_t n) {
    return ErrorOf([&] { formats::Hdf5Reader(file).Numbers("x", formats::AtMost(n)); });
  };
  // The deb layout, written raw: read back (8000 zero bytes per chunk).
  WriteRawChunks(file, 2000, 1000, {{0, 0, Deflated(8000)}, {1000, 0, Deflated(8000)}});
  CHECK(formats::Hdf5Reader(file).Numbers("x", formats::AtMost(2000)) == std::vector<double>(2000, 0.0));
  // A bomb: 1 MB of zeros in a chunk of 1000 values (8000 bytes), 1 kB in
  // the file; HDF5's own deflate filter would grow its buffer to 1 MB.
  WriteRawChunks(file, 1000, 1000, {{0, 0, Deflated(1'000'000)}});
  CHECK(fs::file_size(file) < 10000);
  CHECK(Contains(error(1000), "object 'x' has a chunk that does not inflate to its 8000 bytes"));
  // A chunk the file never holds (HDF5 would fill it with zeros).
  WriteRawChunks(file, 2000, 1000, {{0, 0, Deflated(8000)}});
  CHECK(Contains(error(2000), "object 'x' holds 1 of its 2 chunks"));
  // A chunk stored with its deflation skipped.
  WriteRawChunks(file, 1000, 1000, {{0, 2, std::vector<unsigned char>(8000, 0)}});
  CHECK(Contains(error(1000), "object 'x' has a chunk stored without its filters"));
  // Deflate without the shuffle: another pipeline than deb writes.
  WriteRawChunks(file, 1000, 1000, {{0, 0, Deflated(8000)}}, false);
  CHECK(Contains(error(1000), "object 'x' is compressed or filtered in another way than deb writes"));
  // The declared size still bounds the read before anything is inflated.
  WriteRawChunks(file, 2000, 1000, {{0, 0, Deflated(8000)}, {1000, 0, Deflated(8000)}});
  CHECK(Contains(error(1999), "declares 2000 values, more than the 1999 it may hold"));
}

TEST_CASE("an object header claiming more than the file holds is refused before libhdf5 allocates it") {
  // Version-2 object headers (HDF5 1.8 and later with the latest format);
  // the version-1 headers of MAT-files have their test in mat_file_test.
  const TempDir dir;
  const std::string file = dir.File("v2.h5");
  {
    const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
    REQUIRE(H5Pset_libver_bounds(access, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST) >= 0);
    const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
    REQUIRE(f >= 0);
    const hsize_t n = 4;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t set = H5Dcreate2(f, "v", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const double values[4] = {1, 2, 3, 4};
    REQUIRE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) >= 0);
    H5Dclose(set);
    H5Sclose(space);
    H5Fclose(f);
    H5Pclose(access);
  }
  formats::RequireSelfContainedHdf5(file);  // whole, it passes
  std::string bytes = test::ReadAll(file);
  // The last "OHDR" is the dataset's (the root group's comes first). Its
  // flags byte gives the width of the first chunk's size and what precedes it.
  const std::size_t at = bytes.rfind("OHDR");
  REQUIRE(at != std::string::npos);
  REQUIRE(at > bytes.find("OHDR"));
  const unsigned flags = static_cast<unsigned char>(bytes[at + 5]);
  const std::size_t size_at = at + 6 + ((flags & 0x20) ? 16 : 0) + ((flags & 0x10) ? 4 : 0);
  const std::size_t width = std::size_t{1} << (flags & 0x03);
  for (std::size_t k = 0; k < width; ++k) bytes[size_at + k] = '\xff';
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  const std::string e = ErrorOf([&] { formats::RequireSelfContainedHdf5(file); });
  const std::string claimed = std::to_string((width == 8 ? 0 : (std::uint64_t{1} << (8 * width))) - 1);
  CHECK(Contains(e, "object 'v' has a header of " + claimed + " bytes at address " + std::to_string(at)));
  CHECK(Contains(e, "which the file (" + std::to_string(bytes.size()) + " bytes) does not hold"));
}

// A file written by HDF5 itself with what deb's writer never makes: values
// stored in other files (one holding known bytes, one a FIFO), links to
// another file and within the file, a virtual dataset, and datasets declared
// far larger than what they hold.
struct Hostile {
  std::string file, secret, fifo;
};

Hostile WriteHostile(const TempDir& dir) {
  Hostile h{dir.File("hostile.h5"), dir.File("secret.bin"), dir.File("fifo")};
  const double known[2] = {1234.5, 6789.25};
  std::ofstream(h.secret, std::ios::binary).write(reinterpret_cast<const char*>(known), sizeof known);
  REQUIRE(::mkfifo(h.fifo.c_str(), 0600) == 0);
  const std::string other = dir.File("other.h5");
  const hsize_t two = 2;
  {
    const hid_t f = H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t space = H5Screate_simple(1, &two, nullptr);
    const hid_t set = H5Dcreate2(f, "v", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, known) >= 0);
    H5Dclose(set);
    H5Sclose(space);
    H5Fclose(f);
  }
  const hid_t f = H5Fcreate(h.file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t space = H5Screate_simple(1, &two, nullptr);
  const auto dataset = [&](const char* name, hid_t create) {
    const hid_t set = H5Dcreate2(f, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, create, H5P_DEFAULT);
    REQUIRE(set >= 0);
    return set;
  };
  const hid_t plain = dataset("plain", H5P_DEFAULT);
  REQUIRE(H5Dwrite(plain, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, known) >= 0);
  H5Dclose(plain);
  for (const auto& [name, target] : {std::make_pair("external", h.secret), std::make_pair("fifo_data", h.fifo)}) {
    const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
    REQUIRE(H5Pset_external(create, target.c_str(), 0, sizeof known) >= 0);
    H5Dclose(dataset(name, create));  // created, never written: the target is not touched
    H5Pclose(create);
  }
  {
    const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
    REQUIRE(H5Pset_virtual(create, space, other.c_str(), "v", space) >= 0);
    H5Dclose(dataset("virtual", create));
    H5Pclose(create);
  }
  REQUIRE(H5Lcreate_external(other.c_str(), "v", f, "elink", H5P_DEFAULT, H5P_DEFAULT) >= 0);
  REQUIRE(H5Lcreate_external(other.c_str(), "/", f, "egroup", H5P_DEFAULT, H5P_DEFAULT) >= 0);
  REQUIRE(H5Lcreate_soft("/plain", f, "soft", H5P_DEFAULT, H5P_DEFAULT) >= 0);
  // Declared, never written: 250 M values, and 250 M rows of nothing.
  const hsize_t huge = 250'000'000, empty_rows[2] = {250'000'000, 0};
  const hid_t huge_space = H5Screate_simple(1, &huge, nullptr), rows_space = H5Screate_simple(2, empty_rows, nullptr);
  H5Dclose(H5Dcreate2(f, "declared", H5T_IEEE_F64LE, huge_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Dclose(H5Dcreate2(f, "no_columns", H5T_IEEE_F64LE, rows_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  const hsize_t hundred = 100;
  const hid_t hundred_space = H5Screate_simple(1, &hundred, nullptr);
  H5Dclose(H5Dcreate2(f, "unwritten", H5T_IEEE_F64LE, hundred_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Sclose(hundred_space);
  H5Sclose(huge_space);
  H5Sclose(rows_space);
  H5Sclose(space);
  H5Fclose(f);
  return h;
}

TEST_CASE("values in another file, links and virtual datasets are refused before anything is read from them") {
  const TempDir dir;
  const Hostile h = WriteHostile(dir);
  const formats::Hdf5Reader r(h.file);
  CHECK(r.Numbers("plain", formats::AtMost(2)) == std::vector<double>{1234.5, 6789.25});
  const std::string external = ErrorOf([&] { r.Numbers("external", formats::AtMost(2)); });
  CHECK(Contains(external, "object 'external' keeps its values in another file (HDF5 external storage)"));
  CHECK_FALSE(Contains(external, "1234"));
  // A FIFO never read: the error comes at once instead of a wait for a writer.
  const auto t0 = std::chrono::steady_clock::now();
  CHECK(Contains(ErrorOf([&] { r.Numbers("fifo_data", formats::AtMost(2)); }), "keeps its values in another file"));
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(5));
  CHECK(Contains(ErrorOf([&] { r.Numbers("virtual", formats::AtMost(2)); }), "object 'virtual' is a virtual dataset"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("elink", formats::AtMost(2)); }), "object 'elink' is an external link"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("egroup/v", formats::AtMost(2)); }), "object 'egroup' is an external link"));
  CHECK(Contains(ErrorOf([&] { r.Has("egroup/v"); }), "object 'egroup' is an external link"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("soft", formats::AtMost(2)); }), "object 'soft' is a soft link"));
  // The whole-file check a MAT-file of version 7.3 gets names the first offender.
  const std::string whole = ErrorOf([&] { formats::RequireSelfContainedHdf5(h.file); });
  CHECK(Contains(whole, h.file));
  CHECK((Contains(whole, "keeps its values in another file") || Contains(whole, "is a virtual dataset") ||
         Contains(whole, "link")));
  // The secret was read by nobody: it is as it was, and so is the FIFO.
  CHECK(fs::file_size(h.secret) == 16);
}

TEST_CASE("declared shapes are checked against the caller's bound and the file before anything is allocated") {
  const TempDir dir;
  const Hostile h = WriteHostile(dir);
  const formats::Hdf5Reader r(h.file);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK(Contains(ErrorOf([&] { r.Numbers("declared", formats::AtMost(1000)); }),
                 "object 'declared' declares 250000000 values, more than the 1000 it may hold"));
  CHECK(Contains(ErrorOf([&] { r.Rows("no_columns", formats::AtMost(10), 0); }),
                 "declares 250000000 rows, more than the 10 it may hold"));
  // Within any bound, but never written: HDF5 would make it up from the fill value.
  CHECK(Contains(ErrorOf([&] { r.Numbers("declared", formats::AtMost(300'000'000)); }),
                 "declares 250000000 values, but the file holds 0 of them"));
  CHECK(Contains(ErrorOf([&] { r.Numbers("unwritten", formats::AtMost(100)); }), "but the file holds 0 of them"));
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(5));
  CHECK(Contains(ErrorOf([&] { r.Rows("plain", formats::AtMost(9), 2); }), "has 1 dimensions, not 2"));
}

// The position of `needle` in `bytes`; fails the test if it is not there once.
std::size_t FindOnce(const std::string& bytes, const std::string& needle) {
  const std::size_t at = bytes.find(needle);
  REQUIRE(at != std::string::npos);
  REQUIRE(bytes.find(needle, at + 1) == std::string::npos);
  return at;
}

TEST_CASE("text whose heap entry is damaged is refused before libhdf5 reads it (it read out of bounds)") {
  const TempDir dir;
  const std::string file = dir.File("text.h5");
  const std::string marker = "a text of thirty-two characters!";
  {
    formats::Hdf5Writer w(file);
    w.Text("t", marker);
    w.Texts("list", {"x", "y"});
    w.Close();
  }
  const auto bytes = [&] { return test::ReadAll(file); };
  const auto patch = [&](std::size_t at, const std::string& with) {
    std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
    io.seekp(static_cast<std::streamoff>(at));
    io.write(with.data(), static_cast<std::streamsize>(with.size()));
  };
  CHECK(formats::Hdf5Reader(file).Text("t") == marker);
  // The heap object's size field (8 bytes before the text) claims far more.
  const std::size_t text_at = FindOnce(bytes(), marker);
  const std::string original = bytes().substr(text_at - 8, 8);
  patch(text_at - 8, std::string("\xff\xff\xff\x7f\0\0\0\0", 8));
  const std::string e = ErrorOf([&] { formats::Hdf5Reader(file).Text("t"); });
  CHECK(Contains(e, "object 't' is damaged"));
  patch(text_at - 8, original);
  CHECK(formats::Hdf5Reader(file).Text("t") == marker);
  // The collection's size beyond the end of the file.
  const std::size_t heap_at = FindOnce(bytes(), "GCOL");
  patch(heap_at + 8, std::string("\0\0\0\0\0\0\x10\0", 8));
  CHECK(Contains(ErrorOf([&] { formats::Hdf5Reader(file).Text("t"); }), "object 't' is damaged"));
}

TEST_CASE("text that is not UTF-8 is refused with the object and the byte") {
  const TempDir dir;
  const std::string file = dir.File("latin1.h5");
  {
    formats::Hdf5Writer w(file);
    w.Text("name", "caf\xe9");
    w.Close();
  }
  const std::string e = ErrorOf([&] { formats::Hdf5Reader(file).Text("name"); });
  CHECK(Contains(e, "object 'name' holds text where byte 0xe9 at character 4 is not UTF-8"));
}

TEST_CASE("the same values written a second later give the same file (no times in the objects)") {
  const TempDir dir;
  const auto write = [&](const std::string& name) {
    formats::Hdf5Writer w(dir.File(name));
    w.Text("schema", "x");
    w.Numbers("a/b/c", {1.0, 2.0});
    w.Rows("a/m", {{1.0, 2.0}, {3.0, 4.0}});
    w.Close();
    return test::ReadAll(dir.File(name));
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
