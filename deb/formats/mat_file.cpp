#include "deb/formats/mat_file.h"

#include <matio.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/formats/hdf5_file.h"

namespace deb::formats {
namespace {

// matio's log function and the HDF5 library under it are process-wide:
// every matio call holds HDF5's lock (LockHdf5, hdf5_file.h), which also
// starts HDF5 as deb wants it before matio first uses it.
// The first error or warning matio logged since the current MatioCall
// began. matio reports many problems (a short read, a bad inflate, an HDF5
// error) only through its log and still returns success, so the log is
// checked after every call.
std::string g_problem;

void Log(int level, char* message) {
  // Warnings too: a short read ("Unexpected end-of-file") is only a warning.
  if (level != MATIO_LOG_LEVEL_ERROR && level != MATIO_LOG_LEVEL_CRITICAL && level != MATIO_LOG_LEVEL_WARNING) return;
  if (!g_problem.empty() || message == nullptr) return;
  const std::string text(message);
  g_problem = Excerpt(text.substr(0, text.find('\n')), 160);
}

// The lock for a sequence of matio calls; problem() is what matio reported
// during them ("" if nothing).
class MatioCall {
 public:
  MatioCall() : lock_(LockHdf5()) {
    static const int installed = Mat_LogInitFunc("deb", Log);
    (void)installed;
    g_problem.clear();
  }
  const std::string& problem() const { return g_problem; }
  // " (matio: ...)" or "".
  std::string Because() const { return g_problem.empty() ? "" : " (matio: " + g_problem + ")"; }

