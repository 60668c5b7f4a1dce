#include "deb/formats/hdf5_file.h"

#include <hdf5.h>
#define ZLIB_CONST  // z_stream reads its input through a const pointer
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <set>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/parallel.h"

namespace deb::formats {
namespace {

// Starts the library once per process, before any other use of it (the
// .mat reader calls LockHdf5 too, since matio reads version-7.3 files
// through HDF5). "" if it started, else why not.
std::string Start() {
  // No clean-up of HDF5 at exit: deb closes every file it opens itself, and
  // the library's own clean-up closes again a file whose H5Fclose failed (a
  // full disk), which ends the process in SIGSEGV after its error was
  // reported. Only possible before the library is first used.
  H5dont_atexit();
  if (H5open() < 0) return "the HDF5 library did not start (H5open failed)";
  // Filters are refused (Open) and none is needed: no plugin is loaded
  // from the directories HDF5_PLUGIN_PATH names.
  if (H5PLset_loading_state(0) < 0) return "the HDF5 library refused to turn plugin loading off";
  return "";
}

// Why HDF5 cannot be used, for messages; "" if it can.
const std::string& StartFailure() {
  static const std::string failure = Start();
  return failure;
}

// Every call into HDF5, deb's and matio's, holds this lock: an HDF5 built
// without thread safety needs it, and a thread-safe one serialises its
// calls anyway. Recursive: a matio call that holds it may end in a read
// of this module.
std::recursive_mutex g_hdf5;

// Turns HDF5's printing of its error stack off for the calling thread (once
// per thread): deb reports errors itself, and a thread-safe HDF5 keeps that
// setting per thread (the store is written on a thread of its own).
void QuietThisThread() {
  thread_local bool quiet = false;
  if (!quiet && StartFailure().empty()) quiet = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
}

// The lock, with the calling thread quiet.
class Locked {
 public:
  Locked() : lock_(g_hdf5) { QuietThisThread(); }

