#include "deb/io/hdf5_file.h"

#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <map>
#include <mutex>

#include "deb/core/error.h"
#include "deb/core/shared_library.h"
#include "deb/core/input_file.h"

namespace deb::io {
namespace {

// The HDF5 C library is not linked: it is loaded when the first file is
// opened. With its dependencies (curl, TLS, Kerberos, ...) it costs about
// 6 ms at every start of deb, store or not. DEB_HDF5_SONAME is the library
// the build found. Only the functions and predefined types below are used.
#define DEB_HDF5_FUNCTIONS(X)                                                                                     \
  X(H5open) X(H5Eset_auto2) X(H5Fcreate) X(H5Fopen) X(H5Fclose) X(H5Gcreate2) X(H5Gopen2) X(H5Gclose) X(H5Lexists) \
      X(H5Screate) X(H5Screate_simple) X(H5Sclose) X(H5Sget_simple_extent_ndims) X(H5Sget_simple_extent_dims)      \
          X(H5Dcreate2) X(H5Dopen2) X(H5Dclose) X(H5Dwrite) X(H5Dread) X(H5Dget_space) X(H5Dget_type)              \
              X(H5Dvlen_reclaim) X(H5Tcopy) X(H5Tset_size) X(H5Tset_cset) X(H5Tclose) X(H5Tget_class)            \
                  X(H5Tis_variable_str) X(H5Pcreate) X(H5Pclose) X(H5Pset_obj_track_times) X(H5Pset_buffer) X(H5Pset_libver_bounds) X(H5Dget_create_plist) X(H5Pget_nfilters)

struct Hdf5Api {
#define DEB_HDF5_POINTER(f) decltype(&::f) f = nullptr;
  DEB_HDF5_FUNCTIONS(DEB_HDF5_POINTER)
#undef DEB_HDF5_POINTER
  // The predefined types, valid after H5open.
  const hid_t* native_double = nullptr;
  const hid_t* native_int64 = nullptr;
  const hid_t* file_double = nullptr;
  const hid_t* file_int64 = nullptr;
  const hid_t* c_string = nullptr;
  // The property-list classes of dataset and group creation.
  const hid_t* dataset_create = nullptr;
  const hid_t* group_create = nullptr;
  const hid_t* dataset_transfer_class = nullptr;
  const hid_t* file_access_class = nullptr;
  const hid_t* file_create_class = nullptr;
};

struct LoadedHdf5 {
  Hdf5Api api;
  std::string failure;  // why HDF5 could not be loaded; "" if it was
};

LoadedHdf5 LoadHdf5() {
  LoadedHdf5 l;
  SharedLibrary library(DEB_HDF5_SONAME);
  Hdf5Api& a = l.api;
#define DEB_HDF5_RESOLVE(f) library.Resolve(#f, a.f);
  DEB_HDF5_FUNCTIONS(DEB_HDF5_RESOLVE)
#undef DEB_HDF5_RESOLVE
  // The predefined types and classes are variables the library sets in
  // H5open (SharedLibrary::ResolveVariable: a program linked with HDF5 that
  // refers to H5T_NATIVE_DOUBLE holds the copy the library sets).
  library.ResolveVariable("H5T_NATIVE_DOUBLE_g", a.native_double);
  library.ResolveVariable("H5T_NATIVE_LLONG_g", a.native_int64);
  library.ResolveVariable("H5T_IEEE_F64LE_g", a.file_double);
  library.ResolveVariable("H5T_STD_I64LE_g", a.file_int64);
  library.ResolveVariable("H5T_C_S1_g", a.c_string);
  library.ResolveVariable("H5P_CLS_DATASET_CREATE_ID_g", a.dataset_create);
  library.ResolveVariable("H5P_CLS_GROUP_CREATE_ID_g", a.group_create);
  library.ResolveVariable("H5P_CLS_DATASET_XFER_ID_g", a.dataset_transfer_class);
  library.ResolveVariable("H5P_CLS_FILE_ACCESS_ID_g", a.file_access_class);
  library.ResolveVariable("H5P_CLS_FILE_CREATE_ID_g", a.file_create_class);
  l.failure = library.failure();
  if (l.failure.empty() && a.H5open() < 0) l.failure = "H5open failed";
  // HDF5 prints its error stack on stderr by default: deb reports errors itself.
  if (l.failure.empty()) a.H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (!l.failure.empty()) l.api = Hdf5Api{};
  return l;
}

const LoadedHdf5& Loaded() {
  static const LoadedHdf5 loaded = LoadHdf5();
  return loaded;
}

const Hdf5Api& Api() { return Loaded().api; }

// H5F_ACC_TRUNC and H5F_ACC_RDONLY are macros that call H5check and H5open,
// which would link the library: their values (H5Fpublic.h) instead.
constexpr unsigned kCreateTruncate = 0x0002u;
constexpr unsigned kReadOnly = 0x0000u;

// The HDF5 library deb loads is built without thread safety: every call
// holds this lock.
std::mutex g_hdf5;

// The failure text if HDF5 cannot be loaded, for messages; "" if it can.
std::string LoadFailure() {
  const LoadedHdf5& l = Loaded();
  return l.failure.empty() ? ""
                           : "HDF5 (" DEB_HDF5_SONAME ") cannot be loaded: " + Excerpt(l.failure, 160) +
                                 "; install it (Debian: libhdf5-103-1)";
}

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
  const Hdf5Api& a = Api();
  const hid_t t = a.H5Pcreate(*a.dataset_transfer_class);
  if (t >= 0 && a.H5Pset_buffer(t, std::size_t{64} << 10, nullptr, nullptr) < 0) {
    a.H5Pclose(t);
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
  const Hdf5Api& a = Api();
  Id type(a.H5Tcopy(*a.c_string), a.H5Tclose);
  if (type.ok()) {
    a.H5Tset_size(type.get(), H5T_VARIABLE);
    a.H5Tset_cset(type.get(), H5T_CSET_UTF8);
  }
  return type;
}

}  // namespace

void PreloadHdf5() { Loaded(); }

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
    const Hdf5Api& a = Api();
    for (const auto& g : groups) a.H5Gclose(g.second);
    groups.clear();
    for (hid_t* p : {&dataset_create, &group_create, &transfer})
      if (*p >= 0) a.H5Pclose(*p), *p = -1;
  }
};