 private:
  std::unique_lock<std::recursive_mutex> lock_;
};

struct VarFree {
  void operator()(matvar_t* v) const {
    const auto lock = LockHdf5();
    Mat_VarFree(v);
  }
};
using VarPtr = std::unique_ptr<matvar_t, VarFree>;

[[noreturn]] void Fail(const std::string& path, const std::string& message) { throw InputError(path + ": " + message); }

std::string Quoted(const std::string& name) { return "'" + Excerpt(name) + "'"; }

// ---------------------------------------------------------------------------
// The file's layout, before matio opens it.

enum class Version { k5, k73 };

std::uint32_t Read32(const unsigned char* p, bool little) {
  return little ? (std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24)
                : (std::uint32_t{p[3]} | std::uint32_t{p[2]} << 8 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[0]} << 24);
}

// The size in bytes of one value of a v5 data type (miINT8 ... miUINT64); 0 for others.
std::uintmax_t V5ValueBytes(std::uint32_t type) {
  switch (type) {
    case 1: case 2: return 1;           // miINT8, miUINT8
    case 3: case 4: return 2;           // miINT16, miUINT16
    case 5: case 6: case 7: return 4;   // miINT32, miUINT32, miSINGLE
    case 9: case 12: case 13: return 8; // miDOUBLE, miINT64, miUINT64
    default: return 0;
  }
}

// Inside an uncompressed numeric variable (`body`: its first bytes after the
// tag, `size`: all of them): array flags, dimensions, name, then the real
// part, whose data element must hold every value the dimensions ask for
// (matio reads that many, past a short element). "" if it does, or if the
// layout is not the plain one this checks.
std::string ShortData(const unsigned char* body, std::size_t have, std::uintmax_t size, bool little) {
  std::size_t at = 0;
  // Next subelement: its type, bytes and where its data starts; false past `have`.
  auto next = [&](std::uint32_t& type, std::uint32_t& bytes, std::size_t& data) {
    if (at + 8 > have) return false;
    type = Read32(body + at, little);
    if ((type >> 16) != 0) {  // small element: 4 bytes of data in the tag
      bytes = type >> 16;
      type &= 0xFFFF;
      data = at + 4;
      at += 8;
    } else {
      bytes = Read32(body + at + 4, little);
      data = at + 8;
      at += 8 + (bytes + 7) / 8 * 8;
    }
    return true;
  };
  std::uint32_t type = 0, bytes = 0;
  std::size_t data = 0;
  if (!next(type, bytes, data) || type != 6 || bytes < 8 || data + 8 > have) return "";
  const std::uint32_t class_type = Read32(body + data, little) & 0xFF;
  // The dimensions (their type is checked by MatrixHeaderProblem).
  if (!next(type, bytes, data) || type != 5) return "";
  if (class_type < 6 || class_type > 15) return "";  // not numeric (mxDOUBLE_CLASS ... mxUINT64_CLASS)
  if (data + bytes > have) return "";
  std::uintmax_t count = 1;
  for (std::uint32_t k = 0; k + 4 <= bytes; k += 4) {
    const std::uint32_t d = Read32(body + data + k, little);
    if (d != 0 && count > limits::kMaxMatElements / d) return "";  // refused by its size later
    count *= d;
  }
  if (!next(type, bytes, data)) return "";  // the name
  const std::size_t part = at;
  if (!next(type, bytes, data)) return "";  // the real part
  const std::uintmax_t value = V5ValueBytes(type);
  // matio takes a part of an unknown type for as many values as the
  // dimensions ask (a fuzzed 840-byte file: 33 million).
  if (value == 0) return "its values are stored as data type " + std::to_string(type) + ", which is no numeric type";
  if (bytes / value < count || part + 8 + bytes > size)
    return "its dimensions ask for " + std::to_string(count) + " values, its data holds " +
           std::to_string(bytes / value) + (part + 8 + bytes > size ? " and runs past the variable's end" : "");
  return "";
}

// Reads the 8-byte tag at byte `at` of a matrix's bytes (the file's, or the
// part of a compressed variable deb inflated).
enum class TagRead { kRead, kPastEnd, kNotHeld };
using TagReader = std::function<TagRead(std::uintmax_t at, unsigned char* tag)>;

// Inside a matrix (miMATRIX) of `size` bytes from `at` (after its tag): its
// data elements (array flags, dimensions, name, the class's parts, and
// nested matrices of cells and structs, walked in turn) each end within it.
// matio allocates what an element's length claims before it reads: one
// length changed in a 688-byte file had it allocate 2 GB. "" if they do
// (or the walk reaches bytes `read` does not hold), else what is wrong.
// `elements` counts every element walked (a bound on the work).
// A cell array or struct array (array flags then dimensions at `at`, its
// matrix `size` bytes long): each of its elements is a matrix of at least
// 8 bytes, so its dimensions may ask for at most size/8; matio allocates a
// pointer per element before it reads one (a 840-byte file asking for
// 1.9e9 cells had it allocate 15.5 GB). "" if it fits or is no such array.
std::string ElementsFit(const TagReader& read, std::uintmax_t at, std::uintmax_t size, bool little) {
  unsigned char word[8];
  if (size < 24 || read(at, word) != TagRead::kRead || Read32(word, little) != 6) return "";
  if (read(at + 8, word) != TagRead::kRead) return "";
  const std::uint32_t class_type = Read32(word, little) & 0xFF;
  if (class_type != 1 && class_type != 2) return "";  // mxCELL_CLASS, mxSTRUCT_CLASS
  if (read(at + 16, word) != TagRead::kRead || Read32(word, little) != 5) return "";
  const std::uint32_t dims_bytes = Read32(word + 4, little);
  if (dims_bytes > 4 * 32 || dims_bytes > size) return "";  // not the plain layout: the walk judges it
  std::uintmax_t count = 1;
  const std::uintmax_t most = size / 8;
  for (std::uint32_t k = 0; k < dims_bytes; k += 8) {
    if (read(at + 24 + k, word) != TagRead::kRead) return "";
    for (std::uint32_t j = 0; j < 8 && k + j + 4 <= dims_bytes; j += 4) {
      const std::uint32_t d = Read32(word + j, little);
      if (d == 0) return "";
      if (count > most / d) {
        count = most + 1;
        break;
      }
      count *= d;
    }
  }
  if (count <= most) return "";
  return std::string("its dimensions ask for more ") + (class_type == 1 ? "cells" : "struct elements") +
         " than its " + std::to_string(size) + " bytes can hold (at most " + std::to_string(most) + ")";
}

// A matrix (of `size` > 0 bytes at `at`, after its tag) starts with its
// array flags (miUINT32, 8 bytes), its dimensions (miINT32, at least two)
// and its name (miINT8, possibly empty), as MATLAB and matio write it. ""
// if it does (or the bytes are not held), else what is wrong: matio reads
// these three by position whatever their tags say (a fuzzed 360-byte file
// whose name element was tagged as a matrix had it read 4.2 GB).
std::string MatrixHeaderProblem(const TagReader& read, std::uintmax_t at, std::uintmax_t size, bool little) {
  const char* what[] = {"array flags", "dimensions", "name"};
  const std::uint32_t want[] = {6, 5, 1};
  std::uintmax_t p = 0;
  for (int k = 0; k < 3; ++k) {
    unsigned char tag[8];
    if (p + 8 > size) return std::string("its ") + what[k] + (k == 2 ? " is" : " are") + " missing";
    const TagRead got = read(at + p, tag);
    if (got == TagRead::kPastEnd) return "it runs past the end of the file";
    if (got == TagRead::kNotHeld) return "";
    std::uint32_t type = Read32(tag, little), bytes = 0;
    if ((type >> 16) != 0) {
      bytes = type >> 16;
      type &= 0xFFFF;
      p += 8;
    } else {
      bytes = Read32(tag + 4, little);
      if (bytes > size - p - 8)
        return "a part at byte " + std::to_string(at + p) + " claims " + std::to_string(bytes) +
               " bytes, more than the variable holds";
      p += 8 + (std::uintmax_t{bytes} + 7) / 8 * 8;
    }
    const bool fits = k == 0 ? bytes == 8 : k == 1 ? bytes >= 8 && bytes % 4 == 0 : true;
    if (type != want[k] || !fits)
      return std::string("its ") + what[k] + (k == 2 ? " is" : " are") + " stored as data type " +
             std::to_string(type) + " of " + std::to_string(bytes) + " bytes, not as MAT-files store " +
             (k == 2 ? "it" : "them");
    // Function handles (16) and MATLAB objects such as strings (17) are laid
    // out otherwise after their flags; deb refuses them by class later.
    if (k == 0) {
      unsigned char flags[8];
      if (read(at + 8, flags) != TagRead::kRead) return "";
      const std::uint32_t class_type = Read32(flags, little) & 0xFF;
      if (class_type == 16 || class_type == 17) return "";
    }
  }
  return "";
}

std::string SubElements(const TagReader& read, std::uintmax_t at, std::uintmax_t size, bool little, int depth,
                        std::size_t& elements) {
  constexpr std::uint32_t kMiMatrix = 14;
  if (depth > 32) return "its cells or structs nest more than 32 deep";
  if (size > 0)
    if (std::string problem = MatrixHeaderProblem(read, at, size, little); !problem.empty()) return problem;
  if (std::string problem = ElementsFit(read, at, size, little); !problem.empty()) return problem;
  std::uintmax_t p = 0;
  while (p + 8 <= size) {
    if (++elements > 1'000'000)
      return "it holds more parts than any variable deb reads";
    unsigned char tag[8];
    const TagRead got = read(at + p, tag);
    if (got == TagRead::kPastEnd) return "it runs past the end of the file";
    if (got == TagRead::kNotHeld) return "";
    const std::uint32_t type = Read32(tag, little);
    if ((type >> 16) != 0) {  // small element: 4 bytes of data in the tag
      if ((type >> 16) > 4) return "a part at byte " + std::to_string(at + p) + " claims more than the 4 bytes it has";
      p += 8;
      continue;
    }
    const std::uint32_t bytes = Read32(tag + 4, little);
    if (bytes > size - p - 8)
      return "a part at byte " + std::to_string(at + p) + " claims " + std::to_string(bytes) +
             " bytes, more than the variable holds";
    if (type == kMiMatrix) {
      const std::string nested = SubElements(read, at + p + 8, bytes, little, depth + 1, elements);
      if (!nested.empty()) return nested;
    }
    p += 8 + (std::uintmax_t{bytes} + 7) / 8 * 8;
  }
  return "";
}

// The first bytes of a compressed variable (miCOMPRESSED: a zlib stream of
// one data element), inflated up to `limit` bytes; fewer if the stream ends
// or is damaged (`damaged` then says so).
std::vector<unsigned char> InflateHead(std::ifstream& in, std::uintmax_t at, std::uint32_t bytes, std::size_t limit,
                                       bool& damaged) {
  std::vector<unsigned char> out(limit);
  z_stream z{};
  damaged = inflateInit(&z) != Z_OK;
  if (damaged) return {};
  in.seekg(static_cast<std::streamoff>(at));
  unsigned char chunk[16384];
  std::uintmax_t left = bytes;
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(limit);
  int status = Z_OK;
  while (z.avail_out > 0 && left > 0 && status == Z_OK) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uintmax_t>(sizeof chunk, left));
    in.read(reinterpret_cast<char*>(chunk), static_cast<std::streamsize>(n));
    if (in.gcount() != static_cast<std::streamsize>(n)) {
      damaged = true;
      break;
    }
    left -= n;
    z.next_in = chunk;
    z.avail_in = static_cast<uInt>(n);
    while (z.avail_in > 0 && z.avail_out > 0 && status == Z_OK) status = inflate(&z, Z_NO_FLUSH);
  }
  if (status != Z_OK && status != Z_STREAM_END) damaged = true;
  out.resize(limit - z.avail_out);
  inflateEnd(&z);
  return out;
}