 private:
  std::lock_guard<std::recursive_mutex> lock_;
};

// Closes an HDF5 identifier when it goes out of scope.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id(hid_t id, Closer close) : id_(id), close_(close) {}
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  Id(Id&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id& operator=(Id&&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer close_;
};

// The transfer properties of every read and write of one file: a
// type-conversion buffer of 64 KiB instead of HDF5's 1 MiB, which it
// allocates and zeroes for every dataset of text (converted on the way):
// with the default, writing a store of a few thousand small datasets took
// twice as long. Made per file, not once: another user of the library in
// the process (matio) may close and reopen it. -1 if it cannot be made.
hid_t NewTransfer() {
  const hid_t t = H5Pcreate(H5P_DATASET_XFER);
  if (t >= 0 && H5Pset_buffer(t, std::size_t{64} << 10, nullptr, nullptr) < 0) {
    H5Pclose(t);
    return -1;
  }
  return t;
}

std::vector<std::string> Split(const std::string& object) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= object.size()) {
    const std::size_t end = std::min(object.find('/', start), object.size());
    if (end > start) parts.push_back(object.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

Id VariableString() {
  Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (type.ok()) {
    H5Tset_size(type.get(), H5T_VARIABLE);
    H5Tset_cset(type.get(), H5T_CSET_UTF8);
  }
  return type;
}

}  // namespace

std::unique_lock<std::recursive_mutex> LockHdf5() {
  std::unique_lock<std::recursive_mutex> lock(g_hdf5);
  if (const std::string& why = StartFailure(); !why.empty()) throw InputError(why);
  QuietThisThread();
  return lock;
}

// ---------------------------------------------------------------- writing

struct Hdf5Writer::Handle {
  hid_t file = -1;
  // Creation properties of every dataset and group: without modification
  // times, which HDF5 records by default, so that a file written twice from
  // the same values is the same file (a reproducible report).
  hid_t dataset_create = -1;
  hid_t group_create = -1;
  hid_t transfer = -1;  // NewTransfer
  // The groups created or opened so far, by '/'-path, open until Close.
  std::map<std::string, hid_t> groups;

  void CloseAll() {
    for (const auto& g : groups) H5Gclose(g.second);
    groups.clear();
    for (hid_t* p : {&dataset_create, &group_create, &transfer})
      if (*p >= 0) H5Pclose(*p), *p = -1;
  }
};

Hdf5Writer::Hdf5Writer(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  const Locked lock;
  if (const std::string why = StartFailure(); !why.empty()) throw WriteError("cannot write " + path + ": " + why);
  // The file format of HDF5 1.8 (2008) and later, which any current reader
  // (h5py, MATLAB, HDFView) reads: its groups keep their few links in the
  // group's header instead of a B-tree and a heap, which makes a store of
  // thousands of small objects faster to write and read, and smaller.
  // The root group, like every object below, without modification times.
  const Id access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose), create(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  if (!access.ok() || !create.ok() || H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_V18) < 0 ||
      H5Pset_obj_track_times(create.get(), 0) < 0)
    throw WriteError("cannot set up the HDF5 file " + path);
  handle_->file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, create.get(), access.get());
  if (handle_->file < 0) throw WriteError("cannot create the HDF5 file " + path);
  handle_->transfer = NewTransfer();
  handle_->dataset_create = H5Pcreate(H5P_DATASET_CREATE);
  handle_->group_create = H5Pcreate(H5P_GROUP_CREATE);
  if (handle_->dataset_create < 0 || handle_->group_create < 0 || handle_->transfer < 0 ||
      H5Pset_obj_track_times(handle_->dataset_create, 0) < 0 ||
      H5Pset_obj_track_times(handle_->group_create, 0) < 0)
    throw WriteError("cannot set up the HDF5 file " + path);
}

Hdf5Writer::~Hdf5Writer() {
  if (handle_ && (handle_->file >= 0 || handle_->dataset_create >= 0)) {
    const Locked lock;
    handle_->CloseAll();
    if (handle_->file >= 0) H5Fclose(handle_->file);
  }
}

void Hdf5Writer::Close() {
  const Locked lock;
  handle_->CloseAll();
  const hid_t file = handle_->file;
  handle_->file = -1;
  if (file >= 0 && H5Fclose(file) < 0) throw WriteError("cannot complete the HDF5 file " + path_);
}

namespace {

// Numbers from kCompressFromValues values on are stored compressed: in
// chunks of at most kChunkValues (256 KiB), each byte-shuffled and then
// deflated, HDF5's standard filters, which h5py, MATLAB and HDFView read.
// Spectra compress by 1.5-3x so. Smaller datasets stay contiguous: in this
// file format each chunked dataset carries a chunk index of about 2.5 KiB,
// more than compressing a small one saves. Deflate level 1: level 4 made
// wafer_stage's store 0.8 % smaller and a 1000-mode loop's (55 MB of
// responses, which barely compress) 0.4 %, for 0.65 s more of that run.
constexpr std::size_t kCompressFromValues = 2048;
constexpr std::size_t kChunkValues = 32768;
constexpr unsigned kDeflateLevel = 1;

// The chunk of a compressed dataset of `dims`: whole rows, at most kChunkValues.
std::vector<hsize_t> ChunkOf(const std::vector<hsize_t>& dims) {
  std::vector<hsize_t> chunk = dims;
  if (dims.size() == 1) chunk[0] = std::min<hsize_t>(dims[0], kChunkValues);
  if (dims.size() == 2) {
    chunk[1] = std::min<hsize_t>(dims[1], kChunkValues);
    chunk[0] = std::min<hsize_t>(dims[0], std::max<hsize_t>(1, kChunkValues / chunk[1]));
  }
  return chunk;
}

// `bytes` as one zlib stream (RFC 1950, what HDF5's deflate filter reads)
// at level 1 with its usual search. For Packing::kRuns, `bytes` are the
// byte planes of shuffled doubles, `plane` bytes each (least significant
// first): each plane goes into the stream as matches only of the byte just
// before (zlib's run-length strategy), or, where more than 7 in 8 of its
// bytes differ from the one before (the low mantissa bytes of computed
// values), stored as it is: deflate finds nothing there, and passing noise
// through its coder was most of its time. One stream of mixed blocks, as
// any inflater reads.
std::vector<unsigned char> Deflated(const std::vector<unsigned char>& bytes, Packing packing, std::size_t plane) {
  const bool runs = packing == Packing::kRuns && plane > 0 && bytes.size() % plane == 0;
  z_stream z{};
  if (deflateInit2(&z, static_cast<int>(kDeflateLevel), Z_DEFLATED, 15, 8, runs ? Z_RLE : Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::bad_alloc();
  // deflateBound's room plus the ends of a block per plane (at most 64 planes).
  std::vector<unsigned char> out(deflateBound(&z, static_cast<uLong>(bytes.size())) + 64 * 16);
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  const std::size_t step = runs ? plane : bytes.size();
  int level = static_cast<int>(kDeflateLevel), done = Z_OK;
  for (std::size_t at = 0; at < bytes.size() || at == 0; at += step) {
    const std::size_t count = std::min(step, bytes.size() - at);
    if (runs) {
      std::size_t changes = 0;
      for (std::size_t i = at + 1; i < at + count; ++i) changes += bytes[i] != bytes[i - 1];
      const int wanted = changes * 8 > count * 7 ? 0 : static_cast<int>(kDeflateLevel);
      if (wanted != level && deflateParams(&z, wanted, Z_RLE) != Z_OK) break;
      level = wanted;
    }
    z.next_in = const_cast<unsigned char*>(bytes.data() + at);
    z.avail_in = static_cast<uInt>(count);
    const bool last = at + count >= bytes.size();
    done = deflate(&z, last ? Z_FINISH : Z_NO_FLUSH);
    if (last || done != Z_OK || z.avail_in != 0) break;
  }
  const uLong size = z.total_out;
  deflateEnd(&z);
  // With this room, Z_FINISH completes in one call; anything else is a want
  // of memory.
  if (done != Z_STREAM_END) throw std::bad_alloc();
  out.resize(size);
  return out;
}

// Writes the doubles `data` (row-major, `dims`) into the chunked dataset
// `set` chunk by chunk as the shuffle and deflate filters would store them:
// each chunk (edge chunks padded with zeros, the fill value) byte-shuffled
// and deflated here, on all threads, a batch at a time, then handed to
// HDF5 as it is (H5Dwrite_chunk). HDF5 would filter them one after the
// other: a 200 MB store took 4.5 s so. The values are stored as the file's
// F64LE, converted first where this machine's doubles differ (the inverse of
// ReadCompressed). Returns false if HDF5 refused a chunk or the conversion.
bool WriteShuffledDeflated(hid_t set, const std::vector<hsize_t>& dims, const double* data, Packing packing) {
  std::vector<double> little_endian;
  if (H5Tequal(H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE) <= 0) {
    hsize_t count = 1;
    for (hsize_t d : dims) count *= d;
    little_endian.assign(data, data + count);
    if (H5Tconvert(H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, count, little_endian.data(), nullptr, H5P_DEFAULT) < 0)
      return false;
    data = little_endian.data();
  }
  const std::vector<hsize_t> chunk = ChunkOf(dims);
  const bool two = dims.size() == 2;
  const hsize_t rows = two ? dims[0] : 1, cols = two ? dims[1] : dims[0];
  const hsize_t chunk_rows = two ? chunk[0] : 1, chunk_cols = two ? chunk[1] : chunk[0];
  const hsize_t across = (cols + chunk_cols - 1) / chunk_cols, down = (rows + chunk_rows - 1) / chunk_rows;
  const std::size_t values = static_cast<std::size_t>(chunk_rows * chunk_cols), bytes = values * sizeof(double);
  const std::size_t chunks = static_cast<std::size_t>(across * down);
  // Chunk c's first row and column.
  const auto origin = [&](hsize_t c) { return std::array<hsize_t, 2>{(c / across) * chunk_rows, (c % across) * chunk_cols}; };
  constexpr std::size_t kBatch = 64;  // chunks in memory at once: 16 MiB before compression
  std::vector<std::vector<unsigned char>> out(std::min(kBatch, chunks));
  for (std::size_t first = 0; first < chunks; first += kBatch) {
    const std::size_t count = std::min(kBatch, chunks - first);
    ParallelForEach(count, [&](std::size_t b) {
      const auto [r0, c0] = origin(first + b);
      std::vector<double> values_in(values, 0.0);
      for (hsize_t r = 0; r < chunk_rows && r0 + r < rows; ++r)
        for (hsize_t k = 0; k < chunk_cols && c0 + k < cols; ++k)
          values_in[static_cast<std::size_t>(r * chunk_cols + k)] = data[(r0 + r) * cols + c0 + k];
      const auto* in = reinterpret_cast<const unsigned char*>(values_in.data());
      std::vector<unsigned char> shuffled(bytes);
      for (std::size_t i = 0; i < values; ++i)
        for (std::size_t y = 0; y < sizeof(double); ++y) shuffled[y * values + i] = in[i * sizeof(double) + y];
      out[b] = Deflated(shuffled, packing, values);
    });
    for (std::size_t b = 0; b < count; ++b) {
      const std::array<hsize_t, 2> offset = origin(first + b);  // a vector's offset is its column
      if (H5Dwrite_chunk(set, H5P_DEFAULT, 0, two ? offset.data() : offset.data() + 1, out[b].size(), out[b].data()) < 0)
        return false;
    }
  }
  return true;
}

// Writes one dataset of `type_in_file` and `dims` (empty: a scalar) from
// `data` in `type_in_memory` under `file`, creating the groups above it;
// `compress`: numbers, compressed (as `packing` says) when there are enough
// of them.
void WriteDataset(Hdf5Writer::Handle& h, const std::string& path, const std::string& object, hid_t type_in_file,
                  hid_t type_in_memory, const std::vector<hsize_t>& dims, const void* data, bool compress = false,
                  Packing packing = Packing::kSearch) {
  const std::vector<std::string> parts = Split(object);
  DEB_DEMAND(!parts.empty());
  const auto fail = [&](const std::string& what) {
    throw WriteError("cannot write '" + object + "' to the HDF5 file " + path + ": " + what);
  };
  // The groups above, opened or created once and kept open.
  hid_t at = h.file;
  std::string group_path;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    group_path += "/" + parts[i];
    const auto known = h.groups.find(group_path);
    if (known != h.groups.end()) {
      at = known->second;
      continue;
    }
    const htri_t exists = H5Lexists(at, parts[i].c_str(), H5P_DEFAULT);
    const hid_t g = exists > 0 ? H5Gopen2(at, parts[i].c_str(), H5P_DEFAULT)
                               : H5Gcreate2(at, parts[i].c_str(), H5P_DEFAULT, h.group_create, H5P_DEFAULT);
    if (g < 0) fail("cannot create or open the group '" + parts[i] + "'");
    h.groups.emplace(group_path, g);
    at = g;
  }

  Id space(dims.empty() ? H5Screate(H5S_SCALAR)
                        : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
           H5Sclose);
  if (!space.ok()) fail("cannot make its dataspace");
  hsize_t values = 1;
  for (hsize_t d : dims) values *= d;
  const bool chunked = compress && values >= kCompressFromValues;
  const Id compressed(chunked ? H5Pcopy(h.dataset_create) : -1, H5Pclose);
  if (chunked) {
    const std::vector<hsize_t> chunk = ChunkOf(dims);
    if (!compressed.ok() || H5Pset_chunk(compressed.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
        H5Pset_shuffle(compressed.get()) < 0 || H5Pset_deflate(compressed.get(), kDeflateLevel) < 0)
      fail("cannot set up its compression");
  }
  Id set(H5Dcreate2(at, parts.back().c_str(), type_in_file, space.get(), H5P_DEFAULT,
                    compressed.ok() ? compressed.get() : h.dataset_create, H5P_DEFAULT),
         H5Dclose);
  if (!set.ok())
    fail(H5Lexists(at, parts.back().c_str(), H5P_DEFAULT) > 0 ? "it exists already" : "cannot create the dataset");
  bool empty = false;
  for (hsize_t d : dims) empty |= d == 0;
  if (!empty && chunked) {
    DEB_DEMAND(type_in_memory == H5T_NATIVE_DOUBLE);
    if (!WriteShuffledDeflated(set.get(), dims, static_cast<const double*>(data), packing)) fail("cannot write its data");
  } else if (!empty && H5Dwrite(set.get(), type_in_memory, H5S_ALL, H5S_ALL, h.transfer, data) < 0) {
    fail("cannot write its data");
  }
}

}  // namespace

void Hdf5Writer::Number(const std::string& object, double value) {
  const Locked lock;
  WriteDataset(*handle_, path_, object, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {}, &value);
}

void Hdf5Writer::Integer(const std::string& object, std::int64_t value) {
  const Locked lock;
  const long long v = value;
  WriteDataset(*handle_, path_, object, H5T_STD_I64LE, H5T_NATIVE_LLONG, {}, &v);
}

void Hdf5Writer::Text(const std::string& object, const std::string& value) {
  const Locked lock;
  const Id type = VariableString();
  const char* text = value.c_str();
  WriteDataset(*handle_, path_, object, type.get(), type.get(), {}, &text);
}

void Hdf5Writer::Numbers(const std::string& object, const std::vector<double>& values) {
  const Locked lock;
  WriteDataset(*handle_, path_, object, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {values.size()}, values.data(), true);
}

void Hdf5Writer::Texts(const std::string& object, const std::vector<std::string>& values) {
  const Locked lock;
  const Id type = VariableString();
  std::vector<const char*> texts;
  for (const std::string& v : values) texts.push_back(v.c_str());
  WriteDataset(*handle_, path_, object, type.get(), type.get(), {values.size()}, texts.data());
}

void Hdf5Writer::Rows(const std::string& object, const std::vector<std::vector<double>>& rows, Packing packing) {
  const std::size_t columns = rows.empty() ? 0 : rows.front().size();
  std::vector<double> data;
  data.reserve(rows.size() * columns);
  for (const std::vector<double>& r : rows) {
    DEB_DEMAND(r.size() == columns);
    data.insert(data.end(), r.begin(), r.end());
  }
  Matrix(object, rows.size(), rows.empty() ? 0 : columns, data, packing);
}

void Hdf5Writer::Matrix(const std::string& object, std::size_t rows, std::size_t columns,
                        const std::vector<double>& row_major, Packing packing) {
  DEB_DEMAND(row_major.size() == rows * columns);
  const Locked lock;
  WriteDataset(*handle_, path_, object, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {rows, columns}, row_major.data(), true,
               packing);
}

// ---------------------------------------------------------------- reading

namespace {

// Objects one file may hold for RequireSelfContainedHdf5: a MAT-file's
// 100 000 variables (limits::kMaxMatVariables) with their cells and structs.
constexpr std::size_t kMaxHdf5Objects = 250'000;

// A little-endian unsigned integer of `n` bytes (HDF5's file format).
std::uint64_t Little(const unsigned char* p, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t k = n; k-- > 0;) v = v << 8 | p[k];
  return v;
}

// The bytes of the file as they are on disk, read by deb itself for the
// checks libhdf5 1.10 does not make (VariableText).
class RawFile {
 public:
  explicit RawFile(const std::string& path) : in_(path, std::ios::binary) {
    in_.seekg(0, std::ios::end);
    size_ = in_ ? static_cast<std::uint64_t>(in_.tellg()) : 0;
  }
  std::uint64_t size() const { return size_; }
  // True if `n` bytes at HDF5 address `address` lie in the file; addresses
  // count from `base`, the end of the user block.
  bool Holds(std::uint64_t base, std::uint64_t address, std::uint64_t n) const {
    return address <= size_ && base <= size_ - address && n <= size_ - base - address;
  }
  // `n` bytes at `at`; false if they are not all in the file.
  bool Read(std::uint64_t at, std::uint64_t n, unsigned char* out) {
    if (at > size_ || n > size_ - at) return false;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return in_.gcount() == static_cast<std::streamsize>(n);
  }

 private:
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

// What is wrong with an old-style group's index (HDF5 file format, "Symbol
// Table Message", "Version 1 B-trees", "Symbol Table Node", "Local Heap"), or
// "" if its local heap lies inside the file and its B-tree is a tree: every
// node inside the file, one level below its parent, reached once, its leaves
// symbol table nodes whose entries lie inside the file. libhdf5 1.10 follows
// a B-tree's child addresses without these checks: a fuzzed 13 KB MAT-file
// whose B-tree led back into itself had it allocate 24 GB.
std::string SymbolTableProblem(RawFile& raw, std::uint64_t base, std::size_t sa, std::size_t ss, std::uint64_t btree,
                               std::uint64_t heap) {
  const auto outside = [&](std::uint64_t at, std::uint64_t n) { return !raw.Holds(base, at, n); };
  const auto damaged = [](const std::string& what, std::uint64_t at) {
    return "has a damaged group index: " + what + " at address " + std::to_string(at) + "; is the file damaged?";
  };
  unsigned char head[64] = {};
  if (outside(heap, 8 + 2 * ss + sa) || !raw.Read(base + heap, 8 + 2 * ss + sa, head) ||
      std::memcmp(head, "HEAP", 4) != 0)
    return damaged("no local heap", heap);
  const std::uint64_t heap_bytes = Little(head + 8, ss), heap_data = Little(head + 8 + 2 * ss, sa);
  if (outside(heap_data, heap_bytes)) return damaged("a local heap of " + std::to_string(heap_bytes) + " bytes", heap_data);
  // The heap's free list: blocks of (next offset, size), ended by offset 1.
  // libhdf5 follows it without looking for a cycle, allocating a node per
  // block: a fuzzed MAT-file's list that led back to itself grew it to 24 GB.
  {
    std::uint64_t free_block = Little(head + 8 + ss, ss), blocks = 0;
    unsigned char pair[16];
    while (free_block != 1) {
      if (++blocks > heap_bytes / (2 * ss) || free_block > heap_bytes || 2 * ss > heap_bytes - free_block ||
          !raw.Read(base + heap_data + free_block, 2 * ss, pair))
        return damaged("a local heap whose free list is not a list inside it", heap);
      const std::uint64_t bytes = Little(pair + ss, ss);
      if (bytes > heap_bytes - free_block) return damaged("a local heap whose free list is not a list inside it", heap);
      free_block = Little(pair, ss);
    }
  }
  const std::size_t entry = 2 * sa + 24;  // a symbol table entry
  // The heap's data, for the link names: each must end inside it (libhdf5
  // copies a name up to its terminating zero).
  std::vector<unsigned char> names(static_cast<std::size_t>(heap_bytes));
  if (!raw.Read(base + heap_data, heap_bytes, names.data())) return damaged("an unreadable local heap", heap_data);
  std::vector<std::pair<std::uint64_t, int>> pending{{btree, -1}};  // address, expected level (-1: any)
  std::set<std::uint64_t> seen;
  while (!pending.empty()) {
    const auto [at, expected] = pending.back();
    pending.pop_back();
    if (!seen.insert(at).second) return damaged("a node reached twice", at);
    if (seen.size() > kMaxHdf5Objects) return damaged("more than " + std::to_string(kMaxHdf5Objects) + " nodes", at);
    const std::size_t node_head = 8 + 2 * sa;
    if (outside(at, node_head) || !raw.Read(base + at, node_head, head) || std::memcmp(head, "TREE", 4) != 0 ||
        head[4] != 0)
      return damaged("no group B-tree node", at);
    const int level = head[5];
    const std::uint64_t entries = Little(head + 6, 2);
    if (expected >= 0 && level != expected)
      return damaged("a B-tree node at level " + std::to_string(level) + " below one at level " +
                         std::to_string(expected + 1),
                     at);
    const std::uint64_t body = entries * (ss + sa) + ss;
    if (outside(at + node_head, body)) return damaged("a B-tree node of " + std::to_string(entries) + " entries", at);
    std::vector<unsigned char> keys(static_cast<std::size_t>(body));
    if (!raw.Read(base + at + node_head, body, keys.data())) return damaged("an unreadable B-tree node", at);
    for (std::uint64_t u = 0; u < entries; ++u) {
      const std::uint64_t child = Little(keys.data() + u * (ss + sa) + ss, sa);
      if (level > 0) {
        pending.emplace_back(child, level - 1);
        continue;
      }
      unsigned char node[8];
      if (outside(child, 8) || !raw.Read(base + child, 8, node) || std::memcmp(node, "SNOD", 4) != 0)
        return damaged("no symbol table node", child);
      const std::uint64_t symbols = Little(node + 6, 2);
      if (outside(child + 8, symbols * entry))
        return damaged("a symbol table node of " + std::to_string(symbols) + " entries", child);
      if (!seen.insert(child).second) return damaged("a node reached twice", child);
      std::vector<unsigned char> symbol(entry);
      for (std::uint64_t k = 0; k < symbols; ++k) {
        if (!raw.Read(base + child + 8 + k * entry, entry, symbol.data())) return damaged("an unreadable entry", child);
        const std::uint64_t name = Little(symbol.data(), ss);
        if (name >= names.size() || std::find(names.begin() + static_cast<std::ptrdiff_t>(name), names.end(), 0) ==
                                        names.end())
          return damaged("a link name that does not end inside the group's local heap", child);
      }
    }
  }
  return "";
}

// What is wrong with the object header at `address` (HDF5 file format,
// "Data Object Headers", versions 1 and 2), or "" if its first chunk and
// every continuation chunk it names lie inside the file. libhdf5 1.10
// allocates a chunk of the size the header states before it reads it: a
// fuzzed 7.6 KB MAT-file stated 4 GB. A header deb does not recognise is
// left to libhdf5, which refuses it.
std::string ObjectHeaderProblem(RawFile& raw, std::uint64_t base, std::size_t address_bytes, std::size_t length_bytes,
                                std::uint64_t address) {
  constexpr std::size_t kMaxChunks = 1000;
  constexpr std::uint64_t kMaxCheckedBytes = 64ull << 20;
  const std::uint64_t size = raw.size();
  const auto outside = [&](std::uint64_t at, std::uint64_t n) { return !raw.Holds(base, at, n); };
  const auto past_end = [&](const char* what, std::uint64_t at, std::uint64_t n) {
    return std::string("has ") + what + " of " + std::to_string(n) + " bytes at address " + std::to_string(at) +
           ", which the file (" + std::to_string(size) + " bytes) does not hold; is the file damaged?";
  };
  unsigned char head[48] = {};
  if (outside(address, 6) || !raw.Read(base + address, std::min<std::uint64_t>(sizeof head, size - base - address),
                                       head))
    return "";
  // The first chunk: where its messages start and end.
  bool v2 = false, creation_order = false;
  std::uint64_t start = 0, length = 0;
  if (std::memcmp(head, "OHDR", 4) == 0 && head[4] == 2) {
    v2 = true;
    const unsigned flags = head[5];
    creation_order = (flags & 0x04) != 0;
    std::size_t p = 6 + ((flags & 0x20) ? 16 : 0) + ((flags & 0x10) ? 4 : 0);
    const std::size_t width = std::size_t{1} << (flags & 0x03);
    length = Little(head + p, width);
    start = address + p + width;
    if (length > size || outside(start, length + 4)) return past_end("a header", address, length);
  } else if (head[0] == 1) {
    length = Little(head + 8, 4);
    start = address + 16;
    if (outside(start, length)) return past_end("a header", address, length);
  } else {
    return "";
  }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> chunks{{start, length}};
  std::set<std::uint64_t> seen;
  std::uint64_t checked = 0, btree = 0, heap = 0;
  bool symbol_table = false;
  while (!chunks.empty() && seen.size() < kMaxChunks) {
    const auto [at, n] = chunks.back();
    chunks.pop_back();
    if (!seen.insert(at).second || n > kMaxCheckedBytes - checked) continue;
    checked += n;
    std::vector<unsigned char> chunk(static_cast<std::size_t>(n));
    if (!raw.Read(base + at, n, chunk.data())) return "";
    const std::size_t message_head = v2 ? (creation_order ? 6 : 4) : 8;
    for (std::size_t p = 0; p + message_head <= chunk.size();) {
      const unsigned char* m = chunk.data() + p;
      const std::uint64_t type = v2 ? m[0] : Little(m, 2), bytes = v2 ? Little(m + 1, 2) : Little(m + 2, 2);
      p += message_head;
      if (bytes > chunk.size() - p) break;
      // An attribute's name (versions 1 to 3 of the message: version,
      // flags, name size, datatype size, dataspace size, [encoding], name)
      // must end with its zero inside the message: libhdf5 copies it up to
      // the zero (a fuzzed MAT-file's name ran past the end of the header).
      // Its datatype and dataspace, whose sizes follow the name size, must
      // fit in the message too (version 1 pads each part to 8 bytes): a
      // fuzzed file's dataspace of 2048 bytes in a 48-byte message had it
      // copy past a buffer.
      if (type == 0x0C) {
        const unsigned char* m = chunk.data() + p;
        const std::uint64_t version = bytes >= 8 ? m[0] : 0, at = version >= 3 ? 9 : 8;
        const std::uint64_t name_bytes = bytes >= 8 ? Little(m + 2, 2) : 0;
        if (version < 1 || version > 3 || name_bytes == 0 || at + name_bytes > bytes || m[at + name_bytes - 1] != 0)
          return "has a damaged attribute (its name does not end inside it); is the file damaged?";
        const auto part = [&](std::uint64_t n) { return version == 1 ? (n + 7) / 8 * 8 : n; };
        const std::uint64_t datatype = Little(m + 4, 2), dataspace = Little(m + 6, 2);
        if (datatype == 0 || dataspace == 0 || at + part(name_bytes) + part(datatype) + part(dataspace) > bytes)
          return "has a damaged attribute (its parts do not fit in it); is the file damaged?";
      }
      // An old-style group's index: checked once the header is.
      if (type == 0x11 && 2 * address_bytes <= chunk.size() - p) {
        symbol_table = true;
        btree = Little(chunk.data() + p, address_bytes);
        heap = Little(chunk.data() + p + address_bytes, address_bytes);
      }
      // A continuation: libhdf5 decodes its address and length whatever
      // size the message states.
      if (type == 0x10 && address_bytes + length_bytes <= chunk.size() - p) {
        const std::uint64_t to = Little(chunk.data() + p, address_bytes),
                            count = Little(chunk.data() + p + address_bytes, length_bytes);
        if (outside(to, count)) return past_end("a header continuation", to, count);
        // A version-2 continuation chunk is "OCHK", messages, a checksum.
        if (v2 && count >= 8) chunks.emplace_back(to + 4, count - 8);
        if (!v2) chunks.emplace_back(to, count);
      }
      p += static_cast<std::size_t>(bytes);
    }
  }
  return symbol_table ? SymbolTableProblem(raw, base, address_bytes, length_bytes, btree, heap) : "";
}

}  // namespace

namespace {

// The layout of an open file, for the checks deb reads bytes for: its user
// block (addresses count from its end), and the bytes of an address and of
// a length.
void ReadLayout(const std::string& path, hid_t file, std::uint64_t& base, std::size_t& address_bytes,
                std::size_t& length_bytes) {
  const Id create(H5Fget_create_plist(file), H5Pclose);
  hsize_t user_block = 0;
  if (!create.ok() || H5Pget_sizes(create.get(), &address_bytes, &length_bytes) < 0 ||
      H5Pget_userblock(create.get(), &user_block) < 0 || address_bytes < 2 || address_bytes > 8 || length_bytes < 2 ||
      length_bytes > 8)
    throw InputError(path + ": not an HDF5 file, or a damaged one");
  base = user_block;
}

}  // namespace

struct Hdf5Reader::Handle {
  hid_t file = -1;
  hid_t transfer = -1;  // NewTransfer
  // Paths found to be reached through hard links only (Reach).
  std::set<std::string> hard;
  // The file's layout, for VariableText: its user block (addresses count
  // from its end), and the bytes of an address and of a length.
  std::uint64_t base = 0;
  std::size_t address_bytes = 8, length_bytes = 8;
  std::unique_ptr<RawFile> raw;
  // Global heap collections found whole, by address: each object's index
  // and size.
  std::map<std::uint64_t, std::map<std::uint64_t, std::uint64_t>> heaps;
};

Hdf5Reader::Hdf5Reader(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  RequireInputFile(path, "HDF5 file", kMaxHdf5FileBytes);
  const Locked lock;
  if (const std::string why = StartFailure(); !why.empty()) throw InputError(path + ": reading it needs " + why);
  handle_->file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (handle_->file < 0) throw InputError(path + ": not an HDF5 file, or a damaged one");
  handle_->transfer = NewTransfer();
  if (handle_->transfer < 0) throw InputError(path + ": cannot set up reading it (HDF5)");
  ReadLayout(path, handle_->file, handle_->base, handle_->address_bytes, handle_->length_bytes);
  handle_->raw = std::make_unique<RawFile>(path);
}

Hdf5Reader::~Hdf5Reader() {
  if (handle_ && handle_->file >= 0) {
    const Locked lock;
    if (handle_->transfer >= 0) H5Pclose(handle_->transfer);
    H5Fclose(handle_->file);
  }
}

namespace {

enum class Kind { kDouble, kInteger, kText };

const char* KindName(Kind k) {
  switch (k) {
    case Kind::kDouble: return "numbers";
    case Kind::kInteger: return "an integer";
    case Kind::kText: return "text";
  }
  return "";
}

// An open dataset with its checked shape.
struct OpenSet {
  std::unique_ptr<Id> set;
  std::vector<hsize_t> dims;
  std::size_t elements = 1;
  hid_t transfer = H5P_DEFAULT;  // the reader's (NewTransfer)
  std::vector<hsize_t> chunk;    // of a compressed dataset (ReadCompressed); empty otherwise
};

std::string LinkKind(H5L_type_t type) {
  switch (type) {
    case H5L_TYPE_SOFT: return "a soft link (a path to another object)";
    case H5L_TYPE_EXTERNAL: return "an external link (to an object of another file)";
    default: return "a user-defined link";
  }
}

// Whether `object` exists, reached from the root through hard links only.
// Each name on the way is looked at (H5Lget_info does not follow the link
// it describes) before anything goes through it.
// @throws InputError for a link of another kind on the way.
bool Reach(Hdf5Reader::Handle& h, const std::string& path, const std::string& object) {
  std::string prefix;
  for (const std::string& part : Split(object)) {
    prefix += (prefix.empty() ? "" : "/") + part;
    if (h.hard.count(prefix)) continue;
    H5L_info_t info;
    if (H5Lget_info(h.file, prefix.c_str(), &info, H5P_DEFAULT) < 0) return false;
    if (info.type != H5L_TYPE_HARD)
      throw InputError(path + ": object '" + Excerpt(prefix, 200) + "' is " + LinkKind(info.type) +
                       "; deb reads only objects the file holds itself, reached by plain (hard) links");
    h.hard.insert(prefix);
  }
  return !prefix.empty();
}

// Why a dataset with creation properties `create` must not be read, or "":
// its values outside the file (external storage, a virtual dataset), or
// compressed where `allow_filters` is false (a small file could expand into
// any size; a compressed dataset of numbers is read by ReadCompressed,
// which bounds what each chunk expands into).
std::string StorageProblem(hid_t create, bool allow_filters) {
  if (create < 0) return "has unreadable storage properties; is the file damaged?";
  if (H5Pget_external_count(create) != 0)
    return "keeps its values in another file (HDF5 external storage); deb reads only what the file holds itself";
  if (H5Pget_layout(create) == H5D_VIRTUAL)
    return "is a virtual dataset (its values come from other datasets or files); deb reads only what the file "
           "holds itself";
  if (!allow_filters && H5Pget_nfilters(create) != 0)
    return "is compressed or filtered; a reader of deb's files reads plain datasets only";
  return "";
}

// The most values of one chunk of a compressed dataset: 32 MiB of doubles
// (deb writes chunks of 256 KiB).
constexpr hsize_t kMaxChunkValues = hsize_t{1} << 22;

// Why a filtered dataset of numbers of shape `dims` must not be read, or ""
// (setting `chunk`): deb reads the compression it writes only, chunks of
// little-endian doubles byte-shuffled and then deflated, each chunk at most
// kMaxChunkValues and no larger than the dataset.
std::string CompressionProblem(hid_t create, hid_t type, const std::vector<hsize_t>& dims,
                               std::vector<hsize_t>* chunk) {
  const std::string rule =
      "; a reader of deb's files reads plain datasets, or chunks of doubles byte-shuffled and then deflated";
  const int filters = H5Pget_nfilters(create);
  bool expected = filters == 2;
  for (int k = 0; expected && k < 2; ++k) {
    unsigned flags = 0, info = 0;
    std::size_t values = 0;
    char name[64];
    const H5Z_filter_t id = H5Pget_filter2(create, static_cast<unsigned>(k), &flags, &values, nullptr, sizeof name,
                                           name, &info);
    expected = id == (k == 0 ? H5Z_FILTER_SHUFFLE : H5Z_FILTER_DEFLATE);
  }
  if (!expected) return "is compressed or filtered in another way than deb writes" + rule;
  if (H5Tequal(type, H5T_IEEE_F64LE) <= 0) return "is compressed but does not hold little-endian doubles" + rule;
  if (H5Pget_layout(create) != H5D_CHUNKED) return "is filtered but not chunked; is the file damaged?";
  chunk->assign(dims.size(), 0);
  if (H5Pget_chunk(create, static_cast<int>(dims.size()), chunk->data()) != static_cast<int>(dims.size()))
    return "has an unreadable chunk shape; is the file damaged?";
  hsize_t values = 1;
  for (std::size_t d = 0; d < dims.size(); ++d) {
    if ((*chunk)[d] == 0 || (*chunk)[d] > std::max<hsize_t>(dims[d], 1))
      return "has chunks of " + std::to_string((*chunk)[d]) + " along a dimension of " + std::to_string(dims[d]);
    values *= (*chunk)[d];
  }
  if (values > kMaxChunkValues)
    return "has chunks of " + std::to_string(values) + " values, more than the " + std::to_string(kMaxChunkValues) +
           " deb reads in one";
  return "";
}

// The shape against the caller's bound, before anything is allocated: at
// most `most` elements (rank 1) or rows (rank 2) of `columns` values.
void CheckShape(const std::string& path, const std::string& object, const OpenSet& s, AtMost most,
                std::size_t columns = 0) {
  const auto fail = [&](const std::string& what) {
    throw InputError(path + ": object '" + Excerpt(object, 200) + "' " + what);
  };
  if (s.dims.empty()) return;
  if (s.dims[0] > most.count)
    fail((s.dims.size() == 1 ? "declares " + std::to_string(s.dims[0]) + " values"
                              : "declares " + std::to_string(s.dims[0]) + " rows") +
         ", more than the " + std::to_string(most.count) + " it may hold");
  if (s.dims.size() == 2 && s.dims[0] > 0 && s.dims[1] != columns)
    fail("has rows of " + std::to_string(s.dims[1]) + " values, not " + std::to_string(columns));
}

OpenSet Open(Hdf5Reader::Handle& h, const std::string& path, const std::string& object, Kind kind, int rank,
             AtMost most = AtMost(1), std::size_t columns = 0) {
  const auto fail = [&](const std::string& what) {
    throw InputError(path + ": object '" + Excerpt(object, 200) + "' " + what);
  };
  OpenSet s;
  s.transfer = h.transfer;
  if (!Reach(h, path, object)) fail("is missing");
  s.set = std::make_unique<Id>(H5Dopen2(h.file, object.c_str(), H5P_DEFAULT), H5Dclose);
  if (!s.set->ok()) fail("is not a dataset");
  const Id create(H5Dget_create_plist(s.set->get()), H5Pclose);
  const bool numbers = kind == Kind::kDouble && rank > 0;
  if (const std::string problem = StorageProblem(create.get(), numbers); !problem.empty()) fail(problem);
  const Id type(H5Dget_type(s.set->get()), H5Tclose);
  const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  const bool variable = cls == H5T_STRING && H5Tis_variable_str(type.get()) > 0;
  const bool right = kind == Kind::kDouble    ? cls == H5T_FLOAT || cls == H5T_INTEGER
                     : kind == Kind::kInteger ? cls == H5T_INTEGER
                                              : variable;
  if (!right)
    fail(std::string("holds ") +
         (cls == H5T_STRING ? (variable ? "text" : "text of a fixed length")
                            : cls == H5T_FLOAT ? "numbers" : "another class") +
         ", not " + KindName(kind) + (kind == Kind::kText ? " (variable-length strings)" : ""));
  const Id space(H5Dget_space(s.set->get()), H5Sclose);
  const int ndims = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (ndims != rank)
    fail("has " + std::to_string(ndims) + " dimensions, not " + std::to_string(rank));
  s.dims.assign(static_cast<std::size_t>(rank), 0);
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), s.dims.data(), nullptr) != rank)
    fail("has an unreadable shape");
  for (hsize_t d : s.dims) {
    if (d > kMaxHdf5Elements || (d > 0 && s.elements > kMaxHdf5Elements / d))
      fail("has more than " + std::to_string(kMaxHdf5Elements) + " elements");
    s.elements *= static_cast<std::size_t>(d);
  }
  CheckShape(path, object, s, most, columns);
  if (numbers && H5Pget_nfilters(create.get()) > 0) {
    if (const std::string problem = CompressionProblem(create.get(), type.get(), s.dims, &s.chunk); !problem.empty())
      fail(problem);
    return s;  // ReadCompressed checks that every chunk is in the file
  }
  // Every value declared is in the file: HDF5 fills a dataset whose values
  // were never written, so a small file could declare any size (deb writes
  // every value it declares).
  const std::size_t value_bytes = H5Tget_size(type.get());
  const hsize_t stored = s.elements > 0 ? H5Dget_storage_size(s.set->get()) : 0;
  if (s.elements > 0 && (value_bytes == 0 || stored / value_bytes < s.elements))
    fail("declares " + std::to_string(s.elements) + " values, but the file holds " +
         std::to_string(value_bytes ? stored / value_bytes : 0) + " of them; is it damaged?");
  return s;
}

// The values of a compressed dataset of doubles (CompressionProblem) into
// `out` (s.elements), chunk by chunk without HDF5's filters: each chunk's
// bytes are read as stored and inflated into exactly the chunk's size (a
// chunk that would expand further is refused, where HDF5's own filter
// grows its buffer without bound), then unshuffled; every chunk of the
// dataset must be in the file, once.
void ReadCompressed(const std::string& path, const std::string& object, const OpenSet& s, double* out) {
  const auto fail = [&](const std::string& what) {
    throw InputError(path + ": object '" + Excerpt(object, 200) + "' " + what);
  };
  const std::size_t rank = s.dims.size();
  std::vector<hsize_t> grid(rank);
  std::size_t chunks = 1, chunk_values = 1;
  for (std::size_t d = 0; d < rank; ++d) {
    grid[d] = (s.dims[d] + s.chunk[d] - 1) / s.chunk[d];
    chunks *= static_cast<std::size_t>(grid[d]);
    chunk_values *= static_cast<std::size_t>(s.chunk[d]);
  }
  const std::size_t chunk_bytes = chunk_values * sizeof(double);
  const Id space(H5Dget_space(s.set->get()), H5Sclose);
  hsize_t stored = 0;
  if (!space.ok() || H5Dget_num_chunks(s.set->get(), space.get(), &stored) < 0)
    fail("has an unreadable chunk index; is the file damaged?");
  if (stored != chunks)
    fail("holds " + std::to_string(stored) + " of its " + std::to_string(chunks) + " chunks; is it damaged?");
  std::vector<bool> seen(chunks, false);
  std::vector<unsigned char> packed, shuffled(chunk_bytes), values(chunk_bytes);
  for (hsize_t i = 0; i < stored; ++i) {
    hsize_t offset[2] = {0, 0}, size = 0;
    unsigned mask = 0;
    haddr_t address = 0;
    if (H5Dget_chunk_info(s.set->get(), space.get(), i, offset, &mask, &address, &size) < 0)
      fail("has an unreadable chunk; is the file damaged?");
    if (mask != 0) fail("has a chunk stored without its filters");
    std::size_t index = 0;
    for (std::size_t d = 0; d < rank; ++d) {
      if (offset[d] % s.chunk[d] != 0 || offset[d] >= s.dims[d]) fail("has a chunk outside its shape");
      index = index * static_cast<std::size_t>(grid[d]) + static_cast<std::size_t>(offset[d] / s.chunk[d]);
    }
    if (seen[index]) fail("holds a chunk twice; is the file damaged?");
    seen[index] = true;
    if (size == 0 || size > compressBound(static_cast<uLong>(chunk_bytes)))
      fail("has a chunk of " + std::to_string(size) + " bytes, more than a deflated chunk of " +
           std::to_string(chunk_bytes) + " bytes can take");
    packed.resize(static_cast<std::size_t>(size));
    std::uint32_t filters = 0;
    if (H5Dread_chunk(s.set->get(), s.transfer, offset, &filters, packed.data()) < 0 || filters != 0)
      fail("has a chunk that cannot be read (a damaged file?)");
    uLongf inflated = static_cast<uLongf>(chunk_bytes);
    if (uncompress(shuffled.data(), &inflated, packed.data(), static_cast<uLong>(size)) != Z_OK ||
        inflated != chunk_bytes)
      fail("has a chunk that does not inflate to its " + std::to_string(chunk_bytes) + " bytes");
    // HDF5's shuffle stores byte k of every value together, k = 0..7.
    for (std::size_t v = 0; v < chunk_values; ++v)
      for (std::size_t k = 0; k < sizeof(double); ++k) values[v * sizeof(double) + k] = shuffled[k * chunk_values + v];
    if (H5Tconvert(H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, chunk_values, values.data(), nullptr, H5P_DEFAULT) < 0)
      fail("cannot be converted to this machine's doubles");
    // The part of the chunk inside the dataset, row by row.
    const std::size_t columns = rank == 2 ? static_cast<std::size_t>(s.dims[1]) : 0;
    const std::size_t chunk_rows = rank == 2 ? static_cast<std::size_t>(s.chunk[0]) : 1;
    const std::size_t chunk_columns = static_cast<std::size_t>(s.chunk[rank - 1]);
    const std::size_t rows = std::min<std::size_t>(chunk_rows, rank == 2 ? s.dims[0] - offset[0] : 1);
    const std::size_t take = std::min<std::size_t>(chunk_columns, s.dims[rank - 1] - offset[rank - 1]);
    for (std::size_t r = 0; r < rows; ++r) {
      const std::size_t to = rank == 2 ? (offset[0] + r) * columns + offset[1] : offset[0];
      std::memcpy(out + to, values.data() + r * chunk_columns * sizeof(double), take * sizeof(double));
    }
  }
}

void Read(const std::string& path, const std::string& object, const OpenSet& s, hid_t memory_type, void* data) {
  if (s.elements == 0) return;
  if (!s.chunk.empty()) {
    DEB_DEMAND(memory_type == H5T_NATIVE_DOUBLE);
    ReadCompressed(path, object, s, static_cast<double*>(data));
    return;
  }
  if (H5Dread(s.set->get(), memory_type, H5S_ALL, H5S_ALL, s.transfer, data) < 0)
    throw InputError(path + ": object '" + Excerpt(object, 200) + "' cannot be read (a damaged file?)");
}

void CheckFinite(const std::string& path, const std::string& object, const std::vector<double>& v, bool allow_nan) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) && !(allow_nan && std::isnan(v[i])))
      throw InputError(path + ": object '" + Excerpt(object, 200) + "' holds a value that is not finite at element " +
                       std::to_string(i));
}

