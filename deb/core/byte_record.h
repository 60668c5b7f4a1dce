// Internal: not part of the public API.
// A flat binary record of numbers and strings: results that the ranks of one
// run send each other (deb/distributed). Every rank runs the same build, so
// numbers are written in the machine's own byte order and sizes, exactly
// (no decimal round trip). A record read past its end or with a length that
// does not fit is a program error (DEB_DEMAND): the bytes come from deb.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "deb/core/error.h"

namespace deb {

class ByteWriter {
 public:
  void Int(std::int64_t v) { Raw(&v, sizeof v); }
  void Double(double v) { Raw(&v, sizeof v); }
  void Text(const std::string& s) {
    Int(static_cast<std::int64_t>(s.size()));
    bytes_.append(s);
  }
  void Doubles(const std::vector<double>& v) {
    Int(static_cast<std::int64_t>(v.size()));
    if (!v.empty()) Raw(v.data(), v.size() * sizeof(double));
  }
  const std::string& bytes() const { return bytes_; }

 private:
  void Raw(const void* p, std::size_t n) { bytes_.append(static_cast<const char*>(p), n); }
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  std::int64_t Int() {
    std::int64_t v = 0;
    Raw(&v, sizeof v);
    return v;
  }
  double Double() {
    double v = 0.0;
    Raw(&v, sizeof v);
    return v;
  }
  std::string Text() {
    const std::size_t n = Length(1);
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::vector<double> Doubles() {
    std::vector<double> v(Length(sizeof(double)));
    if (!v.empty()) Raw(v.data(), v.size() * sizeof(double));
    return v;
  }
  bool AtEnd() const { return at_ == bytes_.size(); }

 private:
  // A count of items of `size` bytes that the rest of the record holds.
  std::size_t Length(std::size_t size) {
    const std::int64_t n = Int();
    DEB_DEMAND(n >= 0 && static_cast<std::uint64_t>(n) <= (bytes_.size() - at_) / size);
    return static_cast<std::size_t>(n);
  }
  void Raw(void* p, std::size_t n) {
    DEB_DEMAND(n <= bytes_.size() - at_);
    std::memcpy(p, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

}  // namespace deb
