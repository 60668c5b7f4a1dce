// The OP2 reader of NastranModeFile (deb/formats/nastran_modes.h).
//
// An OP2 file is a sequence of Fortran unformatted records: a 4-byte length
// L, L bytes, L again. A record of one word is a "key". After an optional
// header (key 3, the date; key 7, the tape code; key 2, a label; keys -1, 0)
// come the data blocks, each
//   key 2, its name (8 characters); key -1, key 7, the trailer (7 words);
//   keys -2, 1, 0; then its logical records, each
//     key n, a record of n words (continued by further key n', record pairs
//     when it was written in pieces), keys -r, 1, 0;
//   and key 0 after the last.
// A key 0 where a block would start ends the file. In a file of 64-bit words
// every word (keys included) is 8 bytes; the length markers stay 4 bytes.
//
// The blocks read here:
//   LAMA   records: 0 header, 1 identification (146 words), 2 the modes,
//          7 words each: mode number, extraction order (integers), then
//          eigenvalue, radians, cycles, generalised mass, generalised
//          stiffness (reals);
//   OUGV1 / BOUGV1  records: 0 header, then per mode an identification
//          record (word 0 approach code x 10 + device code, 1 table code,
//          3 subcase, 4 mode number, 5 eigenvalue, 9 words per grid) and a
//          data record, per grid: grid id x 10 + device code, point type
//          (1 grid, 2 scalar, ...), T1 T2 T3 R1 R2 R3.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <unordered_map>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/formats/nastran_reader.h"

namespace deb::formats {
namespace {

// Where one piece of a logical record's data is: the payload's first byte
// and its length.
struct Piece {
  std::uint64_t offset = 0;
  std::uint64_t bytes = 0;
};

// A logical record: its pieces, in order, and where its first key was.
struct LogicalRecord {
  std::uint64_t offset = 0;
  std::vector<Piece> pieces;
  std::uint64_t bytes() const {
    std::uint64_t n = 0;
    for (const Piece& p : pieces) n += p.bytes;
    return n;
  }
};

struct Block {
  std::string name;
  std::uint64_t offset = 0;  // of the key before its name
  std::vector<LogicalRecord> records;  // kept only for the blocks read
};

// Logical records kept of one block: a bound against a file of millions of
// tiny records (two per mode are real, and kMaxFileModes modes).
constexpr std::size_t kMaxKeptRecords = 2 * static_cast<std::size_t>(kMaxFileModes) + 16;
// Pieces kept in all (each is 16 bytes).
constexpr std::size_t kMaxKeptPieces = 8'000'000;

class Op2File {
 public:
  explicit Op2File(const std::string& path) : path_(path) {
    size_ = RequireInputFile(path, "Nastran OP2 file", limits::kMaxSolverFileBytes);
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw InputError(path + ": cannot be opened: " + std::strerror(errno));
    unsigned char first[4];
    ReadAt(0, first, 4, "the first record's length");
    std::uint32_t len;
    std::memcpy(&len, first, 4);
    if (len == 4 || len == 8) {
      swap_ = false;
    } else if (Swapped32(len) == 4 || Swapped32(len) == 8) {
      swap_ = true;
      len = Swapped32(len);
    } else {
      Fail(0, "not an OP2 file: its first record is not one 4- or 8-byte word");
    }
    word_ = len;
    const bool little = (HostIsLittle() != swap_);
    format_ = std::string("OP2, ") + (little ? "little" : "big") + "-endian, " + (word_ == 4 ? "32" : "64") +
              "-bit words";
  }
  ~Op2File() {
    if (fd_ >= 0) ::close(fd_);
  }
  Op2File(const Op2File&) = delete;
  Op2File& operator=(const Op2File&) = delete;

  const std::string& path() const { return path_; }
  const std::string& format() const { return format_; }
  std::uint64_t word() const { return word_; }