// The objects of the global heap collection at `address` (HDF5 file format,
// "Global Heap"): index -> size, if the collection lies whole inside the
// file and its objects inside it, laid out as libhdf5 walks them; else
// nullptr. libhdf5 1.10 walks a collection without bounds and copies an
// object's stored size into a buffer sized from the reference: a damaged
// file made it read and write out of bounds (SIGSEGV).
const std::map<std::uint64_t, std::uint64_t>* HeapCollection(Hdf5Reader::Handle& h, std::uint64_t address) {
  const auto known = h.heaps.find(address);
  if (known != h.heaps.end()) return &known->second;
  const std::size_t length = h.length_bytes;
  const auto align = [](std::uint64_t n) { return (n + 7) / 8 * 8; };
  const std::uint64_t header = align(8 + length), object_header = 8 + length;
  if (!h.raw->Holds(h.base, address, 0)) return nullptr;
  const std::uint64_t at = h.base + address;
  unsigned char head[16];
  if (!h.raw->Read(at, 8 + length, head) || std::memcmp(head, "GCOL", 4) != 0 || head[4] != 1) return nullptr;
  const std::uint64_t size = Little(head + 8, length);
  if (size < header || size > h.raw->size() - at) return nullptr;
  std::vector<unsigned char> heap(static_cast<std::size_t>(size));
  if (!h.raw->Read(at, size, heap.data())) return nullptr;
  std::map<std::uint64_t, std::uint64_t> objects;
  std::uint64_t p = header;
  while (p < size) {
    if (p + object_header > size) break;  // too small for an object: free space to the end
    const unsigned char* o = heap.data() + p;
    const std::uint64_t index = Little(o, 2), bytes = Little(o + 8, length);
    // Object 0 is the free space, its size counting its header.
    const std::uint64_t need = index > 0 ? (bytes > size ? size + 1 : object_header + align(bytes)) : bytes;
    if (need == 0 || need > size - p) return nullptr;
    if (index > 0) objects[index] = bytes;
    p += need;
  }
  return &h.heaps.emplace(address, std::move(objects)).first->second;
}

