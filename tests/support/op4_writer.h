// Writes Nastran OUTPUT4 files of real double matrices, in text (1P,3E23.16)
// or binary (Fortran records in either byte order, 4- or 8-byte words), in
// Nastran's dense layout (deb/formats/op4_file.h describes it), for the
// readers' tests. tests/formats/op4_file_test.cpp checks that they
// reproduce the bytes Nastran wrote for a fixture's matrix.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace deb::test {

using Matrices = std::vector<std::pair<std::string, Eigen::MatrixXd>>;

// Nastran's form: 1 square, 2 rectangular.
inline int FormOf(const Eigen::MatrixXd& m) { return m.rows() == m.cols() ? 1 : 2; }

// `v` as Fortran's 1PE23.16 prints it: 17 significant digits, and a
// 3-digit exponent without its E (-2.2500000000000000-300).
inline std::string FortranE23(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.16E", v);
  std::string s = buffer;
  const std::size_t e = s.find('E');
  if (s.size() - e == 5) s.erase(e, 1);
  return std::string(23 - std::min<std::size_t>(23, s.size()), ' ') + s;
}

// Real double matrices in the dense text layout, as Nastran writes them
// (1P,3E23.16: 17 significant digits, which read back exactly); `form`
// overrides FormOf. Each column from its first to its last nonzero row.
inline std::string TextOp4(const Matrices& matrices, int form = 0) {
  std::string out;
  char buffer[128];
  for (const auto& [name, m] : matrices) {
    std::snprintf(buffer, sizeof buffer, "%8d%8d%8d%8d%-8s1P,3E23.16\n", static_cast<int>(m.cols()),
                  static_cast<int>(m.rows()), form ? form : FormOf(m), 2, name.c_str());
    out += buffer;
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      Eigen::Index first = 0, last = m.rows() - 1;
      while (first < m.rows() && m(first, j) == 0) ++first;
      if (first == m.rows()) continue;
      while (m(last, j) == 0) --last;
      std::snprintf(buffer, sizeof buffer, "%8d%8d%8d\n", static_cast<int>(j + 1), static_cast<int>(first + 1),
                    static_cast<int>(last - first + 1));
      out += buffer;
      for (Eigen::Index i = first; i <= last; ++i) {
        out += FortranE23(m(i, j));
        if ((i - first) % 3 == 2 || i == last) out += "\n";
      }
    }
    std::snprintf(buffer, sizeof buffer, "%8d%8d%8d\n", static_cast<int>(m.cols() + 1), 1, 1);
    out += buffer + FortranE23(1.0) + "\n";
  }
  return out;
}

// The same in binary: Fortran records in either byte order, of 4- or
// 8-byte words.
class BinaryWriter {
 public:
  BinaryWriter(bool little_endian, int word_bytes) : little_(little_endian), word_(word_bytes) {}

  std::string File(const Matrices& matrices, int form = 0) {
    std::string out;
    for (const auto& [name, m] : matrices) {
      std::string header = Int(m.cols()) + Int(m.rows()) + Int(form ? form : FormOf(m)) + Int(2);
      std::string padded = name;
      padded.resize(static_cast<std::size_t>(2 * word_), ' ');
      out += Record(header + padded);
      for (Eigen::Index j = 0; j < m.cols(); ++j) {
        Eigen::Index first = 0, last = m.rows() - 1;
        while (first < m.rows() && m(first, j) == 0) ++first;
        if (first == m.rows()) continue;
        while (m(last, j) == 0) --last;
        const Eigen::Index count = last - first + 1;
        std::string column = Int(j + 1) + Int(first + 1) + Int(count * (word_ == 4 ? 2 : 1));
        for (Eigen::Index i = first; i <= last; ++i) column += Double(m(i, j));
        out += Record(column);
      }
      out += Record(Int(m.cols() + 1) + Int(1) + Int(1) + Double(1.0));
    }
    return out;
  }

  std::string Bytes(std::uint64_t v, int n) const {
    std::string s(static_cast<std::size_t>(n), '\0');
    for (int i = 0; i < n; ++i) s[static_cast<std::size_t>(little_ ? i : n - 1 - i)] = static_cast<char>(v >> (8 * i) & 0xFF);
    return s;
  }
  std::string Int(std::int64_t v) const { return Bytes(static_cast<std::uint64_t>(v), word_); }
  std::string Double(double v) const {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, 8);
    return Bytes(u, 8);
  }
  std::string Record(const std::string& data) const {
    const std::string length = Bytes(data.size(), 4);
    return length + data + length;
  }

 private:
  bool little_;
  int word_;
};

}  // namespace deb::test