  // Every block's name, and the logical records of those `keep` says yes to.
  std::vector<Block> Scan(const std::function<bool(const std::string&)>& keep) {
    pos_ = 0;
    std::vector<Block> blocks;
    std::size_t pieces = 0;
    SkipHeader();
    while (pos_ < size_) {
      const std::uint64_t at = pos_;
      const long long k = Key("a data block's name key (2) or the end of the file (0)");
      if (k == 0) break;
      Block b;
      b.offset = at;
      const Piece name = Record();
      if (k <= 0 || name.bytes != static_cast<std::uint64_t>(k) * word_ || name.bytes > 64)
        Fail(at, "expected a data block's name (key 2 and 8 characters), found key " + std::to_string(k) + " and " +
                     std::to_string(name.bytes) + " bytes");
      b.name = NameAt(name);
      Expect(-1, b.name);
      const long long t = Key("the trailer's length of " + b.name);
      const Piece trailer = Record();
      if (t <= 0 || trailer.bytes != static_cast<std::uint64_t>(t) * word_)
        Fail(trailer.offset - 4, b.name + ": the trailer holds " + std::to_string(trailer.bytes) + " bytes, its key says " +
                                     std::to_string(t) + " words");
      Expect(-2, b.name);
      Expect(1, b.name);
      Expect(0, b.name);
      const bool kept = keep(b.name);
      for (;;) {
        const std::uint64_t record_at = pos_;
        long long n = Key(b.name + ": a record's length in words, or 0 at the block's end");
        if (n == 0) break;
        if (n < 0) Fail(record_at, b.name + ": a record's length is " + std::to_string(n) + " words");
        LogicalRecord r;
        r.offset = record_at;
        while (n > 0) {
          const Piece p = Record();
          if (p.bytes != static_cast<std::uint64_t>(n) * word_)
            Fail(p.offset - 4, b.name + ": a record of " + std::to_string(p.bytes) + " bytes where its key says " +
                                   std::to_string(n) + " words of " + std::to_string(word_) + " bytes");
          if (kept) {
            if (++pieces > kMaxKeptPieces)
              Fail(p.offset - 4, b.name + ": more than " + std::to_string(kMaxKeptPieces) + " record pieces");
            r.pieces.push_back(p);
          }
          n = Key(b.name + ": the next piece's length or the record's end (a negative key)");
        }
        Expect(1, b.name);
        Key(b.name + ": the key after a record's end");
        if (kept) {
          if (b.records.size() >= kMaxKeptRecords)
            Fail(record_at, b.name + ": more than " + std::to_string(kMaxKeptRecords) + " records");
          b.records.push_back(std::move(r));
        }
      }
      blocks.push_back(std::move(b));
    }
    return blocks;
  }

  // The whole logical record.
  std::vector<unsigned char> Read(const LogicalRecord& r, const std::string& what) const {
    std::vector<unsigned char> data(r.bytes());
    std::uint64_t at = 0;
    for (const Piece& p : r.pieces) {
      ReadAt(p.offset, data.data() + at, p.bytes, what);
      at += p.bytes;
    }
    return data;
  }
  // `bytes` bytes from byte `from` of the logical record.
  void ReadPart(const LogicalRecord& r, std::uint64_t from, unsigned char* out, std::uint64_t bytes,
                const std::string& what) const {
    for (const Piece& p : r.pieces) {
      if (from >= p.bytes) {
        from -= p.bytes;
        continue;
      }
      const std::uint64_t n = std::min(bytes, p.bytes - from);
      ReadAt(p.offset + from, out, n, what);
      out += n;
      bytes -= n;
      from = 0;
      if (bytes == 0) return;
    }
    DEB_DEMAND(bytes == 0);
  }