// Checks the references of a dataset of variable-length text (`s`) before
// libhdf5 reads them: each is empty, or names an object of a whole heap
// collection (HeapCollection) of exactly the length it gives.
void CheckVariableText(Hdf5Reader::Handle& h, const std::string& path, const std::string& object, const OpenSet& s) {
  const auto fail = [&](const std::string& what) {
    throw InputError(path + ": object '" + Excerpt(object, 200) + "' " + what);
  };
  if (s.elements == 0) return;
  const Id create(H5Dget_create_plist(s.set->get()), H5Pclose);
  if (H5Pget_layout(create.get()) != H5D_CONTIGUOUS)
    fail("holds text in another layout than deb writes (contiguous)");
  const haddr_t offset = H5Dget_offset(s.set->get());
  if (offset == HADDR_UNDEF) return;  // nothing written: read as null strings
  // Each element: its length (4 bytes), the address of its heap collection
  // and its index there (4 bytes).
  const std::size_t each = 8 + h.address_bytes;
  if (s.elements > (h.raw->size() + each - 1) / each) fail("is damaged: its texts run past the end of the file");
  std::vector<unsigned char> refs(s.elements * each);
  if (!h.raw->Holds(h.base, offset, 0) || !h.raw->Read(h.base + offset, refs.size(), refs.data()))
    fail("is damaged: its texts run past the end of the file");
  for (std::size_t i = 0; i < s.elements; ++i) {
    const unsigned char* r = refs.data() + i * each;
    const std::uint64_t length = Little(r, 4), heap = Little(r + 4, h.address_bytes),
                        index = Little(r + 4 + h.address_bytes, 4);
    if (heap == 0) continue;  // a null string
    const auto* objects = HeapCollection(h, heap);
    const auto found = objects ? objects->find(index) : decltype(objects->end()){};
    if (objects == nullptr || found == objects->end() || found->second != length)
      fail("is damaged: text " + std::to_string(i) + " points to no whole entry of the file's global heap");
  }
}