Hdf5Writer::Hdf5Writer(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  if (const std::string why = LoadFailure(); !why.empty()) throw WriteError("cannot write " + path + ": " + why);
  const Hdf5Api& a = Api();
  // The file format of HDF5 1.8 (2008) and later, which any current reader
  // (h5py, MATLAB, HDFView) reads: its groups keep their few links in the
  // group's header instead of a B-tree and a heap, which makes a store of
  // thousands of small objects faster to write and read, and smaller.
  // The root group, like every object below, without modification times.
  const Id access(a.H5Pcreate(*a.file_access_class), a.H5Pclose), create(a.H5Pcreate(*a.file_create_class), a.H5Pclose);
  if (!access.ok() || !create.ok() || a.H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_V18) < 0 ||
      a.H5Pset_obj_track_times(create.get(), 0) < 0)
    throw WriteError("cannot set up the HDF5 file " + path);
  handle_->file = a.H5Fcreate(path.c_str(), kCreateTruncate, create.get(), access.get());
  if (handle_->file < 0) throw WriteError("cannot create the HDF5 file " + path);
  handle_->transfer = NewTransfer();
  handle_->dataset_create = a.H5Pcreate(*a.dataset_create);
  handle_->group_create = a.H5Pcreate(*a.group_create);
  if (handle_->dataset_create < 0 || handle_->group_create < 0 || handle_->transfer < 0 ||
      a.H5Pset_obj_track_times(handle_->dataset_create, 0) < 0 ||
      a.H5Pset_obj_track_times(handle_->group_create, 0) < 0)
    throw WriteError("cannot set up the HDF5 file " + path);
}