// A compressed variable of `bytes` bytes at `at` (after its tag): the
// matrix it inflates to is checked as an uncompressed one is, as far as its
// first 64 KiB (where matio reads the array flags, dimensions and name
// before it allocates); the size it claims must be one that `bytes` of zlib
// data can inflate to (at most 1032 times as many). "" if it passes.
std::string CompressedVariable(std::ifstream& in, std::uintmax_t at, std::uint32_t bytes, bool little) {
  constexpr std::uint32_t kMiMatrix = 14;
  constexpr std::uintmax_t kZlibMostRatio = 1032;  // deflate's largest expansion (RFC 1951, 258 bytes per 2 bits)
  bool damaged = false;
  const std::vector<unsigned char> head = InflateHead(in, at, bytes, 65536, damaged);
  if (head.size() < 8)
    return damaged ? "its compressed data cannot be inflated" : "its compressed data holds no variable";
  const std::uint32_t type = Read32(head.data(), little);
  if (type != kMiMatrix) return "its compressed data holds no matrix";
  const std::uint32_t size = Read32(head.data() + 4, little);
  if (size > kZlibMostRatio * std::uintmax_t{bytes})
    return "its compressed data of " + std::to_string(bytes) + " bytes claims " + std::to_string(size) +
           " bytes, more than zlib data of that size can inflate to";
  if (damaged && head.size() < std::min<std::uintmax_t>(size + 8, 65536))
    return "its compressed data is damaged (it inflates to " + std::to_string(head.size()) + " of the " +
           std::to_string(size + 8) + " bytes it claims)";
  const TagReader read = [&](std::uintmax_t p, unsigned char* tag) {
    if (p + 8 > head.size()) return TagRead::kNotHeld;
    std::memcpy(tag, head.data() + p, 8);
    return TagRead::kRead;
  };
  std::size_t elements = 0;
  std::string problem = SubElements(read, 8, size, little, 0, elements);
  if (problem.empty()) problem = ShortData(head.data() + 8, head.size() - 8, size, little);
  return problem;
}