std::vector<std::string> ReadTexts(Hdf5Reader::Handle& h, const std::string& path, const std::string& object,
                                   int rank, AtMost most) {
  const OpenSet s = Open(h, path, object, Kind::kText, rank, most);
  CheckVariableText(h, path, object, s);
  const Id type = VariableString();
  std::vector<char*> raw(s.elements, nullptr);
  Read(path, object, s, type.get(), raw.data());
  std::vector<std::string> texts;
  bool null = false;
  for (char* t : raw) {
    null |= t == nullptr;
    texts.emplace_back(t ? t : "");
  }
  if (s.elements > 0) {
    const Id space(H5Dget_space(s.set->get()), H5Sclose);
#if H5_VERSION_GE(1, 12, 0)
    H5Treclaim(type.get(), space.get(), s.transfer, raw.data());
#else
    H5Dvlen_reclaim(type.get(), space.get(), s.transfer, raw.data());
#endif
  }
  if (null) throw InputError(path + ": object '" + Excerpt(object, 200) + "' holds a null string");
  for (const std::string& t : texts)
    if (const std::string problem = Utf8Problem(t); !problem.empty())
      throw InputError(path + ": object '" + Excerpt(object, 200) + "' holds text where " + problem);
  return texts;
}

}  // namespace

bool Hdf5Reader::Has(const std::string& object) const {
  const Locked lock;
  return Reach(*handle_, path_, object);
}