Hdf5Writer::~Hdf5Writer() {
  if (handle_ && (handle_->file >= 0 || handle_->dataset_create >= 0)) {
    const std::lock_guard<std::mutex> lock(g_hdf5);
    handle_->CloseAll();
    if (handle_->file >= 0) Api().H5Fclose(handle_->file);
  }
}

void Hdf5Writer::Close() {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  handle_->CloseAll();
  const hid_t file = handle_->file;
  handle_->file = -1;
  if (file >= 0 && Api().H5Fclose(file) < 0) throw WriteError("cannot complete the HDF5 file " + path_);
}

namespace {

// Writes one dataset of `type_in_file` and `dims` (empty: a scalar) from
// `data` in `type_in_memory` under `file`, creating the groups above it.
void WriteDataset(Hdf5Writer::Handle& h, const std::string& path, const std::string& object, hid_t type_in_file,
                  hid_t type_in_memory, const std::vector<hsize_t>& dims, const void* data) {
  const Hdf5Api& a = Api();
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
    const htri_t exists = a.H5Lexists(at, parts[i].c_str(), H5P_DEFAULT);
    const hid_t g = exists > 0 ? a.H5Gopen2(at, parts[i].c_str(), H5P_DEFAULT)
                               : a.H5Gcreate2(at, parts[i].c_str(), H5P_DEFAULT, h.group_create, H5P_DEFAULT);
    if (g < 0) fail("cannot create or open the group '" + parts[i] + "'");
    h.groups.emplace(group_path, g);
    at = g;
  }

  Id space(dims.empty() ? a.H5Screate(H5S_SCALAR)
                        : a.H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
           a.H5Sclose);
  if (!space.ok()) fail("cannot make its dataspace");
  Id set(a.H5Dcreate2(at, parts.back().c_str(), type_in_file, space.get(), H5P_DEFAULT, h.dataset_create, H5P_DEFAULT),
         a.H5Dclose);
  if (!set.ok())
    fail(a.H5Lexists(at, parts.back().c_str(), H5P_DEFAULT) > 0 ? "it exists already" : "cannot create the dataset");
  bool empty = false;
  for (hsize_t d : dims) empty |= d == 0;
  if (!empty && a.H5Dwrite(set.get(), type_in_memory, H5S_ALL, H5S_ALL, h.transfer, data) < 0)
    fail("cannot write its data");
}

}  // namespace

void Hdf5Writer::Number(const std::string& object, double value) {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  WriteDataset(*handle_, path_, object, *Api().file_double, *Api().native_double, {}, &value);
}

void Hdf5Writer::Integer(const std::string& object, std::int64_t value) {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const long long v = value;
  WriteDataset(*handle_, path_, object, *Api().file_int64, *Api().native_int64, {}, &v);
}

void Hdf5Writer::Text(const std::string& object, const std::string& value) {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const Id type = VariableString();
  const char* text = value.c_str();
  WriteDataset(*handle_, path_, object, type.get(), type.get(), {}, &text);
}

void Hdf5Writer::Numbers(const std::string& object, const std::vector<double>& values) {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  WriteDataset(*handle_, path_, object, *Api().file_double, *Api().native_double, {values.size()},
               values.data());
}

void Hdf5Writer::Texts(const std::string& object, const std::vector<std::string>& values) {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const Id type = VariableString();
  std::vector<const char*> texts;
  for (const std::string& v : values) texts.push_back(v.c_str());
  WriteDataset(*handle_, path_, object, type.get(), type.get(), {values.size()}, texts.data());
}