// The version from the 128-byte header; for version 5 (and 7, the same
// format with compression) the top-level data elements (one per variable)
// are walked, each of which must end within the file: matio reads a
// variable cut short by a truncated file without an error, the missing
// values as zeros.
Version CheckLayout(const std::string& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, std::string("cannot open MAT-file (") + std::strerror(errno) + ")");
  if (size < 128)
    Fail(path, "the file holds " + std::to_string(size) +
                   " bytes, too few for a MAT-file (a MAT-file of version 5, 7 or 7.3 starts with a 128-byte header)");
  unsigned char header[128];
  in.read(reinterpret_cast<char*>(header), sizeof header);
  if (in.gcount() != static_cast<std::streamsize>(sizeof header)) Fail(path, "cannot read the MAT-file header");
  const bool little = header[126] == 'I' && header[127] == 'M', big = header[126] == 'M' && header[127] == 'I';
  if (!little && !big)
    Fail(path, "not a MAT-file of version 5, 7 or 7.3 (no MATLAB header); version 4 files are not read: save it "
               "again in MATLAB with save -v7");
  const unsigned version = little ? (header[124] | header[125] << 8) : (header[124] << 8 | header[125]);
  if (version == 0x0200) return Version::k73;
  if (version != 0x0100) {
    char text[8];
    std::snprintf(text, sizeof text, "0x%04x", version);
    Fail(path, std::string("unknown MAT-file version ") + text + " in the header (5, 7 and 7.3 are read)");
  }
  constexpr std::uint32_t kMiMatrix = 14, kMiCompressed = 15;
  std::uintmax_t at = 128;
  std::size_t count = 0;
  while (at + 8 <= size) {
    unsigned char tag[8];
    in.seekg(static_cast<std::streamoff>(at));
    in.read(reinterpret_cast<char*>(tag), sizeof tag);
    if (in.gcount() != static_cast<std::streamsize>(sizeof tag))
      Fail(path, "cannot read the MAT-file (it changed or shrank while being read)");
    const std::uint32_t type = Read32(tag, little), bytes = Read32(tag + 4, little);
    // A small data element (type and size in the first 4 bytes) is 8 bytes.
    std::uintmax_t end = (type >> 16) != 0 ? at + 8 : at + 8 + bytes;
    if (++count > limits::kMaxMatVariables)
      Fail(path, "more than " + std::to_string(limits::kMaxMatVariables) + " variables; is this a MAT-file?");
    if (end > size)
      Fail(path, "the file is truncated or damaged: its variable " + std::to_string(count) + " (at byte " +
                     std::to_string(at) + ") runs to byte " + std::to_string(end) + ", but the file ends at byte " +
                     std::to_string(size));
    if (type == kMiMatrix) {
      unsigned char body[4096];
      const std::size_t have = static_cast<std::size_t>(std::min<std::uintmax_t>(sizeof body, bytes));
      in.read(reinterpret_cast<char*>(body), static_cast<std::streamsize>(have));
      if (in.gcount() != static_cast<std::streamsize>(have))
        Fail(path, "cannot read the MAT-file (it changed or shrank while being read)");
      std::size_t elements = 0;
      const TagReader read = [&](std::uintmax_t p, unsigned char* tag) {
        in.seekg(static_cast<std::streamoff>(p));
        in.read(reinterpret_cast<char*>(tag), 8);
        return in.gcount() == 8 ? TagRead::kRead : TagRead::kPastEnd;
      };
      std::string problem = SubElements(read, at + 8, bytes, little, 0, elements);
      if (problem.empty()) problem = ShortData(body, have, bytes, little);
      if (!problem.empty())
        Fail(path, "the file is damaged: its variable " + std::to_string(count) + " (at byte " + std::to_string(at) +
                       "): " + problem);
      end = (end + 7) / 8 * 8;  // uncompressed variables are padded to 8 bytes
    } else if (type == kMiCompressed) {
      const std::string problem = CompressedVariable(in, at + 8, bytes, little);
      if (!problem.empty())
        Fail(path, "the file is damaged: its variable " + std::to_string(count) + " (at byte " + std::to_string(at) +
                       "): " + problem);
    }
    at = end;
  }
  return Version::k5;
}

// ---------------------------------------------------------------------------
// What a variable is, for messages.

std::string SizeText(const matvar_t& v) {
  std::string s;
  for (int r = 0; r < v.rank; ++r) s += (r ? "x" : "") + std::to_string(v.dims[r]);
  return v.rank == 1 ? s + "x1" : s;
}

std::string ClassName(const matvar_t& v) {
  if (v.isLogical) return "logical";
  switch (v.class_type) {
    case MAT_C_DOUBLE: return "double";
    case MAT_C_SINGLE: return "single";
    case MAT_C_INT8: return "int8";
    case MAT_C_UINT8: return "uint8";
    case MAT_C_INT16: return "int16";
    case MAT_C_UINT16: return "uint16";
    case MAT_C_INT32: return "int32";
    case MAT_C_UINT32: return "uint32";
    case MAT_C_INT64: return "int64";
    case MAT_C_UINT64: return "uint64";
    case MAT_C_CHAR: return "char";
    case MAT_C_CELL: return "cell";
    case MAT_C_STRUCT: return "struct";
    case MAT_C_OBJECT: return "object";
    case MAT_C_SPARSE: return "sparse";
    case MAT_C_FUNCTION: return "function handle";
    case MAT_C_OPAQUE: return "opaque (object)";
    case MAT_C_EMPTY: return "empty";
  }
  return "unknown class";
}

