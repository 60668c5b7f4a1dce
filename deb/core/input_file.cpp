#include "deb/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <istream>

#include "deb/core/error.h"
#include "deb/core/limits.h"

namespace deb {
namespace {

std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string Bytes(std::uintmax_t n) {
  if (n >= (1ull << 30) && n % (1ull << 30) == 0) return std::to_string(n >> 30) + " GiB";
  if (n >= (1ull << 20) && n % (1ull << 20) == 0) return std::to_string(n >> 20) + " MiB";
  return std::to_string(n) + " bytes";
}

}  // namespace

std::uintmax_t RequireInputFile(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(path + ": cannot open " + what + " (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode))
    throw InputError(path + ": " + what + " is " + KindOf(st.st_mode) + "; deb reads regular files only");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw InputError(path + ": " + what + " holds " + std::to_string(st.st_size) + " bytes, more than the " +
                     Bytes(max_bytes) + " deb reads");
  return static_cast<std::uintmax_t>(st.st_size);
}

std::string ReadInputFile(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  const std::uintmax_t size = RequireInputFile(path, what, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + " (" + std::strerror(errno) + ")");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.gcount() != static_cast<std::streamsize>(text.size()))
    throw InputError(path + ": cannot read " + what + " (it changed or shrank while being read)");
  return text;
}

std::string ReadBoundedStream(std::istream& in, const std::string& name, std::uintmax_t max_bytes) {
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw InputError(name + ": holds more than the " + Bytes(max_bytes) + " deb reads");
  }
  return text;
}

TextLines::TextLines(const std::string& text, std::string name) : text_(text), name_(std::move(name)) {
  if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
}

bool TextLines::Next(std::string& line) {
  if (pos_ >= text_.size()) return false;
  ++line_;
  std::size_t end = text_.find_first_of("\r\n", pos_);
  if (end == std::string::npos) end = text_.size();
  if (end - pos_ > limits::kMaxLineBytes)
    throw InputError(name_ + ":" + std::to_string(line_) + ": the line is longer than " +
                     std::to_string(limits::kMaxLineBytes >> 20) + " MiB; is this a text table?");
  line.assign(text_, pos_, end - pos_);
  pos_ = end;
  if (pos_ < text_.size()) {  // past the line end: LF, CRLF or a lone CR
    const bool crlf = text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n';
    pos_ += crlf ? 2 : 1;
  }
  return true;
}

namespace {

// The length of the well-formed UTF-8 sequence at text[i], or 0.
std::size_t Utf8Length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  if (b < 0x80) return 1;
  // The lead byte gives the length and the range of the second byte
  // (which excludes overlong forms, surrogates and code points > U+10FFFF).
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  if (b >= 0xC2 && b <= 0xDF) n = 2;
  else if (b == 0xE0) n = 3, lo = 0xA0;
  else if (b >= 0xE1 && b <= 0xEC) n = 3;
  else if (b == 0xED) n = 3, hi = 0x9F;
  else if (b >= 0xEE && b <= 0xEF) n = 3;
  else if (b == 0xF0) n = 4, lo = 0x90;
  else if (b >= 0xF1 && b <= 0xF3) n = 4;
  else if (b == 0xF4) n = 4, hi = 0x8F;
  else return 0;
  if (i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

std::string Excerpt(const std::string& text, std::size_t max_chars) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && i < max_chars) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = Utf8Length(text, i);
    if (n > 1 && i + n <= max_chars) {
      out.append(text, i, n);
      i += n;
      continue;
    }
    if (n > 1) break;  // a character the cap would cut
    out += (n == 0 || c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
    ++i;
  }
  if (i < text.size()) out += "…";
  return out;
}

std::size_t FirstNonUtf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = Utf8Length(text, i);
    if (n == 0) return i;
    i += n;
  }
  return std::string::npos;
}

std::string Utf8Problem(const std::string& text) {
  const std::size_t at = FirstNonUtf8(text);
  if (at == std::string::npos) return "";
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", static_cast<unsigned>(static_cast<unsigned char>(text[at])));
  return std::string("byte ") + hex + " at character " + std::to_string(at + 1) + " is not UTF-8";
}

}  // namespace deb