  long long Int(const unsigned char* p) const {
    const std::uint64_t bits = Bits(p);
    if (word_ == 4) {
      std::int32_t s;
      const std::uint32_t v = static_cast<std::uint32_t>(bits);
      std::memcpy(&s, &v, 4);
      return s;
    }
    std::int64_t s;
    std::memcpy(&s, &bits, 8);
    return s;
  }
  double Real(const unsigned char* p) const {
    const std::uint64_t bits = Bits(p);
    if (word_ == 4) {
      float f;
      const std::uint32_t v = static_cast<std::uint32_t>(bits);
      std::memcpy(&f, &v, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &bits, 8);
    return d;
  }

  [[noreturn]] void Fail(std::uint64_t offset, const std::string& rule) const {
    throw InputError(path_ + ": byte " + std::to_string(offset) + ": " + rule);
  }

 private:
  static bool HostIsLittle() {
    const std::uint32_t one = 1;
    unsigned char b;
    std::memcpy(&b, &one, 1);
    return b == 1;
  }
  // The word at `p` in the host's byte order (a 4-byte word in the low bits).
  std::uint64_t Bits(const unsigned char* p) const {
    if (word_ == 4) {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return swap_ ? Swapped32(v) : v;
    }
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    return swap_ ? Swapped64(v) : v;
  }

  void ReadAt(std::uint64_t offset, unsigned char* out, std::uint64_t bytes, const std::string& what) const {
    if (offset > size_ || bytes > size_ - offset)
      Fail(offset, "the file ends (at byte " + std::to_string(size_) + ") inside " + what + " (truncated?)");
    while (bytes > 0) {
      const ssize_t n = ::pread(fd_, out, static_cast<std::size_t>(std::min<std::uint64_t>(bytes, 1u << 30)),
                                static_cast<off_t>(offset));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) Fail(offset, std::string("cannot be read: ") + (n < 0 ? std::strerror(errno) : "unexpected end"));
      out += n;
      offset += static_cast<std::uint64_t>(n);
      bytes -= static_cast<std::uint64_t>(n);
    }
  }

  std::uint32_t Marker(std::uint64_t offset) const {
    unsigned char b[4];
    ReadAt(offset, b, 4, "a record's length marker");
    std::uint32_t v;
    std::memcpy(&v, b, 4);
    return swap_ ? Swapped32(v) : v;
  }

  // The next Fortran record (its payload), checked: both markers equal, within the file.
  Piece Record() {
    const std::uint64_t at = pos_;
    if (size_ - pos_ < 4) Fail(at, "the file ends inside a record's length marker (truncated?)");
    const std::uint32_t len = Marker(at);
    if (len > 0x7fffffffu) Fail(at, "a record length of " + std::to_string(len) + " bytes");
    if (size_ - at - 4 < static_cast<std::uint64_t>(len) + 4)
      Fail(at, "a record of " + std::to_string(len) + " bytes runs past the file's end (at byte " +
                   std::to_string(size_) + "; truncated?)");
    const std::uint32_t end = Marker(at + 4 + len);
    if (end != len)
      Fail(at, "a record's length markers disagree: " + std::to_string(len) + " before it, " + std::to_string(end) +
                   " after it");
    pos_ = at + 8 + len;
    return {at + 4, len};
  }

  long long Key(const std::string& what) {
    const std::uint64_t at = pos_;
    const Piece p = Record();
    if (p.bytes != word_)
      Fail(at, "expected " + what + " (a record of one " + std::to_string(word_) + "-byte word), found a record of " +
                   std::to_string(p.bytes) + " bytes");
    unsigned char b[8];
    ReadAt(p.offset, b, word_, what);
    return Int(b);
  }

  void Expect(long long value, const std::string& block) {
    const std::uint64_t at = pos_;
    const long long k = Key(block + ": key " + std::to_string(value));
    if (k != value) Fail(at, block + ": expected key " + std::to_string(value) + ", found " + std::to_string(k));
  }