bool IsNumeric(const matvar_t& v) {
  switch (v.class_type) {
    case MAT_C_DOUBLE: case MAT_C_SINGLE: case MAT_C_INT8: case MAT_C_UINT8: case MAT_C_INT16:
    case MAT_C_UINT16: case MAT_C_INT32: case MAT_C_UINT32: case MAT_C_INT64: case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

// "variable 'A' is a 3x3 complex double array".
std::string Describe(const std::string& name, const matvar_t& v) {
  return "variable " + Quoted(name) + " is a " + SizeText(v) + " " + (v.isComplex ? "complex " : "") + ClassName(v) +
         (v.class_type == MAT_C_SPARSE ? " matrix" : " array");
}

// The number of values from the dimensions, or kTooMany past the bound.
constexpr std::size_t kTooMany = limits::kMaxMatElements + 1;
std::size_t Count(const matvar_t& v) {
  for (int r = 0; r < v.rank; ++r)
    if (v.dims[r] == 0) return 0;
  std::size_t n = 1;
  for (int r = 0; r < v.rank; ++r) {
    if (v.dims[r] > limits::kMaxMatElements / n) return kTooMany;
    n *= v.dims[r];
  }
  return n;
}

void RequireCount(const std::string& path, const std::string& name, const matvar_t& v, std::size_t max_count,
                  const std::string& what) {
  if (Count(v) > max_count)
    Fail(path, Describe(name, v) + ": more than the " + std::to_string(max_count) + " " + what + " deb reads");
}

template <typename T>
void Convert(const void* data, std::size_t n, double* out) {
  const T* p = static_cast<const T*>(data);
  for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<double>(p[k]);
}

// Bytes per character of a char variable's data; 0 for no character type.
int CharWidth(const matvar_t& v) {
  switch (v.data_type) {
    case MAT_T_UTF8: case MAT_T_INT8: case MAT_T_UINT8: return 1;
    case MAT_T_UTF16: case MAT_T_INT16: case MAT_T_UINT16: return 2;
    case MAT_T_UTF32: case MAT_T_INT32: case MAT_T_UINT32: return 4;
    default: return 0;
  }
}

void AppendUtf8(std::string& s, std::uint32_t c) {
  if (c < 0x80) {
    s += static_cast<char>(c);
  } else if (c < 0x800) {
    s += static_cast<char>(0xC0 | (c >> 6));
    s += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    s += static_cast<char>(0xE0 | (c >> 12));
    s += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    s += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    s += static_cast<char>(0xF0 | ((c >> 18) & 0x07));
    s += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    s += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    s += static_cast<char>(0x80 | (c & 0x3F));
  }
}

// Row `row` of a char array with `rows` rows and `cols` columns (MATLAB
// stores columns first), as UTF-8, trailing blanks and NULs trimmed.
std::string CharRow(const matvar_t& v, std::size_t rows, std::size_t cols, std::size_t row) {
  const int width = CharWidth(v);
  std::string s;
  std::uint32_t high = 0;  // a UTF-16 high surrogate waiting for its pair
  for (std::size_t c = 0; c < cols; ++c) {
    const std::size_t k = row + c * rows;
    if (width == 1) {
      s += static_cast<const char*>(v.data)[k];
      continue;
    }
    std::uint32_t u = width == 2 ? std::uint32_t{static_cast<const std::uint16_t*>(v.data)[k]}
                                 : static_cast<const std::uint32_t*>(v.data)[k];
    if (width == 2 && u >= 0xD800 && u < 0xDC00) {
      high = u;
      continue;
    }
    if (width == 2 && u >= 0xDC00 && u < 0xE000 && high) u = 0x10000 + ((high - 0xD800) << 10) + (u - 0xDC00);
    high = 0;
    AppendUtf8(s, u > 0x10FFFF ? 0xFFFD : u);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------

struct MatFile::Handle {
  mat_t* mat = nullptr;
  ~Handle() {
    if (mat == nullptr) return;
    const auto lock = LockHdf5();
    Mat_Close(mat);  // read only: nothing to lose if closing fails
  }
};

MatFile::MatFile(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  const std::uintmax_t size = RequireInputFile(path, "MAT-file", limits::kMaxMatFileBytes);
  const Version version = CheckLayout(path, size);
  // matio reads a version 7.3 file through HDF5, which would follow an
  // external link or external storage to any file (a FIFO blocks forever):
  // the whole file is checked first.
  if (version == Version::k73) RequireSelfContainedHdf5(path);
  const MatioCall call;
  handle_->mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
  if (handle_->mat == nullptr || !call.problem().empty())
    Fail(path, "cannot be read as a MAT-file" + call.Because() +
                   (version == Version::k73 ? ": a version 7.3 (HDF5) file that is truncated or damaged" : ""));
  const mat_ft opened = Mat_GetVersion(handle_->mat);
  if (opened != (version == Version::k73 ? MAT_FT_MAT73 : MAT_FT_MAT5))
    Fail(path, "matio reads the file as another MAT-file version than its header gives; is it damaged?");
  std::size_t n = 0;
  char** dir = Mat_GetDir(handle_->mat, &n);  // owned by the mat_t
  if (!call.problem().empty()) Fail(path, "cannot list the variables of the MAT-file" + call.Because());
  for (std::size_t i = 0; dir != nullptr && i < n; ++i)
    if (dir[i] != nullptr) variables_.emplace_back(dir[i]);
  // matio would read the first of two variables of one name, silently.
  std::set<std::string> seen;
  for (const std::string& v : variables_)
    if (!seen.insert(v).second) Fail(path, "holds two variables named " + Quoted(v) + "; is the file damaged?");
}

MatFile::~MatFile() = default;

bool MatFile::Has(const std::string& name) const {
  for (const std::string& v : variables_)
    if (v == name) return true;
  return false;
}

namespace {

// A variable read from the file: a top-level variable, or a field inside
// one (owned by it).
struct Var {
  VarPtr root;
  matvar_t* v = nullptr;
  matvar_t* operator->() const { return v; }
  matvar_t& operator*() const { return *v; }
  matvar_t* get() const { return v; }
};

// The header of variable `name` (no data yet); "a.b.c" is field c of the
// 1x1 struct field b of the 1x1 struct variable a.
Var ReadInfo(const MatFile& file, mat_t* mat, const std::string& name) {
  std::vector<std::string> parts;
  for (std::size_t at = 0;;) {
    const std::size_t dot = name.find('.', at);
    parts.push_back(name.substr(at, dot == std::string::npos ? std::string::npos : dot - at));
    if (dot == std::string::npos) break;
    at = dot + 1;
  }
  const std::string& top = parts.front();
  if (!file.Has(top)) {
    std::string held;
    for (std::size_t i = 0; i < file.variables().size() && i < 20; ++i)
      held += (i ? ", " : "") + Excerpt(file.variables()[i]);
    if (file.variables().size() > 20) held += ", ...";
    Fail(file.path(), "no variable " + Quoted(top) + " in the MAT-file (" +
                          (held.empty() ? std::string("it holds no variables") : "it holds " + held) + ")");
  }
  const MatioCall call;
  Var var;
  var.root.reset(Mat_VarReadInfo(mat, top.c_str()));
  var.v = var.root.get();
  if (!var.v || !call.problem().empty() || var.v->rank < 1 || var.v->dims == nullptr)
    Fail(file.path(), "variable " + Quoted(top) + " cannot be read" + call.Because() + "; is the file damaged?");
  std::string at = top;
  for (std::size_t p = 1; p < parts.size(); ++p) {
    if (var.v->class_type != MAT_C_STRUCT || Count(*var.v) != 1)
      Fail(file.path(), Describe(at, *var.v) + ", not a 1x1 struct; " + Quoted(name) + " asks for its field " +
                            Quoted(parts[p]));
    matvar_t* const field = Mat_VarGetStructFieldByName(var.v, parts[p].c_str(), 0);
    if (field == nullptr) {
      std::string fields;
      const unsigned n = Mat_VarGetNumberOfFields(var.v);
      char* const* names = Mat_VarGetStructFieldnames(var.v);
      for (unsigned i = 0; names != nullptr && i < n && i < 20; ++i)
        fields += (i ? ", " : "") + Excerpt(names[i] != nullptr ? names[i] : "");
      if (n > 20) fields += ", ...";
      Fail(file.path(), "the struct " + Quoted(at) + " has no field " + Quoted(parts[p]) + " (its fields: " +
                            (fields.empty() ? std::string("none") : fields) + ")");
    }
    at += "." + parts[p];
    var.v = field;
    if (!call.problem().empty() || var.v->rank < 1 || var.v->dims == nullptr)
      Fail(file.path(), "variable " + Quoted(at) + " cannot be read" + call.Because() + "; is the file damaged?");
  }
  return var;
}

void ReadData(const MatFile& file, mat_t* mat, matvar_t& v, const std::string& name) {
  const MatioCall call;
  const int err = Mat_VarReadDataAll(mat, &v);
  if (err != MATIO_E_NO_ERROR || !call.problem().empty())
    Fail(file.path(), "the values of " + Describe(name, v) + " cannot be read" + call.Because() +
                          "; is the file damaged?");
}

// Data present and as long as `count` values of its type.
void RequireData(const MatFile& file, const matvar_t& v, const std::string& name, std::size_t count) {
  const std::size_t size = Mat_SizeOf(v.data_type);
  if (v.data == nullptr || size == 0 || v.nbytes / size < count)
    Fail(file.path(), Describe(name, v) + " but holds fewer values; is the file damaged?");
}

}  // namespace

Eigen::MatrixXd MatFile::Matrix(const std::string& name) const {
  const Var v = ReadInfo(*this, handle_->mat, name);
  const std::string expected = "; expected a real 2-D matrix";
  if (v->class_type == MAT_C_EMPTY) return Eigen::MatrixXd(0, 0);
  if (v->rank > 2)
    Fail(path_, "variable " + Quoted(name) + " is " + SizeText(*v) + " (a " + std::to_string(v->rank) + "-D array)" +
                    expected);
  if (!IsNumeric(*v)) Fail(path_, Describe(name, *v) + expected + " of numbers");
  if (v->isComplex) Fail(path_, Describe(name, *v) + expected + " (complex values are not read)");
  RequireCount(path_, name, *v, limits::kMaxMatElements, "values");
  const std::size_t n = Count(*v);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(v->dims[0]), static_cast<Eigen::Index>(v->rank == 2 ? v->dims[1] : 1));
  if (n == 0) return out;
  ReadData(*this, handle_->mat, *v, name);
  RequireData(*this, *v, name, n);
  switch (v->data_type) {
    case MAT_T_DOUBLE: Convert<double>(v->data, n, out.data()); break;
    case MAT_T_SINGLE: Convert<float>(v->data, n, out.data()); break;
    case MAT_T_INT8: Convert<std::int8_t>(v->data, n, out.data()); break;
    case MAT_T_UINT8: Convert<std::uint8_t>(v->data, n, out.data()); break;
    case MAT_T_INT16: Convert<std::int16_t>(v->data, n, out.data()); break;
    case MAT_T_UINT16: Convert<std::uint16_t>(v->data, n, out.data()); break;
    case MAT_T_INT32: Convert<std::int32_t>(v->data, n, out.data()); break;
    case MAT_T_UINT32: Convert<std::uint32_t>(v->data, n, out.data()); break;
    case MAT_T_INT64: Convert<std::int64_t>(v->data, n, out.data()); break;
    case MAT_T_UINT64: Convert<std::uint64_t>(v->data, n, out.data()); break;
    default: Fail(path_, Describe(name, *v) + " whose values are of an unknown type; is the file damaged?");
  }
  for (Eigen::Index c = 0; c < out.cols(); ++c)
    for (Eigen::Index r = 0; r < out.rows(); ++r)
      if (!std::isfinite(out(r, c)))
        Fail(path_, name + "(" + std::to_string(r + 1) + "," + std::to_string(c + 1) + ") = " +
                        NumberText(out(r, c)) + " in the " + SizeText(*v) + " " + ClassName(*v) +
                        " array; expected finite numbers");
  return out;
}

std::vector<double> MatFile::Vector(const std::string& name) const {
  const Eigen::MatrixXd m = Matrix(name);
  const std::string size = std::to_string(m.rows()) + "x" + std::to_string(m.cols());
  if (m.size() == 0) Fail(path_, "variable " + Quoted(name) + " is empty (" + size + "); expected at least one value");
  if (m.rows() != 1 && m.cols() != 1)
    Fail(path_, "variable " + Quoted(name) + " is " + size + "; expected a vector (1xn or nx1) or a scalar");
  return std::vector<double>(m.data(), m.data() + m.size());
}

std::vector<std::string> MatFile::Names(const std::string& name) const {
  const Var v = ReadInfo(*this, handle_->mat, name);
  const std::string expected =
      "; expected names: a cell array of char row vectors ({'Fx', 'Fy'}) or a char matrix (char('Fx', 'Fy'))";
  std::vector<std::string> names;
  if (v->class_type == MAT_C_CHAR) {
    if (v->rank != 2) Fail(path_, Describe(name, *v) + expected);
    if (v->dims[0] > static_cast<std::size_t>(limits::kMaxChannels))
      Fail(path_, Describe(name, *v) + ": more than the " + std::to_string(limits::kMaxChannels) + " names deb reads");
    RequireCount(path_, name, *v, limits::kMaxMatElements, "characters");
    const std::size_t n = Count(*v);
    if (n == 0) Fail(path_, Describe(name, *v) + ", which holds no names");
    ReadData(*this, handle_->mat, *v, name);
    if (CharWidth(*v) == 0) Fail(path_, Describe(name, *v) + " whose characters are of an unknown type");
    RequireData(*this, *v, name, n);
    for (std::size_t r = 0; r < v->dims[0]; ++r) {
      names.push_back(CharRow(*v, v->dims[0], v->dims[1], r));
      if (names.back().empty())
        Fail(path_, Describe(name, *v) + " whose row " + std::to_string(r + 1) + " is blank; every name must be given");
      if (const std::string problem = Utf8Problem(names.back()); !problem.empty())
        Fail(path_, Describe(name, *v) + " whose row " + std::to_string(r + 1) + " is not text: " + problem + " (save the names as UTF-8)");
    }
    return names;
  }
  if (v->class_type != MAT_C_CELL || v->rank != 2 || (v->dims[0] != 1 && v->dims[1] != 1))
    Fail(path_, Describe(name, *v) + expected);
  if (Count(*v) > static_cast<std::size_t>(limits::kMaxChannels))
    Fail(path_, Describe(name, *v) + ": more than the " + std::to_string(limits::kMaxChannels) + " names deb reads");
  const std::size_t n = Count(*v);
  if (n == 0) Fail(path_, Describe(name, *v) + ", which holds no names");
  ReadData(*this, handle_->mat, *v, name);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string element = name + "{" + std::to_string(i + 1) + "}";
    matvar_t* e = nullptr;
    {
      const MatioCall call;
      e = Mat_VarGetCell(v.get(), static_cast<int>(i));  // owned by the cell array
      if (e == nullptr || !call.problem().empty())
        Fail(path_, element + " of the " + SizeText(*v) + " cell array cannot be read" + call.Because() +
                        "; is the file damaged?");
    }
    if (e->rank < 1 || e->dims == nullptr) Fail(path_, element + " cannot be read; is the file damaged?");
    const std::string what = element + " is a " + SizeText(*e) + " " + ClassName(*e) + " array";
    if (e->class_type != MAT_C_CHAR || e->rank != 2 || (e->dims[0] != 1 && Count(*e) != 0))
      Fail(path_, what + "; expected one name (a char row vector) per element of the " + SizeText(*v) + " cell array");
    const std::size_t chars = Count(*e);
    if (chars > 0) {
      if (CharWidth(*e) == 0) Fail(path_, what + " whose characters are of an unknown type");
      RequireData(*this, *e, element, chars);
      names.push_back(CharRow(*e, 1, chars, 0));
    } else {
      names.emplace_back();
    }
    if (names.back().empty()) Fail(path_, what + ": an empty name; every name must be given");
    if (const std::string problem = Utf8Problem(names.back()); !problem.empty())
      Fail(path_, what + " that is not text: " + problem + " (save the names as UTF-8)");
  }
  return names;
}


// ---------------------------------------------------------------------------
// Writing.

MatValue MatValue::Matrix(Eigen::MatrixXd m) {
  MatValue v;
  v.matrix = std::move(m);
  return v;
}

MatValue MatValue::Scalar(double value) { return Matrix(Eigen::MatrixXd::Constant(1, 1, value)); }

MatValue MatValue::Column(const std::vector<double>& values) {
  return Matrix(Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())));
}

