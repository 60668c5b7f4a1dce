// Writes OP2 files of normal modes (an eigenvalue table LAMA and
// eigenvectors OUGV1) in either byte order and word size, as Nastran lays
// them out (deb/formats/nastran_op2.cpp describes the layout), for the
// readers' tests and the OP2 benchmark. Values are given by a function, so
// that a file of gigabytes is written without holding it.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace deb::test {

struct Op2Layout {
  bool big_endian = false;
  int word = 4;         // bytes per word: 4 (float32, int32) or 8 (float64, int64)
  bool header = true;   // the file's header (date, tape code, label) before the blocks
  bool eigenvalues = true;   // write LAMA
  bool eigenvectors = true;  // write OUGV1
  long long approach_code = 2;  // 2 real eigenvalues, 9 complex
  long long num_wide = 8;       // words per grid
};

struct Op2Mode {
  long long number = 0;
  double eigenvalue = 0, radians = 0, cycles = 0, generalized_mass = 1, generalized_stiffness = 0;
};

class Op2Writer {
 public:
  Op2Writer(const std::string& path, const Op2Layout& layout)
      : out_(path, std::ios::binary | std::ios::trunc), layout_(layout) {
    if (!out_) throw std::runtime_error("cannot write " + path);
  }

  // A Fortran record: its length, the bytes, its length.
  void Record(const std::vector<unsigned char>& bytes) {
    Marker(static_cast<std::uint32_t>(bytes.size()));
    out_.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    Marker(static_cast<std::uint32_t>(bytes.size()));
  }
  void Key(long long k) {
    std::vector<unsigned char> b;
    Int(b, k);
    Record(b);
  }
  void Int(std::vector<unsigned char>& b, long long v) const {
    if (layout_.word == 4) {
      const std::int32_t s = static_cast<std::int32_t>(v);
      Append(b, &s, 4);
    } else {
      const std::int64_t s = v;
      Append(b, &s, 8);
    }
  }
  void Real(std::vector<unsigned char>& b, double v) const {
    if (layout_.word == 4) {
      const float f = static_cast<float>(v);
      Append(b, &f, 4);
    } else {
      Append(b, &v, 8);
    }
  }
  // 8 characters, in 2 words (each 4 characters, blank-padded to the word).
  void Text8(std::vector<unsigned char>& b, const std::string& name) const {
    std::string n = name;
    n.resize(8, ' ');
    for (int w = 0; w < 2; ++w) {
      std::string part = n.substr(static_cast<std::size_t>(4 * w), 4);
      part.resize(static_cast<std::size_t>(layout_.word), ' ');
      b.insert(b.end(), part.begin(), part.end());
    }
  }

  void Header() {
    Key(3);
    std::vector<unsigned char> date;
    for (long long v : {12, 6, 26}) Int(date, v);
    Record(date);
    Key(7);
    const std::string tape = "NASTRAN FORT TAPE ID CODE - ";
    Record(std::vector<unsigned char>(tape.begin(), tape.end()));
    Key(2);
    std::vector<unsigned char> label;
    Text8(label, "XXXXXXXX");
    Record(label);
    Key(-1);
    Key(0);
  }

  // A data block: name, trailer, then each record of `records`.
  void Block(const std::string& name, const std::vector<std::vector<unsigned char>>& records) {
    BeginBlock(name);
    for (const auto& r : records) BlockRecord(r);
    EndBlock();
  }
  void BeginBlock(const std::string& name) {
    Key(2);
    std::vector<unsigned char> n;
    Text8(n, name);
    Record(n);
    Key(-1);
    Key(7);
    std::vector<unsigned char> trailer;
    for (long long v : {101, 0, 0, 0, 0, 0, 1}) Int(trailer, v);
    Record(trailer);
    Key(-2);
    Key(1);
    Key(0);
    next_ = -3;
  }
  void BlockRecord(const std::vector<unsigned char>& r) {
    Key(static_cast<long long>(r.size()) / layout_.word);
    Record(r);
    Key(next_--);
    Key(1);
    Key(0);
  }
  void EndBlock() { Key(0); }
  void End() {
    Key(0);
    out_.flush();
    if (!out_) throw std::runtime_error("writing an OP2 file failed");
  }