double Hdf5Reader::Number(const std::string& object, bool allow_nan) const {
  const Locked lock;
  const OpenSet s = Open(*handle_, path_, object, Kind::kDouble, 0);
  std::vector<double> v(1);
  Read(path_, object, s, H5T_NATIVE_DOUBLE, v.data());
  CheckFinite(path_, object, v, allow_nan);
  return v[0];
}

std::int64_t Hdf5Reader::Integer(const std::string& object) const {
  const Locked lock;
  const OpenSet s = Open(*handle_, path_, object, Kind::kInteger, 0);
  long long v = 0;
  Read(path_, object, s, H5T_NATIVE_LLONG, &v);
  return v;
}

std::string Hdf5Reader::Text(const std::string& object) const {
  const Locked lock;
  return ReadTexts(*handle_, path_, object, 0, AtMost(1)).front();
}

std::vector<double> Hdf5Reader::Numbers(const std::string& object, AtMost most, bool allow_nan) const {
  const Locked lock;
  const OpenSet s = Open(*handle_, path_, object, Kind::kDouble, 1, most);
  std::vector<double> v(s.elements);
  Read(path_, object, s, H5T_NATIVE_DOUBLE, v.data());
  CheckFinite(path_, object, v, allow_nan);
  return v;
}

std::vector<std::string> Hdf5Reader::Texts(const std::string& object, AtMost most) const {
  const Locked lock;
  return ReadTexts(*handle_, path_, object, 1, most);
}