MatValue MatValue::Text(std::string text) {
  MatValue v;
  v.kind = Kind::kText;
  v.text = std::move(text);
  return v;
}

MatValue MatValue::Names(std::vector<std::string> names) {
  MatValue v;
  v.kind = Kind::kNames;
  v.names = std::move(names);
  return v;
}

MatValue MatValue::Struct() {
  MatValue v;
  v.kind = Kind::kStruct;
  return v;
}

MatValue& MatValue::Add(const std::string& field, MatValue value) {
  DEB_DEMAND(kind == Kind::kStruct);
  field_names.push_back(field);
  fields.push_back(std::move(value));
  return *this;
}

namespace {

// UTF-8 as UTF-16 code units (MATLAB's characters); a byte that does not
// start a valid sequence becomes U+FFFD.
std::vector<std::uint16_t> Utf16(const std::string& s) {
  std::vector<std::uint16_t> out;
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char b = static_cast<unsigned char>(s[i]);
    const int extra = b < 0x80 ? 0 : (b >> 5) == 0x6 ? 1 : (b >> 4) == 0xE ? 2 : (b >> 3) == 0x1E ? 3 : -1;
    std::uint32_t c = extra == 0 ? b : extra == 1 ? (b & 0x1F) : extra == 2 ? (b & 0x0F) : (b & 0x07);
    bool valid = extra >= 0 && i + static_cast<std::size_t>(extra) < s.size();
    for (int k = 1; valid && k <= extra; ++k) {
      const unsigned char t = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      valid = (t >> 6) == 0x2;
      c = c << 6 | (t & 0x3F);
    }
    if (!valid || c > 0x10FFFF || (c >= 0xD800 && c < 0xE000)) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    i += 1 + static_cast<std::size_t>(extra);
    if (c >= 0x10000) {
      out.push_back(static_cast<std::uint16_t>(0xD800 + ((c - 0x10000) >> 10)));
      out.push_back(static_cast<std::uint16_t>(0xDC00 + ((c - 0x10000) & 0x3FF)));
    } else {
      out.push_back(static_cast<std::uint16_t>(c));
    }
  }
  return out;
}