  // The name's letters, digits and underscores (blanks and, in 64-bit files,
  // padding dropped).
  std::string NameAt(const Piece& p) const {
    unsigned char b[64];
    ReadAt(p.offset, b, p.bytes, "a data block's name");
    std::string name;
    for (std::uint64_t i = 0; i < p.bytes; ++i)
      if (std::isalnum(b[i]) || b[i] == '_') name += static_cast<char>(b[i]);
    return name;
  }

  void SkipHeader() {
    if (Key("the first key") != 3) {
      pos_ = 0;  // no header: the file starts with a block
      return;
    }
    Record();  // the date
    Key("the tape code's length");
    Record();
    Key("the label's length");
    Record();
    Expect(-1, "the file's header");
    Expect(0, "the file's header");
  }

  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::uint64_t pos_ = 0;
  std::uint64_t word_ = 4;
  bool swap_ = false;
  std::string format_;
};

// Where each requested grid's row is in a mode's data record.
struct Row {
  std::uint64_t index = 0;
  int point_type = 0;
};

class Op2Modes final : public NastranModeFile::Reader {
 public:
  explicit Op2Modes(const std::string& path) : file_(path) {
    format = file_.format();
    const std::vector<Block> blocks = file_.Scan([](const std::string& name) {
      return name.rfind("LAMA", 0) == 0 || name == "OUGV1" || name == "BOUGV1";
    });
    const Block* lama = nullptr;
    const Block* shapes = nullptr;
    std::vector<std::string> names;
    for (const Block& b : blocks) {
      names.push_back(b.name);
      if (!lama && b.name.rfind("LAMA", 0) == 0) lama = &b;
      if (b.name == "OUGV1" && (!shapes || shapes->name != "OUGV1")) shapes = &b;
      if (b.name == "BOUGV1" && !shapes) shapes = &b;
    }
    std::string listed;
    for (const std::string& n : names) listed += (listed.empty() ? "" : ", ") + n;
    if (!lama)
      throw InputError(file_.path() + ": no eigenvalue table (LAMA): not the results of a normal modes run (SOL 103)? "
                                      "The file holds " + (listed.empty() ? std::string("no data block") : listed));
    if (!shapes)
      throw InputError(file_.path() + ": no eigenvectors (OUGV1 or BOUGV1): request them with DISP(PLOT)=ALL (or a "
                                      "SET) in the case control. The file holds " + listed);
    table = shapes->name;
    ReadEigenvalues(*lama);
    IndexShapes(*shapes);
  }

  Eigen::MatrixXd Shapes(const std::vector<NastranDof>& dofs, int count) const override {
    Eigen::MatrixXd phi(static_cast<Eigen::Index>(dofs.size()), count);
    if (count == 0 || dofs.empty()) return phi;
    const std::uint64_t w = file_.word(), row_bytes = num_wide_ * w;
    // The rows of the requested grids, found in the first mode's record;
    // later modes are checked to hold each grid at the same row, and searched
    // again where one does not.
    std::map<long long, Row> rows;
    for (const NastranDof& d : dofs) rows[d.grid];
    FindRows(data_[0], rows, dofs);
    std::vector<unsigned char> buffer(row_bytes);
    for (int k = 0; k < count; ++k) {
      const LogicalRecord& r = data_[static_cast<std::size_t>(k)];
      const std::string what = table + " (mode " + std::to_string(modes[k].number) + ")";
      bool found = true;
      for (auto& [grid, row] : rows) {
        if ((row.index + 1) * row_bytes > r.bytes()) {
          found = false;
          break;
        }
        file_.ReadPart(r, row.index * row_bytes, buffer.data(), w, what);
        if (file_.Int(buffer.data()) / 10 != grid) found = false;
      }
      if (!found) FindRows(r, rows, dofs);
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        const Row& row = rows.at(dofs[i].grid);
        file_.ReadPart(r, row.index * row_bytes, buffer.data(), row_bytes, what);
        const double v = file_.Real(buffer.data() + (1 + static_cast<std::uint64_t>(dofs[i].component)) * w);
        if (!std::isfinite(v))
          throw InputError(file_.path() + ": " + what + ": " + NastranDofText(dofs[i]) + " is " + NumberText(v));
        phi(static_cast<Eigen::Index>(i), k) = v;
      }
    }
    return phi;
  }