  std::vector<unsigned char> Ident(long long acode, long long tcode, long long mode, double eigenvalue,
                                   long long num_wide) const {
    std::vector<unsigned char> b;
    for (int w = 0; w < 146; ++w) {
      if (w == 5)
        Real(b, eigenvalue);
      else
        Int(b, w == 0 ? acode : w == 1 ? tcode : w == 3 ? 1 : w == 4 ? mode : w == 8 ? 1 : w == 9 ? num_wide : 0);
    }
    return b;
  }

  const Op2Layout& layout() const { return layout_; }

 private:
  void Append(std::vector<unsigned char>& b, const void* v, int n) const {
    unsigned char bytes[8];
    std::memcpy(bytes, v, static_cast<std::size_t>(n));
    if (layout_.big_endian != BigEndianHost())
      for (int i = 0; i < n / 2; ++i) std::swap(bytes[i], bytes[n - 1 - i]);
    b.insert(b.end(), bytes, bytes + n);
  }
  void Marker(std::uint32_t len) {
    unsigned char bytes[4];
    std::memcpy(bytes, &len, 4);
    if (layout_.big_endian != BigEndianHost()) {
      std::swap(bytes[0], bytes[3]);
      std::swap(bytes[1], bytes[2]);
    }
    out_.write(reinterpret_cast<const char*>(bytes), 4);
  }
  static bool BigEndianHost() {
    const std::uint32_t one = 1;
    unsigned char b;
    std::memcpy(&b, &one, 1);
    return b == 0;
  }

  std::ofstream out_;
  Op2Layout layout_;
  long long next_ = -3;
};

// A normal-modes OP2 file: LAMA of `modes` and OUGV1 of the points `grids`
// (point type 1, a grid, unless listed in `scalar_points`), mode k's value at
// grid index g and component c (0..5) given by shape(k, g, c).
inline void WriteModesOp2(const std::string& path, const Op2Layout& layout, const std::vector<Op2Mode>& modes,
                          const std::vector<long long>& grids,
                          const std::function<double(std::size_t, std::size_t, int)>& shape,
                          const std::vector<long long>& scalar_points = {}) {
  Op2Writer w(path, layout);
  if (layout.header) w.Header();
  if (layout.eigenvalues) {
    std::vector<unsigned char> head, data;
    w.Text8(head, "LAMAS0");
    for (const Op2Mode& m : modes) {
      w.Int(data, m.number);
      w.Int(data, m.number);
      for (double v : {m.eigenvalue, m.radians, m.cycles, m.generalized_mass, m.generalized_stiffness}) w.Real(data, v);
    }
    w.Block("LAMA", {head, w.Ident(21, 6, 0, 0.0, 7), data});
  }
  if (layout.eigenvectors) {
    w.BeginBlock("OUGV1");
    std::vector<unsigned char> head;
    w.Text8(head, "OUG1");
    w.BlockRecord(head);
    std::vector<unsigned char> data;
    for (std::size_t k = 0; k < modes.size(); ++k) {
      w.BlockRecord(w.Ident(layout.approach_code * 10 + 1, 7, modes[k].number, modes[k].eigenvalue, layout.num_wide));
      data.clear();
      for (std::size_t g = 0; g < grids.size(); ++g) {
        bool scalar = false;
        for (long long s : scalar_points) scalar = scalar || s == grids[g];
        w.Int(data, grids[g] * 10 + 1);
        w.Int(data, scalar ? 2 : 1);
        for (int c = 0; c < 6; ++c) w.Real(data, scalar && c > 0 ? 0.0 : shape(k, g, c));
        for (long long extra = 8; extra < layout.num_wide; ++extra) w.Real(data, 0.0);
      }
      w.BlockRecord(data);
    }
    w.EndBlock();
  }
  w.End();
}

}  // namespace deb::test