// A matvar being built (freed unless released into a parent or written).
using NewVar = std::unique_ptr<matvar_t, VarFree>;

// The matio variable of `value`, named `name` (nullptr inside a struct or
// cell). `where` names it in messages ("outputs.position.psd").
NewVar MakeVar(const char* name, const MatValue& value, const std::string& path, const std::string& where) {
  const auto made = [&](matvar_t* v) {
    if (v == nullptr) throw WriteError(path + ": cannot make the MAT-file variable " + where + " (matio refused it)");
    return NewVar(v);
  };
  switch (value.kind) {
    case MatValue::Kind::kMatrix: {
      size_t dims[2] = {static_cast<size_t>(value.matrix.rows()), static_cast<size_t>(value.matrix.cols())};
      // Copied by matio (opt 0); Eigen stores columns first, as MATLAB does.
      void* data = value.matrix.size() ? const_cast<double*>(value.matrix.data()) : nullptr;
      return made(Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, data, 0));
    }
    case MatValue::Kind::kText: {
      std::vector<std::uint16_t> chars = Utf16(value.text);
      size_t dims[2] = {chars.empty() ? size_t{0} : size_t{1}, chars.size()};
      return made(Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT16, 2, dims, chars.empty() ? nullptr : chars.data(), 0));
    }
    case MatValue::Kind::kNames: {
      std::vector<NewVar> cells;
      for (std::size_t i = 0; i < value.names.size(); ++i)
        cells.push_back(MakeVar(nullptr, MatValue::Text(value.names[i]), path, where + "{" + std::to_string(i + 1) + "}"));
      size_t dims[2] = {cells.size(), 1};
      // matio copies the array of pointers and owns the elements from here.
      std::vector<matvar_t*> pointers;
      for (const NewVar& c : cells) pointers.push_back(c.get());
      NewVar cell = made(Mat_VarCreate(name, MAT_C_CELL, MAT_T_CELL, 2, dims, pointers.empty() ? nullptr : pointers.data(), 0));
      for (NewVar& c : cells) c.release();
      return cell;
    }
    case MatValue::Kind::kStruct: {
      std::vector<const char*> fields;
      for (const std::string& f : value.field_names) fields.push_back(f.c_str());
      fields.push_back(nullptr);
      const size_t dims[2] = {1, 1};
      NewVar s = made(Mat_VarCreateStruct2(name, 2, dims, fields.data()));
      for (std::size_t i = 0; i < value.fields.size(); ++i) {
        const std::string field_where = where + "." + value.field_names[i];
        NewVar f = MakeVar(nullptr, value.fields[i], path, field_where);
        if (Mat_VarSetStructFieldByName(s.get(), value.field_names[i].c_str(), 0, f.get()) != nullptr)
          throw WriteError(path + ": cannot set the MAT-file field " + field_where + " (it was set twice)");
        f.release();  // owned by the struct (SetStructFieldByName returned no previous field)
      }
      return s;
    }
  }
  throw WriteError(path + ": cannot make the MAT-file variable " + where);
}

}  // namespace