 private:
  void ReadEigenvalues(const Block& lama) {
    if (lama.records.size() < 3)
      file_.Fail(lama.offset, lama.name + " holds " + std::to_string(lama.records.size()) +
                                  " record(s); the eigenvalues are its third");
    if (lama.records.size() > 3)
      file_.Fail(lama.records[3].offset, lama.name + " holds " + std::to_string(lama.records.size()) +
                                             " records: several subcases? deb reads the modes of one");
    const LogicalRecord& r = lama.records[2];
    const std::uint64_t w = file_.word(), per_mode = 7 * w;
    if (r.bytes() % per_mode != 0)
      file_.Fail(r.offset, lama.name + ": the eigenvalue record holds " + std::to_string(r.bytes()) +
                               " bytes, not a multiple of 7 words (" + std::to_string(per_mode) + " bytes) per mode");
    const std::uint64_t n = r.bytes() / per_mode;
    if (n > static_cast<std::uint64_t>(kMaxFileModes))
      file_.Fail(r.offset, lama.name + ": " + std::to_string(n) + " modes; at most " + std::to_string(kMaxFileModes) +
                               " are read");
    const std::vector<unsigned char> data = file_.Read(r, lama.name);
    for (std::uint64_t k = 0; k < n; ++k) {
      const unsigned char* p = data.data() + k * per_mode;
      NastranMode m;
      m.number = file_.Int(p);
      m.eigenvalue = file_.Real(p + 2 * w);
      m.f_hz = file_.Real(p + 4 * w);
      m.generalized_mass = file_.Real(p + 5 * w);
      m.generalized_stiffness = file_.Real(p + 6 * w);
      const std::string mode = lama.name + ": mode " + std::to_string(m.number);
      for (double v : {m.eigenvalue, m.f_hz, m.generalized_mass, m.generalized_stiffness})
        if (!std::isfinite(v)) file_.Fail(r.offset, mode + ": a value that is not finite (" + NumberText(v) + ")");
      if (m.f_hz < 0.0) file_.Fail(r.offset, mode + ": cycles " + NumberText(m.f_hz) + " < 0");
      if (!(m.generalized_mass > 0.0))
        file_.Fail(r.offset, mode + ": generalised mass " + NumberText(m.generalized_mass) + " (must be > 0)");
      if (!modes.empty() && m.number <= modes.back().number)
        file_.Fail(r.offset, mode + " after mode " + std::to_string(modes.back().number) +
                                 ": mode numbers must increase (several subcases?)");
      modes.push_back(m);
    }
  }

