// Internal: not part of the public API.
// Files deb reads on the user's behalf (budgets, spectra, FRF tables,
// recordings, summaries). Every one is treated as possibly hostile: only a
// regular file is read (a FIFO would block forever, /dev/zero never ends, a
// directory is no table), its size is bounded, text lines are bounded, and a
// message quotes at most a short, printable excerpt of what the file holds.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

namespace deb {

// The whole content of the file at `path`. `what` names it in messages
// ("spectrum file").
// @throws InputError "<path>: ..." if it does not exist, is not a regular
//         file (naming what it is), cannot be read, or holds more than
//         `max_bytes`.
std::string ReadInputFile(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

// The same checks without reading, for a file a library opens itself (a
// MAT-file): its size in bytes.
// @throws InputError as ReadInputFile.
std::uintmax_t RequireInputFile(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

// The rest of a stream, at most `max_bytes` of it.
// @throws InputError "<name>: ..." if it holds more.
std::string ReadBoundedStream(std::istream& in, const std::string& name, std::uintmax_t max_bytes);

// Lines of a text: LF, CRLF and CR-only line ends alike, a UTF-8 byte-order
// mark before the first line dropped, each line at most limits::kMaxLineBytes.
// The text is not copied: it must outlive the TextLines.
class TextLines {
 public:
  TextLines(const std::string& text, std::string name);
  // The next line without its line end; false at the end of the text.
  // @throws InputError "name:line: ..." for a line longer than the limit.
  bool Next(std::string& line);
  int line_number() const { return line_; }

 private:
  const std::string& text_;
  std::string name_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

// `text` as a message may quote it: at most `max_chars` bytes (then "…"),
// never cutting a UTF-8 character, control bytes and bytes that are not
// UTF-8 as '?'. For cells of files.
std::string Excerpt(const std::string& text, std::size_t max_chars = 40);

// The position of the first byte of `text` that is not part of well-formed
// UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing above
// U+10FFFF), or std::string::npos.
std::size_t FirstNonUtf8(const std::string& text);

// "" if `text` is UTF-8, else the rule it breaks, for a message: "byte 0xe9
// at character 4 is not UTF-8". Every text deb
// reads from a file (YAML scalars, table headers and names, a store's text,
// a MAT-file's names) is checked with it where it is read: summary.json and
// every other file deb writes are UTF-8.
std::string Utf8Problem(const std::string& text);

}  // namespace deb