void Hdf5Writer::Rows(const std::string& object, const std::vector<std::vector<double>>& rows) {
  const std::size_t columns = rows.empty() ? 0 : rows.front().size();
  std::vector<double> data;
  data.reserve(rows.size() * columns);
  for (const std::vector<double>& r : rows) {
    DEB_DEMAND(r.size() == columns);
    data.insert(data.end(), r.begin(), r.end());
  }
  const std::lock_guard<std::mutex> lock(g_hdf5);
  WriteDataset(*handle_, path_, object, *Api().file_double, *Api().native_double,
               {rows.size(), rows.empty() ? 0 : columns}, data.data());
}

// ---------------------------------------------------------------- reading

struct Hdf5Reader::Handle {
  hid_t file = -1;
  hid_t transfer = -1;  // NewTransfer
};

Hdf5Reader::Hdf5Reader(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  RequireInputFile(path, "HDF5 file", kMaxHdf5FileBytes);
  const std::lock_guard<std::mutex> lock(g_hdf5);
  if (const std::string why = LoadFailure(); !why.empty()) throw InputError(path + ": reading it needs " + why);
  handle_->file = Api().H5Fopen(path.c_str(), kReadOnly, H5P_DEFAULT);
  if (handle_->file < 0) throw InputError(path + ": not an HDF5 file, or a damaged one");
  handle_->transfer = NewTransfer();
  if (handle_->transfer < 0) throw InputError(path + ": cannot set up reading it (HDF5)");
}

Hdf5Reader::~Hdf5Reader() {
  if (handle_ && handle_->file >= 0) {
    const std::lock_guard<std::mutex> lock(g_hdf5);
    if (handle_->transfer >= 0) Api().H5Pclose(handle_->transfer);
    Api().H5Fclose(handle_->file);
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
};

bool Exists(hid_t file, const std::string& object) {
  const Hdf5Api& a = Api();
  std::string prefix;
  for (const std::string& part : Split(object)) {
    prefix += (prefix.empty() ? "" : "/") + part;
    if (a.H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return !prefix.empty();
}

OpenSet Open(hid_t file, hid_t transfer, const std::string& path, const std::string& object, Kind kind, int rank) {
  const Hdf5Api& a = Api();
  const auto fail = [&](const std::string& what) { throw InputError(path + ": object '" + object + "' " + what); };
  OpenSet s;
  s.transfer = transfer;
  // Opened straight away (a store reads thousands of objects); only a
  // failure asks why.
  s.set = std::make_unique<Id>(a.H5Dopen2(file, object.c_str(), H5P_DEFAULT), a.H5Dclose);
  if (!s.set->ok()) fail(Exists(file, object) ? "is not a dataset" : "is missing");
  const Id type(a.H5Dget_type(s.set->get()), a.H5Tclose);
  const H5T_class_t cls = type.ok() ? a.H5Tget_class(type.get()) : H5T_NO_CLASS;
  const bool right = kind == Kind::kDouble    ? cls == H5T_FLOAT || cls == H5T_INTEGER
                     : kind == Kind::kInteger ? cls == H5T_INTEGER
                                              : cls == H5T_STRING && a.H5Tis_variable_str(type.get()) > 0;
  if (!right)
    fail(std::string("holds ") + (cls == H5T_STRING ? "text" : cls == H5T_FLOAT ? "numbers" : "another class") +
         ", not " + KindName(kind) + (kind == Kind::kText ? " (variable-length strings)" : ""));
  const Id space(a.H5Dget_space(s.set->get()), a.H5Sclose);
  const int ndims = space.ok() ? a.H5Sget_simple_extent_ndims(space.get()) : -1;
  if (ndims != rank)
    fail("has " + std::to_string(ndims) + " dimensions, not " + std::to_string(rank));
  s.dims.assign(static_cast<std::size_t>(rank), 0);
  if (rank > 0 && a.H5Sget_simple_extent_dims(space.get(), s.dims.data(), nullptr) != rank)
    fail("has an unreadable shape");
  for (hsize_t d : s.dims) {
    if (d > kMaxHdf5Elements || (d > 0 && s.elements > kMaxHdf5Elements / d))
      fail("has more than " + std::to_string(kMaxHdf5Elements) + " elements");
    s.elements *= static_cast<std::size_t>(d);
  }
  // A compressed dataset could expand a small file into any size: what is
  // read is bounded by the file's size only if nothing is compressed (deb
  // compresses nothing).
  const Id create(a.H5Dget_create_plist(s.set->get()), a.H5Pclose);
  if (!create.ok() || a.H5Pget_nfilters(create.get()) != 0)
    fail("is compressed or filtered; a reader of deb's files reads plain datasets only");
  return s;
}

void Read(const std::string& path, const std::string& object, const OpenSet& s, hid_t memory_type, void* data) {
  if (s.elements == 0) return;
  if (Api().H5Dread(s.set->get(), memory_type, H5S_ALL, H5S_ALL, s.transfer, data) < 0)
    throw InputError(path + ": object '" + object + "' cannot be read (a damaged file?)");
}

void CheckFinite(const std::string& path, const std::string& object, const std::vector<double>& v, bool allow_nan) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) && !(allow_nan && std::isnan(v[i])))
      throw InputError(path + ": object '" + object + "' holds a value that is not finite at element " +
                       std::to_string(i));
}