std::vector<std::vector<double>> Hdf5Reader::Rows(const std::string& object, AtMost most, std::size_t columns,
                                                  bool allow_nan) const {
  const Locked lock;
  const OpenSet s = Open(*handle_, path_, object, Kind::kDouble, 2, most, columns);
  std::vector<double> v(s.elements);
  Read(path_, object, s, H5T_NATIVE_DOUBLE, v.data());
  CheckFinite(path_, object, v, allow_nan);
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(s.dims[0]));
  for (std::size_t r = 0; r < rows.size(); ++r)
    rows[r].assign(v.begin() + static_cast<std::ptrdiff_t>(r * columns),
                   v.begin() + static_cast<std::ptrdiff_t>((r + 1) * columns));
  return rows;
}

// ---------------------------------------------------------------- a whole file

void RequireSelfContainedHdf5(const std::string& path) {
  const Locked lock;
  if (const std::string why = StartFailure(); !why.empty()) throw InputError(path + ": reading it needs " + why);
  const Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw InputError(path + ": not an HDF5 file, or a damaged one");
  const auto fail = [&](const std::string& object, const std::string& what) {
    throw InputError(path + ": object '" + Excerpt(object, 200) + "' " + what);
  };
  std::uint64_t base = 0;
  std::size_t address_bytes = 8, length_bytes = 8;
  ReadLayout(path, file.get(), base, address_bytes, length_bytes);
  RawFile raw(path);
  // The objects still to look at: their addresses, and a name for messages.
  std::vector<std::pair<haddr_t, std::string>> pending;
  std::set<haddr_t> seen;
  {
    H5O_info_t root;
    const Id g(H5Oopen(file.get(), "/", H5P_DEFAULT), H5Oclose);
    if (!g.ok() || H5Oget_info2(g.get(), &root, H5O_INFO_BASIC) < 0) fail("/", "cannot be read; is the file damaged?");
    pending.emplace_back(root.addr, "/");
  }
  struct Links {
    std::vector<std::pair<haddr_t, std::string>> hard;
    std::string other;  // the first link of another kind
    H5L_type_t other_type = H5L_TYPE_HARD;
  };
  const H5L_iterate_t collect = [](hid_t, const char* name, const H5L_info_t* info, void* data) -> herr_t {
    Links& links = *static_cast<Links*>(data);
    if (info->type != H5L_TYPE_HARD) {
      links.other = name;
      links.other_type = info->type;
      return 1;
    }
    links.hard.emplace_back(info->u.address, name);
    return links.hard.size() > kMaxHdf5Objects ? 1 : 0;
  };
  while (!pending.empty()) {
    const auto [address, name] = pending.back();
    pending.pop_back();
    if (!seen.insert(address).second) continue;
    if (seen.size() > kMaxHdf5Objects)
      throw InputError(path + ": more than " + std::to_string(kMaxHdf5Objects) + " objects; is the file damaged?");
    if (const std::string problem = ObjectHeaderProblem(raw, base, address_bytes, length_bytes, address);
        !problem.empty())
      fail(name, problem);
    const Id object(H5Oopen_by_addr(file.get(), address), H5Oclose);
    H5O_info_t info;
    if (!object.ok() || H5Oget_info2(object.get(), &info, H5O_INFO_BASIC) < 0)
      fail(name, "cannot be read; is the file damaged?");
    const std::string prefix = name == "/" ? "" : name + "/";
    if (info.type == H5O_TYPE_GROUP) {
      Links links;
      if (H5Literate(object.get(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect, &links) < 0)
        fail(name, "cannot be listed; is the file damaged?");
      if (!links.other.empty())
        fail(prefix + links.other,
             "is " + LinkKind(links.other_type) + "; deb reads only objects the file holds itself, reached by plain "
                                                  "(hard) links");
      if (links.hard.size() > kMaxHdf5Objects)
        throw InputError(path + ": more than " + std::to_string(kMaxHdf5Objects) + " objects; is the file damaged?");
      for (const auto& [child, child_name] : links.hard) pending.emplace_back(child, prefix + child_name);
      continue;
    }
    if (info.type != H5O_TYPE_DATASET) continue;
    {
      const Id create(H5Dget_create_plist(object.get()), H5Pclose);
      if (const std::string problem = StorageProblem(create.get(), true); !problem.empty()) fail(name, problem);
    }
    const Id type(H5Dget_type(object.get()), H5Tclose);
    // A value of a MAT-file is at most 16 bytes (a complex double); matio
    // allocates count x size before it reads (a fuzzed file's datatype of
    // 4294966792 bytes had it ask for 4 GB).
    if (type.ok()) {
      const std::size_t value_bytes = H5Tget_size(type.get());
      if (value_bytes == 0 || value_bytes > 16)
        fail(name, "stores values of " + std::to_string(value_bytes) +
                       " bytes each; the values of a MAT-file are 1 to 16 bytes");
    }
    // Object references (matio's cell arrays and structs in cells) lead to
    // objects that no link may name.
    if (!type.ok() || H5Tget_class(type.get()) != H5T_REFERENCE) continue;
    if (H5Tequal(type.get(), H5T_STD_REF_OBJ) <= 0) fail(name, "holds references of another kind than objects");
    const Id space(H5Dget_space(object.get()), H5Sclose);
    const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0 || rank > 32) fail(name, "has an unreadable shape");
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    std::size_t count = 1;
    if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) != rank)
      fail(name, "has an unreadable shape");
    for (hsize_t d : dims) {
      if (d > kMaxHdf5Objects || (d > 0 && count > kMaxHdf5Objects / d))
        fail(name, "holds more than " + std::to_string(kMaxHdf5Objects) + " references");
      count *= static_cast<std::size_t>(d);
    }
    if (count == 0) continue;
    std::vector<hobj_ref_t> references(count);
    if (H5Dread(object.get(), H5T_STD_REF_OBJ, H5S_ALL, H5S_ALL, H5P_DEFAULT, references.data()) < 0)
      fail(name, "cannot be read; is the file damaged?");
    for (std::size_t i = 0; i < count; ++i)
      if (references[i] != 0) pending.emplace_back(references[i], name + "[" + std::to_string(i) + "]");
  }
}

}  // namespace deb::formats
