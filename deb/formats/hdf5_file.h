// Internal: not part of the public API.
// HDF5 files of numbers and text, written and read through the HDF5 C
// library. This is the one module that uses HDF5 (matio, mat_file.h, reads
// version-7.3 MAT-files through it, under LockHdf5).
//
// Objects are named by paths of '/'-separated names ("outputs/0/psd");
// writing a dataset creates the groups above it. What is written:
//   - a number (double, 0-dimensional), an integer (int64, 0-dimensional),
//   - a text (variable-length UTF-8 string, 0-dimensional),
//   - a vector of doubles or of texts (1-dimensional),
//   - a matrix of doubles given as rows of equal length (2-dimensional,
//     rows x columns, row-major as h5py and HDF5 show it).
// Vectors and matrices of 2 048 numbers or more are stored in chunks,
// byte-shuffled and deflated (HDF5's standard filters).
// Every file read is treated as possibly hostile (deb/core/input_file.h):
// only a regular file of at most kMaxHdf5FileBytes is opened; an object is
// reached through hard links only (a soft or external link, which could
// lead into another file, is refused before it is followed); a dataset
// whose values lie outside the file (HDF5 external storage, a virtual
// dataset) or are compressed other than as the writer compresses numbers
// is refused before anything is read from it, and a compressed one is
// inflated chunk by chunk into no more than each chunk's size;
// its shape is checked from its header against the bound the caller gives
// (and kMaxHdf5Elements) before anything is allocated; its class and rank
// must be the ones asked for; variable-length text is read only after its
// entries in the file's global heap are found to be whole and inside the
// file (libhdf5 1.10 reads a damaged entry out of bounds); every text must
// be UTF-8; and every number read must be finite unless the caller allows
// NaN (an absent value).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace deb::formats {

// Bounds of what a reader opens: a file of 16 GiB, and a dataset of the
// densest grid (limits::kMaxGridPoints) times 50 channels (2 GB of doubles).
inline constexpr std::uintmax_t kMaxHdf5FileBytes = 16ull << 30;
inline constexpr std::size_t kMaxHdf5Elements = std::size_t{5'000'000} * 50;

// Starts the HDF5 library if it has not started (before any other use of it
// in the process, matio's included: deb turns off its clean-up at exit and
// its plugin loading) and returns the one lock that every call into HDF5
// holds, this module's and matio's. Recursive: the holder may call this
// module.
// @throws InputError if the library does not start.
std::unique_lock<std::recursive_mutex> LockHdf5();

// The most elements (or rows) one read may return. Explicit, so that a bound
// is never taken for a flag or a column count.
struct AtMost {
  explicit AtMost(std::size_t n) : count(n) {}
  std::size_t count;
};

// Checks a whole HDF5 file that another library will read (a MAT-file of
// version 7.3, which matio reads): every object reachable from the root
// through links, and through the object references of datasets (matio's
// cell arrays), is reached by hard links only and holds its values in the
// file itself (no external storage, no virtual dataset). Nothing is read
// but the file's structure and its references.
// @throws InputError "<path>: ..." naming the first offending object, or if
//         the file is not HDF5, is damaged, or holds more than a bound of
//         objects.
void RequireSelfContainedHdf5(const std::string& path);

// How a writer deflates a dataset of numbers (both at zlib's level 1, both
// read by any HDF5 reader). kSearch: zlib's usual search for repeated
// strings, for smooth data (spectra, CPS, grids), which compresses by 1.5 to
// 3 so. kRuns: matches only of the byte just before (zlib's run-length
// strategy), for values whose mantissas are noise to deflate, such as a
// path's gains and phases over a fine grid: the runs in their sign and
// exponent bytes are all there is to find, and searching the mantissas costs
// most of the time. Of the shuffled bytes, a plane that is noise (more than
// 7 in 8 of its bytes differ from the one before) is stored as it is, in the
// same zlib stream. Measured on the responses of a 1000-mode path (20 x 20,
// 10 958 frequencies): 67.4 MB each way; deflate took 1.45 s of CPU with
// the usual search, 0.45 s with runs; storing the noise halved what was left
// (0.25 to 0.13 s in perf's samples of a whole run).
enum class Packing { kSearch, kRuns };

class Hdf5Writer {
 public:
  // Creates (or truncates) `path`.
  // @throws WriteError if HDF5 cannot be loaded or the file cannot be created.
  explicit Hdf5Writer(const std::string& path);
  ~Hdf5Writer();
  Hdf5Writer(const Hdf5Writer&) = delete;
  Hdf5Writer& operator=(const Hdf5Writer&) = delete;

  // Each @throws WriteError naming the file and the object, if HDF5 fails or
  // the object exists already.
  void Number(const std::string& object, double value);
  void Integer(const std::string& object, std::int64_t value);
  void Text(const std::string& object, const std::string& value);
  void Numbers(const std::string& object, const std::vector<double>& values);
  void Texts(const std::string& object, const std::vector<std::string>& values);
  // @pre every row has the same length (DEB_DEMAND); no rows: a 0 x 0 matrix.
  void Rows(const std::string& object, const std::vector<std::vector<double>>& rows,
            Packing packing = Packing::kSearch);
  // A rows x columns matrix from its entries row after row (no copy of a
  // large table). @pre row_major.size() == rows * columns (DEB_DEMAND).
  void Matrix(const std::string& object, std::size_t rows, std::size_t columns, const std::vector<double>& row_major,
              Packing packing = Packing::kSearch);

  // Flushes and closes the file.
  // @throws WriteError if it cannot be completed.
  void Close();

  struct Handle;  // the open file and its groups (hdf5_file.cpp)

 private:
  std::string path_;
  std::unique_ptr<Handle> handle_;
};

class Hdf5Reader {
 public:
  // @throws InputError "<path>: ..." if HDF5 cannot be loaded, the file does
  //         not exist, is not a regular file, is larger than the bound or is
  //         not an HDF5 file.
  explicit Hdf5Reader(const std::string& path);
  ~Hdf5Reader();
  Hdf5Reader(const Hdf5Reader&) = delete;
  Hdf5Reader& operator=(const Hdf5Reader&) = delete;

  const std::string& path() const { return path_; }
  // Whether the object (group or dataset) exists.
  // @throws InputError if it, or a group above it, is a soft or external link.
  bool Has(const std::string& object) const;

  // Each @throws InputError "<path>: object 'NAME' ..." for a missing object,
  // one reached through a soft or external link, one stored outside the
  // file or compressed otherwise than deb writes, a compressed chunk that
  // does not inflate to its size or is missing, one of another class or
  // rank than asked for, more elements (rows) than `most` or
  // kMaxHdf5Elements, rows of another length than `columns`, text that is not UTF-8 or whose heap entries are
  // damaged, a value that is not finite (NaN allowed where `allow_nan`), or
  // anything HDF5 reports while reading.
  double Number(const std::string& object, bool allow_nan = false) const;
  std::int64_t Integer(const std::string& object) const;
  std::string Text(const std::string& object) const;
  std::vector<double> Numbers(const std::string& object, AtMost most, bool allow_nan = false) const;
  std::vector<std::string> Texts(const std::string& object, AtMost most) const;
  // A matrix of at most `most` rows of `columns` values each (a matrix
  // without rows may declare any number of columns).
  std::vector<std::vector<double>> Rows(const std::string& object, AtMost most, std::size_t columns,
                                        bool allow_nan = false) const;

  struct Handle;  // the open file and what was checked of it (hdf5_file.cpp)

 private:
  std::string path_;
  std::unique_ptr<Handle> handle_;
};

}  // namespace deb::formats