void WriteMatFile(const std::string& path, const std::vector<std::pair<std::string, MatValue>>& variables,
                  const std::string& description) {
  std::error_code ec;
  std::filesystem::remove(path, ec);  // matio would refuse an existing file of another version
  bool written = false;
  const auto cleanup = [&] {
    if (!written) std::filesystem::remove(path, ec);
  };
  try {
    const MatioCall call;
    const std::string header = ("MATLAB 5.0 MAT-file, " + description).substr(0, 116);
    mat_t* mat = Mat_CreateVer(path.c_str(), header.c_str(), MAT_FT_MAT5);
    if (mat == nullptr)
      throw WriteError(path + ": cannot create the MAT-file" + call.Because() + " (" + std::strerror(errno) + ")");
    try {
      for (const auto& [name, value] : variables) {
        NewVar v = MakeVar(name.c_str(), value, path, name);
        if (Mat_VarWrite(mat, v.get(), MAT_COMPRESSION_ZLIB) != 0 || !call.problem().empty())
          throw WriteError(path + ": cannot write the MAT-file variable " + name + call.Because());
      }
    } catch (...) {
      Mat_Close(mat);
      throw;
    }
    if (Mat_Close(mat) != 0 || !call.problem().empty())
      throw WriteError(path + ": cannot finish the MAT-file" + call.Because());
    written = true;
  } catch (...) {
    cleanup();
    throw;
  }
}

}  // namespace deb::formats