std::vector<std::string> ReadTexts(hid_t file, hid_t transfer, const std::string& path, const std::string& object,
                                   int rank) {
  const OpenSet s = Open(file, transfer, path, object, Kind::kText, rank);
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
    const Id space(Api().H5Dget_space(s.set->get()), Api().H5Sclose);
    Api().H5Dvlen_reclaim(type.get(), space.get(), s.transfer, raw.data());
  }
  if (null) throw InputError(path + ": object '" + object + "' holds a null string");
  return texts;
}

}  // namespace

bool Hdf5Reader::Has(const std::string& object) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  return Exists(handle_->file, object);
}

double Hdf5Reader::Number(const std::string& object, bool allow_nan) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const OpenSet s = Open(handle_->file, handle_->transfer, path_, object, Kind::kDouble, 0);
  std::vector<double> v(1);
  Read(path_, object, s, *Api().native_double, v.data());
  CheckFinite(path_, object, v, allow_nan);
  return v[0];
}

std::int64_t Hdf5Reader::Integer(const std::string& object) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const OpenSet s = Open(handle_->file, handle_->transfer, path_, object, Kind::kInteger, 0);
  long long v = 0;
  Read(path_, object, s, *Api().native_int64, &v);
  return v;
}

std::string Hdf5Reader::Text(const std::string& object) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  return ReadTexts(handle_->file, handle_->transfer, path_, object, 0).front();
}

std::vector<double> Hdf5Reader::Numbers(const std::string& object, bool allow_nan) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const OpenSet s = Open(handle_->file, handle_->transfer, path_, object, Kind::kDouble, 1);
  std::vector<double> v(s.elements);
  Read(path_, object, s, *Api().native_double, v.data());
  CheckFinite(path_, object, v, allow_nan);
  return v;
}

std::vector<std::string> Hdf5Reader::Texts(const std::string& object) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  return ReadTexts(handle_->file, handle_->transfer, path_, object, 1);
}

std::vector<std::vector<double>> Hdf5Reader::Rows(const std::string& object, bool allow_nan) const {
  const std::lock_guard<std::mutex> lock(g_hdf5);
  const OpenSet s = Open(handle_->file, handle_->transfer, path_, object, Kind::kDouble, 2);
  std::vector<double> v(s.elements);
  Read(path_, object, s, *Api().native_double, v.data());
  CheckFinite(path_, object, v, allow_nan);
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(s.dims[0]));
  const std::size_t columns = static_cast<std::size_t>(s.dims[1]);
  for (std::size_t r = 0; r < rows.size(); ++r)
    rows[r].assign(v.begin() + static_cast<std::ptrdiff_t>(r * columns),
                   v.begin() + static_cast<std::ptrdiff_t>((r + 1) * columns));
  return rows;
}

}  // namespace deb::io