  // The data record of each mode, checked against its identification record.
  void IndexShapes(const Block& b) {
    const std::uint64_t w = file_.word();
    if (b.records.size() < 3) file_.Fail(b.offset, b.name + " holds no eigenvector");
    std::unordered_map<long long, std::size_t> data_of;  // mode number -> record
    for (std::size_t i = 1; i < b.records.size(); i += 2) {
      const LogicalRecord& id = b.records[i];
      if (i + 1 >= b.records.size())
        file_.Fail(id.offset, b.name + ": an identification record without its data record");
      if (id.bytes() < 10 * w)
        file_.Fail(id.offset, b.name + ": an identification record of " + std::to_string(id.bytes()) +
                                  " bytes (at least 10 words)");
      std::vector<unsigned char> head(10 * w);
      file_.ReadPart(id, 0, head.data(), head.size(), b.name);
      const long long acode = file_.Int(head.data()), tcode = file_.Int(head.data() + w),
                      subcase = file_.Int(head.data() + 3 * w), mode = file_.Int(head.data() + 4 * w),
                      wide = file_.Int(head.data() + 9 * w);
      const std::string at = b.name + " (mode " + std::to_string(mode) + ")";
      if (acode / 10 == 9)
        file_.Fail(id.offset, at + ": complex eigenvectors (approach code 9, a complex eigenvalue analysis): deb "
                                   "reads real normal modes (SOL 103)");
      if (acode / 10 != 2)
        file_.Fail(id.offset, at + ": approach code " + std::to_string(acode / 10) +
                                   ", not real eigenvalues (2): deb reads the eigenvectors of a normal modes run "
                                   "(SOL 103)");
      if (tcode % 1000 != 7)
        file_.Fail(id.offset, at + ": table code " + std::to_string(tcode) + ", not eigenvectors (7)");
      if (tcode / 1000 != 0)
        file_.Fail(id.offset, at + ": table code " + std::to_string(tcode) +
                                   ": SORT2 or complex output; deb reads SORT1 real eigenvectors");
      if (wide != 8)
        file_.Fail(id.offset, at + ": " + std::to_string(wide) + " words per grid; real eigenvectors have 8 " +
                                   "(complex ones 14)");
      if (subcase0_ == 0) subcase0_ = subcase;
      if (subcase != subcase0_)
        file_.Fail(id.offset, at + ": subcase " + std::to_string(subcase) + " after subcase " +
                                   std::to_string(subcase0_) + ": deb reads the modes of one subcase");
      if (!data_of.emplace(mode, i + 1).second)
        file_.Fail(id.offset, at + ": mode " + std::to_string(mode) + " a second time");
      const LogicalRecord& data = b.records[i + 1];
      if (data.bytes() % (8 * w) != 0)
        file_.Fail(data.offset, at + ": a data record of " + std::to_string(data.bytes()) +
                                     " bytes, not a multiple of 8 words per grid");
    }
    num_wide_ = 8;
    for (const NastranMode& m : modes) {
      const auto it = data_of.find(m.number);
      if (it == data_of.end())
        file_.Fail(b.offset, b.name + " has no eigenvector of mode " + std::to_string(m.number) + " (of " +
                                 std::to_string(modes.size()) + " in LAMA)");
      data_.push_back(b.records[it->second]);
    }
  }

  // Searches the record for every grid in `rows`.
  void FindRows(const LogicalRecord& r, std::map<long long, Row>& rows, const std::vector<NastranDof>& dofs) const {
    const std::uint64_t w = file_.word(), row_bytes = num_wide_ * w;
    const std::vector<unsigned char> data = file_.Read(r, table);
    const std::uint64_t n = data.size() / row_bytes;
    for (auto& [grid, row] : rows) row.point_type = 0;
    std::vector<long long> grids;
    for (std::uint64_t i = 0; i < n; ++i) {
      const long long grid = file_.Int(data.data() + i * row_bytes) / 10;
      grids.push_back(grid);
      const auto it = rows.find(grid);
      if (it != rows.end() && it->second.point_type == 0)
        it->second = {i, static_cast<int>(file_.Int(data.data() + i * row_bytes + w))};
    }
    for (const NastranDof& d : dofs) {
      const Row& row = rows.at(d.grid);
      if (row.point_type == 0) throw InputError(file_.path() + ": " + MissingGridText(d, table, grids));
      if (row.point_type != 1 && d.component != 1)
        throw InputError(file_.path() + ": " + NastranDofText(d) + ": point " + std::to_string(d.grid) +
                         " is a scalar or extra point (type " + std::to_string(row.point_type) +
                         "), with one component: T1");
    }
  }

  Op2File file_;
  std::vector<LogicalRecord> data_;  // per mode of `modes`
  std::uint64_t num_wide_ = 8;
  long long subcase0_ = 0;
};

}  // namespace

std::unique_ptr<NastranModeFile::Reader> OpenOp2Modes(const std::string& path) {
  return std::make_unique<Op2Modes>(path);
}

}  // namespace deb::formats
