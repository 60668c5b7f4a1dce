#include "deb/formats/op4_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/core/suggest.h"

namespace deb::formats {
namespace {

// IS = row + 65536 (length + 1): the packed string header of the sparse layout.
constexpr std::int64_t kIsRowSpan = 65536;
// The largest column or row count: ncol + 1 (the end of a matrix) must fit an int.
constexpr std::int64_t kMaxCount = std::numeric_limits<int>::max() - 1;

std::string Quoted(const std::string& name) { return "'" + Excerpt(name) + "'"; }

std::string Count(std::int64_t n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

// True if line[from, end) is blank.
bool BlankFrom(const std::string& line, std::size_t from) {
  for (std::size_t i = from; i < line.size(); ++i)
    if (!IsBlank(line[i])) return false;
  return true;
}

std::string_view Trimmed(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

// An integer with blanks around it (a leading + allowed); nullopt for
// anything else, or one longer than 19 characters.
std::optional<std::int64_t> ParseInt(std::string_view text) {
  text = Trimmed(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.size() > 19) return std::nullopt;
  std::int64_t v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

// The integer in the `width` characters of `line` from `from`; nullopt if
// the line is shorter or the field holds anything else.
std::optional<std::int64_t> FixedInt(const std::string& line, std::size_t from, std::size_t width) {
  if (line.size() < from + width) return std::nullopt;
  return ParseInt(std::string_view(line).substr(from, width));
}

// A Fortran E or D field: blanks around it, D (or d) for E, and the form
// Fortran prints for a 3-digit exponent, 1.0-100 for 1.0E-100. False for
// anything else (the value may then be inf or NaN: from_chars reads them).
bool ParseFortranReal(std::string_view field, double* value) {
  field = Trimmed(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty() || field.size() > 64) return false;
  char buffer[72];
  std::size_t n = 0;
  bool exponent = false;
  for (std::size_t i = 0; i < field.size(); ++i) {
    char c = field[i];
    if (c == 'D' || c == 'd' || c == 'E' || c == 'e') {
      c = 'E';
      exponent = true;
    } else if ((c == '+' || c == '-') && i > 0 && !exponent &&
               (std::isdigit(static_cast<unsigned char>(field[i - 1])) || field[i - 1] == '.')) {
      buffer[n++] = 'E';
      exponent = true;
    }
    buffer[n++] = c;
  }
  const auto r = std::from_chars(buffer, buffer + n, *value);
  return r.ec == std::errc() && r.ptr == buffer + n;
}

// The header's integers, as read, against the rules both encodings share;
// "" if they keep them.
std::string HeaderProblem(std::int64_t ncol, std::int64_t nrow, std::int64_t form, std::int64_t type) {
  if (ncol < 1 || ncol > kMaxCount)
    return "ncol " + std::to_string(ncol) + " is not a column count (1 to " + std::to_string(kMaxCount) + ")";
  if (nrow == 0 || nrow > kMaxCount || nrow < -kMaxCount)
    return "nrow " + std::to_string(nrow) + " is not a row count (1 to " + std::to_string(kMaxCount) +
           ", negative for the bigmat layout)";
  if (form < std::numeric_limits<int>::min() || form > std::numeric_limits<int>::max())
    return "form " + std::to_string(form) + " is not a Nastran matrix form";
  if (type < 1 || type > 4)
    return "unknown type " + std::to_string(type) +
           " (1 real single, 2 real double, 3 complex single, 4 complex double precision)";
  return "";
}

// "" if `name` (its padding removed) is a matrix name: printable ASCII
// without blanks, as Nastran writes names.
std::string NameProblem(const std::string& name) {
  if (name.empty()) return "the header gives no matrix name";
  for (const char c : name)
    if (c < 0x21 || c > 0x7E) return "the matrix name " + Quoted(name) + " is not printable ASCII without blanks";
  return "";
}

// Where a matrix's values go: a real matrix, a complex one, or nowhere
// while the file is checked.
struct Target {
  Eigen::MatrixXd* real = nullptr;
  Eigen::MatrixXcd* complex = nullptr;
};

// One run of numbers (a dense column, or a string of a sparse one) down
// column `col` from `row` (both from 0): a number per row, or (real,
// imaginary) pairs for a complex matrix.
class Run {
 public:
  Run(const Target& into, bool complex, std::int64_t row, std::int64_t col)
      : into_(into), complex_(complex), row_(static_cast<Eigen::Index>(row)), col_(static_cast<Eigen::Index>(col)) {}
  void Add(double v) {
    if (complex_ && imaginary_) {
      if (into_.complex) (*into_.complex)(row_, col_).imag(v);
      imaginary_ = false;
      ++row_;
      return;
    }
    if (into_.real) (*into_.real)(row_, col_) = v;
    if (into_.complex) (*into_.complex)(row_, col_).real(v);
    if (complex_) imaginary_ = true;
    else ++row_;
  }
  // The row (from 1) and part the next number goes to, for a message.
  std::string Where() const {
    return "column " + std::to_string(col_ + 1) + ", row " + std::to_string(row_ + 1) +
           (complex_ ? (imaginary_ ? " (imaginary part)" : " (real part)") : "");
  }

 private:
  Target into_;
  bool complex_;
  Eigen::Index row_, col_;
  bool imaginary_ = false;
};

// The rules of a matrix's columns that both encodings share. Each check
// returns "" or the rule broken.
class ColumnRules {
 public:
  // `words_per_number`: 2 for double precision in 4-byte words, else 1.
  ColumnRules(const Op4Matrix& m, int words_per_number) : m_(m), words_per_number_(words_per_number) {}

  int words_per_number() const { return words_per_number_; }

  // A column record's number, before its values.
  std::string Column(std::int64_t col) {
    if (col < 1 || col > m_.cols)
      return "column " + std::to_string(col) + " is out of range: the matrix has " + Count(m_.cols, "column") +
             ", and column " + std::to_string(std::int64_t{m_.cols} + 1) + " ends it";
    if (col <= col_)
      return "column " + std::to_string(col) + " follows column " + std::to_string(col_) +
             ": columns must come in increasing order";
    col_ = col;
    last_row_ = 0;
    return "";
  }

  // A string of `words` words: a whole number of values.
  std::string Words(std::int64_t words) const {
    if (words < 1) return "a string of " + Count(words, "word") + " holds no value";
    if (words % words_per_number_ != 0)
      return "a string of " + Count(words, "word") + " is no whole number of double precision values (2 words each)";
    return "";
  }

  // A run of `numbers` numbers from `row` (from 1) down the current column.
  std::string Rows(std::int64_t row, std::int64_t numbers) {
    if (numbers < 1) return "column " + std::to_string(col_) + ": a run of " + Count(numbers, "number") + " holds no value";
    if (m_.complex() && numbers % 2 != 0)
      return "column " + std::to_string(col_) + ": " + Count(numbers, "number") +
             " for a complex matrix, whose values are (real, imaginary) pairs";
    const std::int64_t values = m_.complex() ? numbers / 2 : numbers;
    if (row < 1) return "column " + std::to_string(col_) + ": first row " + std::to_string(row) + " (rows count from 1)";
    if (row <= last_row_)
      return "column " + std::to_string(col_) + ": a string at row " + std::to_string(row) +
             " after one that ends at row " + std::to_string(last_row_) + ": strings must come in increasing order";
    if (row - 1 > m_.rows - values)
      return "column " + std::to_string(col_) + ": " + Count(values, "value") + " from row " + std::to_string(row) +
             " pass the last row: the matrix has " + Count(m_.rows, "row");
    last_row_ = row - 1 + values;
    return "";
  }

  std::int64_t col() const { return col_; }

 private:
  const Op4Matrix& m_;
  int words_per_number_;
  std::int64_t col_ = 0;
  std::int64_t last_row_ = 0;
};

bool Bigmat(std::int64_t nrow) { return nrow < 0 || nrow >= kIsRowSpan; }

// The string header of a sparse column: its first row, its words of values
// and the words it takes with its header.
struct StringHeader {
  std::int64_t row = 0, words = 0, used = 0;
};

// From IS = row + 65536 (length + 1), or bigmat's (length + 1, row).
StringHeader Unpacked(std::int64_t is) {
  const std::int64_t length = is / kIsRowSpan - 1;
  return {is % kIsRowSpan, length, length + 1};
}
StringHeader BigmatString(std::int64_t length_plus_one, std::int64_t row) {
  return {row, length_plus_one - 1, length_plus_one + 1};
}

// ---------------------------------------------------------------------------
// Text files.

class TextReader {
 public:
  TextReader(const std::string& content, const std::string& path) : lines_(content, path), path_(path) {}

  // The next matrix's header (number `index` from 1); false at the end.
  bool Header(std::size_t index, Op4Matrix& m) {
    matrix_.clear();
    do {
      if (!lines_.Next(line_)) return false;
    } while (BlankFrom(line_, 0));
    const std::string about = "matrix " + std::to_string(index) + "'s header: ";
    if (line_.size() < 40)
      Fail(1, about + "a header holds ncol, nrow, form and type in four 8-character fields, the name in columns 33-40 "
                      "and the format of the numbers (e.g. 1P,3E23.16); this line holds " +
                  Count(static_cast<std::int64_t>(line_.size()), "character") + ": " + Quoted(line_) +
                  (index == 1 ? "; is this an OP4 file?" : ""));
    static const char* const kFields[] = {"ncol", "nrow", "form", "type"};
    std::int64_t v[4];
    for (int k = 0; k < 4; ++k) {
      const auto field = FixedInt(line_, 8 * k, 8);
      if (!field)
        Fail(8 * k + 1, about + "columns " + std::to_string(8 * k + 1) + "-" + std::to_string(8 * k + 8) +
                            " hold its " + kFields[k] + ", an integer, not " + Quoted(line_.substr(8 * k, 8)) +
                            (index == 1 ? "; is this an OP4 file?" : ""));
      v[k] = *field;
    }
    if (const std::string problem = HeaderProblem(v[0], v[1], v[2], v[3]); !problem.empty()) Fail(1, about + problem);
    m.name = std::string(Trimmed(std::string_view(line_).substr(32, 8)));
    if (const std::string problem = NameProblem(m.name); !problem.empty()) Fail(33, about + problem + " (columns 33-40)");
    m.cols = static_cast<int>(v[0]);
    m.rows = static_cast<int>(std::abs(v[1]));
    m.form = static_cast<int>(v[2]);
    m.type = static_cast<int>(v[3]);
    bigmat_ = Bigmat(v[1]);
    matrix_ = m.name;
    Format(std::string(Trimmed(std::string_view(line_).substr(40))));
    return true;
  }

  // The columns of the matrix whose header was read last, into `into`.
  void Body(const Op4Matrix& m, const Target& into) {
    // A text file counts a sparse string's words as a binary file of 4-byte words does.
    ColumnRules rules(m, m.type % 2 == 0 ? 2 : 1);
    for (;;) {
      NextOrEnd(m, rules);
      std::int64_t v[3];
      static const char* const kFields[] = {"column number", "first row", "word count"};
      for (int k = 0; k < 3; ++k) {
        const auto field = FixedInt(line_, 8 * k, 8);
        if (!field)
          Fail(8 * k + 1, "a column record holds its column number, first row and word count in three 8-character "
                          "fields; columns " + std::to_string(8 * k + 1) + "-" + std::to_string(8 * k + 8) +
                              " should hold its " + kFields[k] + ", not " + Quoted(line_.substr(8 * k, 8)));
        v[k] = *field;
      }
      if (!BlankFrom(line_, 24)) Fail(25, "characters after a column record's three fields: " + Quoted(line_.substr(24)));
      const std::int64_t col = v[0], row = v[1], words = v[2];
      if (col == std::int64_t{m.cols} + 1) {
        // The end of the matrix. Its value lines are skipped unread: Nastran
        // writes them in another width than the header's format at times.
        if (words < 0) Fail(17, "the end record's word count " + std::to_string(words) + " is negative");
        const auto per_line = static_cast<std::int64_t>(per_line_);
        for (std::int64_t line = 0; line < (words + per_line - 1) / per_line; ++line) NextOrEnd(m, rules);
        return;
      }
      if (const std::string problem = rules.Column(col); !problem.empty()) Fail(1, problem);
      if (row > 0) {  // dense: the record counts its numbers
        if (const std::string problem = rules.Rows(row, words); !problem.empty()) Fail(9, problem);
        Run run(into, m.complex(), row - 1, col - 1);
        Numbers(words, run, m, rules);
      } else if (row == 0) {
        Sparse(m, rules, into, col, words);
      } else {
        Fail(9, "column " + std::to_string(col) + ": first row " + std::to_string(row) +
                    " (0 starts a sparse column, a row from 1 a dense one)");
      }
    }
  }

 private:
  [[noreturn]] void Fail(std::size_t column, const std::string& message) const {
    throw InputError(path_ + ":" + std::to_string(lines_.line_number()) + ":" + std::to_string(column) + ": " +
                     (matrix_.empty() ? "" : "matrix " + Quoted(matrix_) + ": ") + message);
  }

  // The next line inside the matrix.
  void NextOrEnd(const Op4Matrix& m, const ColumnRules& rules) {
    if (lines_.Next(line_)) return;
    throw InputError(path_ + ":" + std::to_string(lines_.line_number()) + ": matrix " + Quoted(matrix_) +
                     ": the file ends inside the matrix" +
                     (rules.col() > 0 ? ", in or after column " + std::to_string(rules.col()) : "") +
                     " (a column number of ncol + 1 = " + std::to_string(std::int64_t{m.cols} + 1) +
                     " ends a matrix); is it truncated?");
  }

  // The header's number format: [nP,]kEw.d or kDw.d, possibly in parentheses.
  void Format(const std::string& text) {
    std::string f;
    for (const char c : text)
      if (!IsBlank(c)) f += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (!f.empty() && f.front() == '(' && f.back() == ')') f = f.substr(1, f.size() - 2);
    // An optional scale factor before P ("1P,").
    const std::size_t p = f.find('P');
    const bool scale = p == std::string::npos || ParseInt(f.substr(0, p)).has_value();
    if (p != std::string::npos) f = f.substr(f.compare(p + 1, 1, ",") == 0 ? p + 2 : p + 1);
    const std::size_t e = f.find_first_of("ED"), dot = f.find('.');
    const bool parts = e != std::string::npos && dot != std::string::npos && e < dot;
    const auto per_line = parts ? ParseInt(f.substr(0, e)) : std::nullopt;
    const auto width = parts ? ParseInt(f.substr(e + 1, dot - e - 1)) : std::nullopt;
    const auto digits = parts ? ParseInt(f.substr(dot + 1)) : std::nullopt;
    if (!scale || !per_line || !width || !digits || *per_line < 1 || *per_line > 999 || *width < 2 || *width > 64 ||
        *digits < 0 || *digits >= *width)
      Fail(41, "the header's number format " + Quoted(text) +
                   " (from column 41) is not a Fortran format such as 1P,3E23.16 (3 numbers of 23 characters a line)");
    per_line_ = static_cast<std::size_t>(*per_line);
    width_ = static_cast<std::size_t>(*width);
  }

  // A sparse column's strings, `words` words in all.
  void Sparse(const Op4Matrix& m, ColumnRules& rules, const Target& into, std::int64_t col, std::int64_t words) {
    if (words < 1) Fail(17, "column " + std::to_string(col) + ": a sparse column of " + Count(words, "word"));
    for (std::int64_t left = words; left > 0;) {
      NextOrEnd(m, rules);
      StringHeader s;
      if (bigmat_) {
        const auto length = FixedInt(line_, 0, 8), row = FixedInt(line_, 8, 8);
        if (!length || !row || !BlankFrom(line_, 16))
          Fail(1, "column " + std::to_string(col) + ": a bigmat string starts with its length + 1 and its first row "
                  "in two 8-character fields, not " + Quoted(line_));
        s = BigmatString(*length, *row);
      } else {
        const auto is = ParseInt(line_);
        if (!is || *is < 0)
          Fail(1, "column " + std::to_string(col) + ": a sparse string starts with IS = row + 65536 (length + 1) "
                  "alone on its line, not " + Quoted(line_));
        s = Unpacked(*is);
      }
      if (const std::string problem = rules.Words(s.words); !problem.empty())
        Fail(1, "column " + std::to_string(col) + ": " + problem);
      if (s.used > left)
        Fail(1, "column " + std::to_string(col) + ": its strings hold more words than the " +
                    std::to_string(words) + " its record gives");
      const std::int64_t numbers = s.words / rules.words_per_number();
      if (const std::string problem = rules.Rows(s.row, numbers); !problem.empty()) Fail(1, problem);
      Run run(into, m.complex(), s.row - 1, col - 1);
      Numbers(numbers, run, m, rules);
      left -= s.used;
    }
  }

  // `count` numbers from the next line on, per_line_ a line, into `run`.
  void Numbers(std::int64_t count, Run& run, const Op4Matrix& m, const ColumnRules& rules) {
    for (std::int64_t left = count; left > 0;) {
      NextOrEnd(m, rules);
      const std::size_t here = static_cast<std::size_t>(std::min<std::int64_t>(left, static_cast<std::int64_t>(per_line_)));
      for (std::size_t j = 0; j < here; ++j) {
        const std::size_t at = j * width_;
        if (line_.size() < at + width_)
          Fail(std::min(line_.size(), at) + 1,
               "the line holds " + Count(static_cast<std::int64_t>(j), "number") + " of the " + std::to_string(here) +
                   " expected here (the header's format: " + std::to_string(per_line_) + " numbers of " +
                   std::to_string(width_) + " characters a line)");
        const std::string_view field = std::string_view(line_).substr(at, width_);
        double v = 0;
        if (!ParseFortranReal(field, &v))
          Fail(at + 1, run.Where() + ": " + Quoted(std::string(field)) + " is not a number (a Fortran E or D field of " +
                           std::to_string(width_) + " characters)");
        if (!std::isfinite(v)) Fail(at + 1, run.Where() + ": " + Quoted(std::string(field)) + " is not finite");
        run.Add(v);
      }
      if (!BlankFrom(line_, here * width_))
        Fail(here * width_ + 1, "characters after the " + Count(static_cast<std::int64_t>(here), "number") +
                                    " expected on this line: " + Quoted(line_.substr(here * width_)));
      left -= static_cast<std::int64_t>(here);
    }
  }

  TextLines lines_;
  std::string path_;
  std::string line_;
  std::string matrix_;  // the name of the matrix being read, for messages
  bool bigmat_ = false;
  std::size_t per_line_ = 0, width_ = 0;
};

// ---------------------------------------------------------------------------
// Binary files.

class BinaryReader {
 public:
  BinaryReader(const std::string& content, const std::string& path, bool little_endian, int word_bytes)
      : data_(content), path_(path), little_(little_endian), word_(static_cast<std::size_t>(word_bytes)) {}

  bool Header(std::size_t index, Op4Matrix& m) {
    matrix_.clear();
    if (!Next()) return false;
    const std::string about = "matrix " + std::to_string(index) + "'s header: ";
    if (bytes_ != 6 * word_)
      Fail(at_, about + "a header record holds 6 words of " + std::to_string(word_) +
                    " bytes (ncol, nrow, form, type and the name in two), " + std::to_string(6 * word_) +
                    " bytes, not " + std::to_string(bytes_));
    const std::int64_t ncol = Int(data_at_), nrow = Int(data_at_ + word_), form = Int(data_at_ + 2 * word_),
                       type = Int(data_at_ + 3 * word_);
    if (const std::string problem = HeaderProblem(ncol, nrow, form, type); !problem.empty())
      Fail(data_at_, about + problem);
    m.name.clear();
    for (std::size_t i = data_at_ + 4 * word_; i < data_at_ + 6 * word_; ++i)
      if (data_[i] != ' ' && data_[i] != '\0') m.name += data_[i];
    if (const std::string problem = NameProblem(m.name); !problem.empty()) Fail(data_at_ + 4 * word_, about + problem);
    m.cols = static_cast<int>(ncol);
    m.rows = static_cast<int>(std::abs(nrow));
    m.form = static_cast<int>(form);
    m.type = static_cast<int>(type);
    bigmat_ = Bigmat(nrow);
    matrix_ = m.name;
    return true;
  }

  void Body(const Op4Matrix& m, const Target& into) {
    // In 8-byte words every number is one word (single precision is stored as double).
    const bool double_precision = word_ == 8 || m.type % 2 == 0;
    ColumnRules rules(m, word_ == 4 && double_precision ? 2 : 1);
    const std::size_t number_bytes = double_precision ? 8 : 4;
    for (;;) {
      if (!Next())
        Fail(data_.size(), "the file ends inside the matrix" +
                               (rules.col() > 0 ? ", after column " + std::to_string(rules.col()) : std::string()) +
                               " (a column number of ncol + 1 = " + std::to_string(std::int64_t{m.cols} + 1) +
                               " ends a matrix); is it truncated?");
      if (bytes_ < 3 * word_)
        Fail(at_, "a column record holds at least 3 words (column number, first row, word count) of " +
                      std::to_string(word_) + " bytes, this one " + Count(static_cast<std::int64_t>(bytes_), "byte"));
      const std::int64_t col = Int(data_at_), row = Int(data_at_ + word_), words = Int(data_at_ + 2 * word_);
      if (col == std::int64_t{m.cols} + 1) return;  // the end of the matrix; its value is skipped
      if (const std::string problem = rules.Column(col); !problem.empty()) Fail(data_at_, problem);
      const std::size_t first = data_at_ + 3 * word_, payload = bytes_ - 3 * word_;
      if (words < 1 || static_cast<std::uint64_t>(words) != payload / word_ || payload % word_ != 0)
        Fail(data_at_ + 2 * word_, "column " + std::to_string(col) + ": the word count " + std::to_string(words) +
                                       " does not match the record, which holds " +
                                       Count(static_cast<std::int64_t>(payload), "byte") + " of values (words of " +
                                       std::to_string(word_) + " bytes)");
      if (row > 0) {
        if (words % rules.words_per_number() != 0)
          Fail(data_at_ + 2 * word_, "column " + std::to_string(col) + ": " + Count(words, "word") +
                                         " are no whole number of double precision values (2 words each)");
        const std::int64_t numbers = words / rules.words_per_number();
        if (const std::string problem = rules.Rows(row, numbers); !problem.empty()) Fail(data_at_ + word_, problem);
        Numbers(first, numbers, number_bytes, Run(into, m.complex(), row - 1, col - 1));
      } else if (row == 0) {
        std::size_t at = first;
        for (std::int64_t left = words; left > 0;) {
          const std::int64_t header_words = bigmat_ ? 2 : 1;
          if (left < header_words)
            Fail(at, "column " + std::to_string(col) + ": the record ends inside a string's header");
          if (!bigmat_ && Int(at) < 0) Fail(at, "column " + std::to_string(col) + ": a negative string header IS");
          const StringHeader s = bigmat_ ? BigmatString(Int(at), Int(at + word_)) : Unpacked(Int(at));
          if (const std::string problem = rules.Words(s.words); !problem.empty())
            Fail(at, "column " + std::to_string(col) + ": " + problem);
          if (s.used > left)
            Fail(at, "column " + std::to_string(col) + ": its strings hold more words than the " +
                         std::to_string(words) + " its record gives");
          const std::int64_t numbers = s.words / rules.words_per_number();
          if (const std::string problem = rules.Rows(s.row, numbers); !problem.empty()) Fail(at, problem);
          Numbers(at + static_cast<std::size_t>(header_words) * word_, numbers, number_bytes,
                  Run(into, m.complex(), s.row - 1, col - 1));
          at += static_cast<std::size_t>(s.used) * word_;
          left -= s.used;
        }
      } else {
        Fail(data_at_ + word_, "column " + std::to_string(col) + ": first row " + std::to_string(row) +
                                   " (0 starts a sparse column, a row from 1 a dense one)");
      }
    }
  }

 private:
  [[noreturn]] void Fail(std::size_t byte, const std::string& message) const {
    throw InputError(path_ + ": byte " + std::to_string(byte) + ": " +
                     (matrix_.empty() ? "" : "matrix " + Quoted(matrix_) + ": ") + message);
  }

  std::uint64_t Unsigned(std::size_t at, std::size_t bytes) const {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
      const auto b = static_cast<unsigned char>(data_[at + (little_ ? bytes - 1 - i : i)]);
      v = v << 8 | b;
    }
    return v;
  }

  // A signed word.
  std::int64_t Int(std::size_t at) const {
    const std::uint64_t u = Unsigned(at, word_);
    if (word_ == 8) return static_cast<std::int64_t>(u);
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(u));
  }

  // `count` numbers of `bytes` bytes (IEEE 754 in the file's byte order) from `at`.
  void Numbers(std::size_t at, std::int64_t count, std::size_t bytes, Run run) const {
    for (std::int64_t k = 0; k < count; ++k, at += bytes) {
      double v = 0;
      if (bytes == 8) {
        const std::uint64_t u = Unsigned(at, 8);
        std::memcpy(&v, &u, 8);
      } else {
        const auto u = static_cast<std::uint32_t>(Unsigned(at, 4));
        float f = 0;
        std::memcpy(&f, &u, 4);
        v = f;
      }
      if (!std::isfinite(v)) Fail(at, run.Where() + ": the value is not finite (" + NumberText(v) + ")");
      run.Add(v);
    }
  }

  // The next record: at_ (its leading length), data_at_, bytes_; false at
  // the end of the file.
  bool Next() {
    const std::size_t size = data_.size();
    if (pos_ == size) return false;
    at_ = pos_;
    if (size - pos_ < 4)
      Fail(pos_, Count(static_cast<std::int64_t>(size - pos_), "byte") +
                     " after the last record, too few for a record's length; is the file truncated?");
    const std::uint64_t length = Unsigned(pos_, 4);
    if (size - pos_ < 8 || length > size - pos_ - 8)
      Fail(pos_, "a record of " + Count(static_cast<std::int64_t>(length), "byte") + " starts here, but the file ends " +
                     Count(static_cast<std::int64_t>(size - pos_ - 4), "byte") +
                     " later (it needs its data and its closing length); is the file truncated?");
    const std::size_t end = pos_ + 4 + static_cast<std::size_t>(length);
    if (Unsigned(end, 4) != length)
      Fail(end, "the record at byte " + std::to_string(pos_) + " of " + Count(static_cast<std::int64_t>(length), "byte") +
                    " ends with the length " + std::to_string(Unsigned(end, 4)) +
                    " (a Fortran record starts and ends with its length in bytes)");
    data_at_ = pos_ + 4;
    bytes_ = static_cast<std::size_t>(length);
    pos_ = end + 4;
    return true;
  }

  const std::string& data_;
  std::string path_;
  bool little_;
  std::size_t word_;
  std::size_t pos_ = 0, at_ = 0, data_at_ = 0, bytes_ = 0;
  std::string matrix_;
  bool bigmat_ = false;
};

// The encoding of a file that starts with `head`: a binary file's first
// record is a header of 6 words, 24 or 48 bytes.
struct Layout {
  bool binary = false, little_endian = true;
  int word_bytes = 4;
};
Layout Detect(std::string_view head) {
  if (head.size() < 4) return {};
  const auto byte = [&](std::size_t i) { return std::uint32_t{static_cast<unsigned char>(head[i])}; };
  const std::uint32_t little = byte(0) | byte(1) << 8 | byte(2) << 16 | byte(3) << 24;
  const std::uint32_t big = byte(3) | byte(2) << 8 | byte(1) << 16 | byte(0) << 24;
  if (little == 24 || little == 48) return {true, true, static_cast<int>(little / 6)};
  if (big == 24 || big == 48) return {true, false, static_cast<int>(big / 6)};
  return {};
}

}  // namespace

std::string Op4TypeText(int type) {
  switch (type) {
    case 1: return "real single precision";
    case 2: return "real double precision";
    case 3: return "complex single precision";
    case 4: return "complex double precision";
    default: return "unknown type " + std::to_string(type);
  }
}

Op4File::Op4File(const std::string& path)
    : path_(path), content_(ReadInputFile(path, "OP4 file", limits::kMaxOp4FileBytes)) {
  const Layout e = Detect(content_);
  encoding_ = e.binary ? Encoding::kBinary : Encoding::kText;
  little_endian_ = e.little_endian;
  word_bytes_ = e.word_bytes;
  const auto scan = [&](auto& reader) {
    for (Op4Matrix m; reader.Header(matrices_.size() + 1, m);) {
      if (matrices_.size() == limits::kMaxOp4Matrices)
        throw InputError(path_ + ": holds more than the " + std::to_string(limits::kMaxOp4Matrices) +
                         " matrices deb reads from one OP4 file");
      reader.Body(m, Target{});
      matrices_.push_back(m);
    }
  };
  if (e.binary) {
    BinaryReader reader(content_, path_, little_endian_, word_bytes_);
    scan(reader);
  } else {
    TextReader reader(content_, path_);
    scan(reader);
  }
  if (matrices_.empty()) throw InputError(path_ + ": the OP4 file holds no matrix (it is empty or blank)");
}

std::string Op4File::EncodingText() const {
  if (encoding_ == Encoding::kText) return "text";
  return std::string("binary, ") + (little_endian_ ? "little" : "big") + "-endian, " + std::to_string(word_bytes_) +
         "-byte words";
}

bool Op4File::Has(const std::string& name) const {
  return std::any_of(matrices_.begin(), matrices_.end(), [&](const Op4Matrix& m) { return m.name == name; });
}

std::string Op4File::NamesText() const {
  std::string names;
  for (std::size_t i = 0; i < matrices_.size() && i < 20; ++i) names += (i ? ", " : "") + matrices_[i].name;
  if (matrices_.size() > 20) names += ", ...";
  return names;
}

std::size_t Op4File::IndexOf(const std::string& name) const {
  std::vector<std::size_t> found;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < matrices_.size(); ++i) {
    if (matrices_[i].name == name) found.push_back(i);
    names.push_back(matrices_[i].name);
  }
  if (found.empty()) {
    // Nastran writes names in capitals; a budget may not.
    std::string hint = DidYouMean(name, names);
    for (const std::string& n : names)
      if (n.size() == name.size() && std::equal(n.begin(), n.end(), name.begin(), [](char a, char b) {
            return std::toupper(static_cast<unsigned char>(a)) == std::toupper(static_cast<unsigned char>(b));
          }))
        hint = " (did you mean " + Quoted(n) + "?)";
    throw InputError(path_ + ": no matrix " + Quoted(name) + " in the OP4 file" + hint + " (it holds " + NamesText() +
                     ")");
  }
  if (found.size() > 1)
    throw InputError(path_ + ": the OP4 file holds " + std::to_string(found.size()) + " matrices named " +
                     Quoted(name) + " (numbers " + std::to_string(found[0] + 1) + " and " +
                     std::to_string(found[1] + 1) + "); which one is meant is not clear");
  return found.front();
}

void Op4File::Read(std::size_t index, Eigen::MatrixXd* real, Eigen::MatrixXcd* complex) const {
  const Op4Matrix& m = matrices_[index];
  // A complex value is two numbers: the bound is on memory.
  const std::uint64_t values = static_cast<std::uint64_t>(m.rows) * static_cast<std::uint64_t>(m.cols);
  const std::uint64_t numbers = complex ? 2 * values : values;
  if (numbers > limits::kMaxMatElements)
    throw InputError(path_ + ": matrix " + Quoted(m.name) + " is " + std::to_string(m.rows) + "x" +
                     std::to_string(m.cols) + ", " +
                     (complex ? std::to_string(values) + " complex values, " + std::to_string(numbers) + " numbers"
                              : std::to_string(values) + " values") +
                     ", more than the " + std::to_string(limits::kMaxMatElements) + " deb reads of one matrix");
  if (real) real->setZero(m.rows, m.cols);
  if (complex) complex->setZero(m.rows, m.cols);
  const auto read = [&](auto& reader) {
    Op4Matrix header;
    for (std::size_t i = 0; i <= index; ++i) {
      const bool found = reader.Header(i + 1, header);
      DEB_DEMAND(found);  // the file was checked when it was opened
      reader.Body(header, i == index ? Target{real, complex} : Target{});
    }
  };
  if (encoding_ == Encoding::kBinary) {
    BinaryReader reader(content_, path_, little_endian_, word_bytes_);
    read(reader);
  } else {
    TextReader reader(content_, path_);
    read(reader);
  }
}

Eigen::MatrixXd Op4File::Matrix(const std::string& name) const {
  const std::size_t index = IndexOf(name);
  const Op4Matrix& m = matrices_[index];
  if (m.complex())
    throw InputError(path_ + ": matrix " + Quoted(m.name) + " is complex (type " + std::to_string(m.type) + ", " +
                     Op4TypeText(m.type) + "); a real matrix is expected here");
  Eigen::MatrixXd real;
  Read(index, &real, nullptr);
  return real;
}

Eigen::MatrixXcd Op4File::ComplexMatrix(const std::string& name) const {
  Eigen::MatrixXcd z;
  Read(IndexOf(name), nullptr, &z);
  return z;
}

bool LooksLikeOp4File(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || ec) return false;
  std::ifstream in(path, std::ios::binary);
  char buffer[256];
  in.read(buffer, sizeof buffer);
  std::string head(buffer, static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  if (Detect(head).binary) return true;
  if (head.compare(0, 3, "\xEF\xBB\xBF") == 0) head.erase(0, 3);
  const std::string line = head.substr(0, head.find_first_of("\r\n"));
  for (std::size_t k = 0; k < 4; ++k)
    if (!FixedInt(line, 8 * k, 8)) return false;
  return true;
}

}  // namespace deb::formats
