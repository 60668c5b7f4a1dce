#include "deb/formats/uff58_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"

namespace deb::formats {
namespace {

constexpr int kFirstDataRecord = 12;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool IsDelimiter(std::string_view line) { return Trim(line) == "-1"; }

// `text` as UTF-8: kept if it is, else read as Latin-1; control characters
// become blanks (labels go into messages and unit strings).
std::string ToUtf8(std::string_view text) {
  std::string s(text);
  if (FirstNonUtf8(s) != std::string::npos) {
    std::string out;
    out.reserve(2 * s.size());
    for (const char ch : s) {
      const unsigned char c = static_cast<unsigned char>(ch);
      if (c < 0x80) {
        out += ch;
      } else {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
      }
    }
    s = std::move(out);
  }
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7F) ch = ' ';
  return s;
}

// The byte offsets where the characters of UTF-8 `text` start, and its size last.
std::vector<std::size_t> CharStarts(const std::string& text) {
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < text.size(); ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) starts.push_back(i);
  starts.push_back(text.size());
  return starts;
}

// Columns [first, first + width) (1-based, in characters) of `text`, "" past its end.
std::string Columns(const std::string& text, const std::vector<std::size_t>& starts, int first, int width) {
  const std::size_t chars = starts.size() - 1;
  const std::size_t a = std::min(chars, static_cast<std::size_t>(first - 1));
  const std::size_t b = std::min(chars, static_cast<std::size_t>(first - 1 + width));
  return text.substr(starts[a], starts[b] - starts[a]);
}

// A number of a data or header line: the text without a leading '+', a
// Fortran D exponent read as E. False if the text is no number.
bool ParseDouble(std::string_view text, double* value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.size() > 64) return false;
  char buffer[65];
  std::size_t n = 0;
  for (const char c : text) buffer[n++] = (c == 'D' || c == 'd') ? 'E' : c;
  const auto result = std::from_chars(buffer, buffer + n, *value);
  if (result.ptr != buffer + n) return false;
  if (result.ec == std::errc::result_out_of_range) {
    // Beyond a double's range: an overflow is not finite (and refused as
    // such), an underflow is 0.
    const std::size_t e = std::string_view(buffer, n).find_first_of("Ee");
    const bool underflow = e != std::string_view::npos && e + 1 < n && buffer[e + 1] == '-';
    *value = underflow ? 0.0 : HUGE_VAL;
    return true;
  }
  return result.ec == std::errc();
}

bool ParseInt(std::string_view text, long long* value) {
  text = Trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), *value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

// A whitespace-separated field and its 1-based column.
struct Field {
  std::string_view text;
  int column = 0;
};

std::vector<Field> SplitFields(std::string_view line) {
  std::vector<Field> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return fields;
}

// The numbers of one field: one, or several that touch ("1.2E-03-4.5E-03"),
// split before a sign that does not follow an exponent letter, each part
// with a decimal point (so that "1.0-100", an exponent without its letter,
// is no number rather than two). False if the field is not numbers.
bool ParseNumbers(std::string_view field, std::vector<double>& out) {
  double v = 0.0;
  if (ParseDouble(field, &v)) {
    out.push_back(v);
    return true;
  }
  const std::size_t before = out.size();
  std::size_t start = 0;
  for (std::size_t i = 1; i <= field.size(); ++i) {
    const bool cut = i == field.size() ||
                     ((field[i] == '-' || field[i] == '+') && std::string_view("EeDd").find(field[i - 1]) == std::string_view::npos);
    if (!cut) continue;
    const std::string_view part = field.substr(start, i - start);
    if (part.find('.') == std::string_view::npos || !ParseDouble(part, &v)) {
      out.resize(before);
      return false;
    }
    out.push_back(v);
    start = i;
  }
  return true;
}

// The bytes of the file, line by line: LF, CRLF and a lone CR end a line.
class Cursor {
 public:
  Cursor(const std::string& bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  // The next line without its end; false at the end of the bytes.
  bool Next(std::string_view& line) {
    if (pos_ >= bytes_.size()) return false;
    ++line_;
    line_start_ = pos_;
    std::size_t end = bytes_.find_first_of("\r\n", pos_);
    if (end == std::string::npos) end = bytes_.size();
    if (end - pos_ > limits::kMaxLineBytes)
      throw InputError(InputLocation{name_, line_, 1, ""},
                       "the line is longer than " + std::to_string(limits::kMaxLineBytes >> 20) +
                           " MiB; is this a universal file?");
    line = std::string_view(bytes_).substr(pos_, end - pos_);
    pos_ = end;
    if (pos_ < bytes_.size()) pos_ += (bytes_[pos_] == '\r' && pos_ + 1 < bytes_.size() && bytes_[pos_ + 1] == '\n') ? 2 : 1;
    return true;
  }
  // Past `n` bytes (binary data), counting the line ends among them as
  // Next() would, so that later lines keep their numbers.
  void Skip(std::size_t n) {
    for (std::size_t i = pos_; i < pos_ + n; ++i)
      if (bytes_[i] == '\n' || (bytes_[i] == '\r' && (i + 1 >= bytes_.size() || bytes_[i + 1] != '\n'))) ++line_;
    pos_ += n;
  }
  int line() const { return line_; }
  std::size_t line_start() const { return line_start_; }
  std::size_t pos() const { return pos_; }
  std::size_t left() const { return bytes_.size() - pos_; }

 private:
  const std::string& bytes_;
  const std::string& name_;
  std::size_t pos_ = 0, line_start_ = 0;
  int line_ = 0;
};

// Where a rule is broken: the file, the dataset and its record.
class Place {
 public:
  Place(const std::string& name, int dataset, std::string kind) : name_(name), dataset_(dataset), kind_(std::move(kind)) {}
  void SetKind(std::string kind) { kind_ = std::move(kind); }

  [[noreturn]] void Fail(int line, int column, int record, const std::string& rule) const {
    throw InputError(InputLocation{name_, line, std::max(column, 1), ""}, Prefix(record) + rule);
  }
  [[noreturn]] void FailAtByte(std::size_t offset, int record, const std::string& rule) const {
    throw InputError(InputLocation{name_, 0, 0, ""}, "byte " + std::to_string(offset) + ": " + Prefix(record) + rule);
  }

 private:
  std::string Prefix(int record) const {
    std::string s = "dataset #" + std::to_string(dataset_) + " (" + kind_ + ")";
    if (record > 0) s += ", record " + std::to_string(record);
    return s + ": ";
  }
  const std::string& name_;
  int dataset_;
  std::string kind_;
};

std::string Quoted(std::string_view text) { return "'" + Excerpt(std::string(text)) + "'"; }

// An integer field of a record read by columns.
long long IntAt(const Place& at, int line, int record, const std::string& text, int first, int width,
                const char* what) {
  long long v = 0;
  if (!ParseInt(text, &v)) {
    const std::string where = "columns " + std::to_string(first) + "-" + std::to_string(first + width - 1);
    if (Trim(text).empty()) at.Fail(line, first, record, where + " (" + what + ") are blank; an integer is needed");
    at.Fail(line, first, record, where + " (" + what + ") hold " + Quoted(Trim(text)) + ", not an integer");
  }
  return v;
}

int DirectionAt(const Place& at, int line, int record, const std::string& text, int first, const char* what) {
  const long long d = IntAt(at, line, record, text, first, 4, what);
  if (d < -6 || d > 6)
    at.Fail(line, first, record,
            std::string(what) + " " + std::to_string(d) +
                " is not a direction: 0 (scalar), 1-3 (+X, +Y, +Z), 4-6 (+RX, +RY, +RZ) or their negatives");
  return static_cast<int>(d);
}

void ParseRecord6(const Place& at, int line, std::string_view raw, Uff58Record& r) {
  const std::string text = ToUtf8(raw);
  const std::vector<std::size_t> starts = CharStarts(text);
  const auto col = [&](int first, int width) { return Columns(text, starts, first, width); };
  const long long type = IntAt(at, line, 6, col(1, 5), 1, 5, "function type");
  if (type < 0 || type > 28)
    at.Fail(line, 1, 6,
            "function type " + std::to_string(type) +
                " is unknown; the types are 0 (general) to 28 (phase compensation), e.g. 1 time response, "
                "2 auto spectrum, 4 FRF, 9 PSD");
  r.function = static_cast<UffFunction>(type);
  const auto small = [&](long long v, int first, const char* what) {
    if (v < -2'000'000'000LL || v > 2'000'000'000LL)
      at.Fail(line, first, 6, std::string(what) + " " + std::to_string(v) + " is out of range");
    return static_cast<int>(v);
  };
  r.function_id = small(IntAt(at, line, 6, col(6, 10), 6, 10, "function identification number"), 6, "function id");
  r.version = small(IntAt(at, line, 6, col(16, 5), 16, 5, "version number"), 16, "version number");
  r.load_case = small(IntAt(at, line, 6, col(21, 10), 21, 10, "load case"), 21, "load case");
  r.response_entity = std::string(Trim(col(32, 10)));
  r.response.node = small(IntAt(at, line, 6, col(42, 10), 42, 10, "response node"), 42, "response node");
  r.response.direction = DirectionAt(at, line, 6, col(52, 4), 52, "response direction");
  r.reference_entity = std::string(Trim(col(57, 10)));
  r.reference.node = small(IntAt(at, line, 6, col(67, 10), 67, 10, "reference node"), 67, "reference node");
  r.reference.direction = DirectionAt(at, line, 6, col(77, 4), 77, "reference direction");
}

// The numbers of a line read as fields (record 7): exactly `count` of them.
std::vector<double> NumbersOf(const Place& at, int line, int record, std::string_view raw, std::size_t count,
                              const std::string& what) {
  std::vector<double> values;
  for (const Field& f : SplitFields(raw)) {
    if (!ParseNumbers(f.text, values))
      at.Fail(line, f.column, record, Quoted(f.text) + " is not a number (" + what + ")");
  }
  if (values.size() != count)
    at.Fail(line, 1, record, "the record holds " + std::to_string(values.size()) + " number(s); " + what + " are " +
                                 std::to_string(count));
  return values;
}

// The number of points.
std::size_t ParseRecord7(const Place& at, int line, std::string_view raw, Uff58Record& r) {
  const std::vector<double> v =
      NumbersOf(at, line, 7, raw, 6,
                "ordinate data type, number of points, abscissa spacing, abscissa minimum, increment and z value");
  const auto whole = [&](double x, const char* what) {
    if (!(x == std::floor(x) && std::abs(x) < 1e15))
      at.Fail(line, 1, 7, std::string(what) + " " + Excerpt(std::to_string(x)) + " is not a whole number");
    return static_cast<long long>(x);
  };
  const long long type = whole(v[0], "the ordinate data type");
  if (type != 2 && type != 4 && type != 5 && type != 6)
    at.Fail(line, 1, 7,
            "ordinate data type " + std::to_string(type) +
                " is unknown; the types are 2 (real, single precision), 4 (real, double), 5 (complex, single), 6 "
                "(complex, double)");
  r.ordinate = static_cast<UffOrdinate>(type);
  const long long n = whole(v[1], "the number of points");
  if (n < 1) at.Fail(line, 1, 7, "the number of points is " + std::to_string(n) + "; at least 1 is needed");
  if (static_cast<unsigned long long>(n) > limits::kMaxGridPoints)
    at.Fail(line, 1, 7,
            std::to_string(n) + " points is more than the " + std::to_string(limits::kMaxGridPoints) +
                " deb reads in one dataset");
  const long long spacing = whole(v[2], "the abscissa spacing");
  if (spacing != 0 && spacing != 1)
    at.Fail(line, 1, 7, "abscissa spacing " + std::to_string(spacing) + " is neither 1 (even) nor 0 (uneven)");
  r.even_spacing = spacing == 1;
  for (int k = 3; k < 6; ++k)
    if (!std::isfinite(v[k])) at.Fail(line, 1, 7, "the abscissa minimum, increment and z value must be finite");
  r.abscissa_min = v[3];
  r.abscissa_increment = v[4];
  r.z_value = v[5];
  return static_cast<std::size_t>(n);
}

void ParseAxis(const Place& at, int line, int record, std::string_view raw, UffAxis& axis) {
  std::string text = ToUtf8(raw);
  std::vector<std::size_t> starts = CharStarts(text);
  // Column 47 separates the two labels. A writer that padded a UTF-8 label
  // by bytes instead of characters puts it at byte 47.
  if (!Trim(Columns(text, starts, 47, 1)).empty()) {
    const std::string bytes(raw);
    if (FirstNonUtf8(bytes) == std::string::npos && bytes.size() >= 47 && bytes[46] == ' ') {
      starts.clear();
      for (std::size_t i = 0; i <= text.size(); ++i) starts.push_back(i);
    } else {
      at.Fail(line, 47, record,
              "column 47 must be blank: it separates the axis label (columns 27-46) from the units label "
              "(48-67), format I10,3I5,2(1X,A20)");
    }
  }
  const auto col = [&](int first, int width) { return Columns(text, starts, first, width); };
  const auto small = [&](int first, int width, const char* what) {
    const long long v = IntAt(at, line, record, col(first, width), first, width, what);
    if (v < -1000 || v > 1'000'000) at.Fail(line, first, record, std::string(what) + " " + std::to_string(v) + " is out of range");
    return static_cast<int>(v);
  };
  axis.data_type = small(1, 10, "specific data type");
  axis.length_exponent = small(11, 5, "length units exponent");
  axis.force_exponent = small(16, 5, "force units exponent");
  axis.temperature_exponent = small(21, 5, "temperature units exponent");
  axis.label = std::string(Trim(col(27, 20)));
  axis.units = std::string(Trim(col(48, 20)));
}

std::size_t ValuesPerPoint(const Uff58Record& r) { return (r.is_complex() ? 2 : 1) + (r.even_spacing ? 0 : 1); }

bool IsDouble(UffOrdinate o) { return o == UffOrdinate::kRealDouble || o == UffOrdinate::kComplexDouble; }

std::string DataForm(const Uff58Record& r, std::size_t n) {
  return std::to_string(n) + " point(s) of " + ToString(r.ordinate) + (r.even_spacing ? "" : " with their abscissae");
}

// Turns the values read (per point: [x,] re[, im]) into x and y.
void StoreValues(const Uff58Record& header, std::size_t n, const std::vector<double>& values, Uff58Record& r) {
  const std::size_t per = ValuesPerPoint(header);
  r.x.resize(n);
  r.y.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* v = values.data() + i * per;
    std::size_t k = 0;
    r.x[i] = header.even_spacing ? header.abscissa_min + static_cast<double>(i) * header.abscissa_increment : v[k++];
    const double re = v[k++];
    r.y[i] = {re, header.is_complex() ? v[k] : 0.0};
  }
}

// Record 12 as text: numbers up to the closing delimiter.
void ReadAsciiData(Cursor& c, const Place& at, std::size_t n, Uff58Record& r) {
  const std::size_t per = ValuesPerPoint(r);
  const std::size_t need = n * per;
  std::vector<double> values;
  values.reserve(std::min(need, c.left() / 2 + 1));
  std::string_view line;
  const int first_line = c.line() + 1;
  for (;;) {
    if (!c.Next(line)) {
      if (values.size() < need)
        at.Fail(c.line(), 1, kFirstDataRecord,
                "the file ends after " + std::to_string(values.size()) + " of the " + std::to_string(need) +
                    " values that " + DataForm(r, n) + " need (the dataset is truncated)");
      at.Fail(c.line(), 1, kFirstDataRecord, "the file ends without the delimiter -1 that closes the dataset");
    }
    if (IsDelimiter(line)) break;
    for (const Field& f : SplitFields(line)) {
      const std::size_t before = values.size();
      if (!ParseNumbers(f.text, values))
        at.Fail(c.line(), f.column, kFirstDataRecord, Quoted(f.text) + " is not a number");
      for (std::size_t k = before; k < values.size(); ++k)
        if (!std::isfinite(values[k]))
          at.Fail(c.line(), f.column, kFirstDataRecord, Quoted(f.text) + " is not a finite number");
      if (values.size() > need)
        at.Fail(c.line(), f.column, kFirstDataRecord,
                "more values than the " + std::to_string(need) + " that " + DataForm(r, n) +
                    " need (record 7 gives the number of points; a missing delimiter -1?)");
    }
  }
  if (values.size() < need)
    at.Fail(c.line(), 1, kFirstDataRecord,
            "the data (lines " + std::to_string(first_line) + "-" + std::to_string(c.line() - 1) + ") holds " +
                std::to_string(values.size()) + " values, but " + DataForm(r, n) + " need " + std::to_string(need) +
                " (record 7 gives the number of points)");
  StoreValues(r, n, values, r);
}

double Decode(const unsigned char* p, bool wide, bool big_endian) {
  const std::size_t size = wide ? 8 : 4;
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < size; ++k) {
    const std::size_t from = big_endian ? k : size - 1 - k;
    bits = (bits << 8) | p[from];
  }
  if (wide) {
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  const std::uint32_t b32 = static_cast<std::uint32_t>(bits);
  float f;
  std::memcpy(&f, &b32, sizeof f);
  return static_cast<double>(f);
}

// The 58b header line's fields after "58b".
struct BinaryForm {
  bool big_endian = false;
  std::uint64_t bytes = 0;
};

BinaryForm ParseBinaryHeader(const Place& at, int line, std::string_view raw) {
  const std::vector<Field> fields = SplitFields(raw);
  BinaryForm form;
  if (fields.size() < 5)
    at.Fail(line, 1, 0,
            "the 58b line needs the byte order, floating-point format, number of ASCII lines and number of bytes "
            "after '58b'; it holds " + std::to_string(fields.size() - 1) + " field(s)");
  long long v[4];
  const char* what[4] = {"byte order", "floating-point format", "number of ASCII lines", "number of bytes"};
  for (int k = 0; k < 4; ++k)
    if (!ParseInt(fields[k + 1].text, &v[k]))
      at.Fail(line, fields[k + 1].column, 0, Quoted(fields[k + 1].text) + " (" + what[k] + ") is not an integer");
  if (v[0] != 1 && v[0] != 2)
    at.Fail(line, fields[1].column, 0, "byte order " + std::to_string(v[0]) + " is neither 1 (little endian) nor 2 (big endian)");
  if (v[1] != 2)
    at.Fail(line, fields[2].column, 0,
            "floating-point format " + std::to_string(v[1]) +
                ": deb reads 2 (IEEE 754) only, not 1 (DEC VAX) or 3 (IBM 370)");
  if (v[2] != 11)
    at.Fail(line, fields[3].column, 0,
            std::to_string(v[2]) + " ASCII lines announced; a dataset 58b has 11 (records 1-11) before its data");
  if (v[3] < 0) at.Fail(line, fields[4].column, 0, "the number of bytes " + std::to_string(v[3]) + " is negative");
  form.big_endian = v[0] == 2;
  form.bytes = static_cast<std::uint64_t>(v[3]);
  return form;
}

// Record 12 as binary data: exactly the bytes the header announced, then the delimiter.
void ReadBinaryData(Cursor& c, const std::string& bytes, const Place& at, const BinaryForm& form, std::size_t n,
                    Uff58Record& r) {
  const std::size_t start = c.pos();
  const std::size_t size = IsDouble(r.ordinate) ? 8 : 4;
  const std::size_t per = ValuesPerPoint(r);
  const std::uint64_t need = static_cast<std::uint64_t>(n) * per * size;
  if (form.bytes != need)
    at.FailAtByte(start, kFirstDataRecord,
                  "the 58b header announces " + std::to_string(form.bytes) + " bytes of data, but " + DataForm(r, n) +
                      " take " + std::to_string(need) + " bytes");
  if (need > c.left())
    at.FailAtByte(start, kFirstDataRecord,
                  "the 58b header announces " + std::to_string(need) + " bytes of data, but the file ends " +
                      std::to_string(c.left()) + " bytes after record 11 (the dataset is truncated)");
  std::vector<double> values(n * per);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + start);
  for (std::size_t k = 0; k < values.size(); ++k) {
    values[k] = Decode(p + k * size, size == 8, form.big_endian);
    if (!std::isfinite(values[k]))
      at.FailAtByte(start + k * size, kFirstDataRecord,
                    "value " + std::to_string(k + 1) + " (point " + std::to_string(k / per + 1) +
                        ") is not finite (NaN or infinity)");
  }
  c.Skip(need);
  StoreValues(r, n, values, r);
  // The delimiter, on the rest of the data's line or on a line after it.
  std::string_view line;
  while (c.Next(line)) {
    if (IsDelimiter(line)) return;
    if (!Trim(line).empty())
      at.FailAtByte(c.line_start(), 0,
                    "the delimiter -1 must follow the " + std::to_string(need) + " bytes of data; found " +
                        Quoted(line) + " (does the 58b header give the right number of bytes?)");
  }
  at.FailAtByte(c.pos(), 0, "the file ends without the delimiter -1 that closes the dataset");
}

}  // namespace

std::string ToString(UffFunction f) {
  static const char* const kNames[] = {
      "general", "time response", "auto spectrum", "cross spectrum", "FRF", "transmissibility", "coherence",
      "auto-correlation", "cross-correlation", "PSD", "ESD", "probability density", "spectrum",
      "cumulative frequency distribution", "peaks valley", "stress/cycles", "strain/cycles", "orbit",
      "mode indicator function", "force pattern", "partial power", "partial coherence", "eigenvalue",
      "eigenvector", "shock response spectrum", "FIR filter", "multiple coherence", "order function",
      "phase compensation"};
  const int i = static_cast<int>(f);
  return i >= 0 && i <= 28 ? kNames[i] : "function type " + std::to_string(i);
}

std::string ToString(UffOrdinate o) {
  switch (o) {
    case UffOrdinate::kRealSingle: return "real single precision";
    case UffOrdinate::kRealDouble: return "real double precision";
    case UffOrdinate::kComplexSingle: return "complex single precision";
    case UffOrdinate::kComplexDouble: return "complex double precision";
  }
  return "ordinate type " + std::to_string(static_cast<int>(o));
}

std::string ToString(const UffDof& dof) {
  static const char* const kAxes[] = {"X", "Y", "Z", "RX", "RY", "RZ"};
  const int d = dof.direction;
  std::string dir = "scalar";
  if (d != 0 && d >= -6 && d <= 6) dir = std::string(d > 0 ? "+" : "-") + kAxes[std::abs(d) - 1];
  else if (d != 0) dir = std::to_string(d);
  return std::to_string(dof.node) + ":" + dir;
}

UffDof ParseUffDof(const std::string& text) {
  const std::string form = "'" + Excerpt(text) +
                           "' is not a DOF NODE:DIRECTION, e.g. '1:+Z', '12:-X', '3:RY' or '0:scalar' "
                           "(directions scalar, X, Y, Z, RX, RY, RZ with an optional sign)";
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) throw InputError(form);
  long long node = 0;
  if (!ParseInt(std::string_view(text).substr(0, colon), &node) || node < 0 || node > 2'000'000'000LL)
    throw InputError(form);
  std::string dir(Trim(std::string_view(text).substr(colon + 1)));
  for (char& ch : dir) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  UffDof dof;
  dof.node = static_cast<int>(node);
  if (dir == "SCALAR" || dir == "0") return dof;
  int sign = 1;
  if (!dir.empty() && (dir.front() == '+' || dir.front() == '-')) {
    sign = dir.front() == '-' ? -1 : 1;
    dir.erase(0, 1);
  }
  static const char* const kAxes[] = {"X", "Y", "Z", "RX", "RY", "RZ"};
  for (int k = 0; k < 6; ++k)
    if (dir == kAxes[k]) {
      dof.direction = sign * (k + 1);
      return dof;
    }
  throw InputError(form);
}

std::vector<double> Uff58Record::RealValues() const {
  std::vector<double> v(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) v[i] = y[i].real();
  return v;
}

std::string Uff58Record::Describe() const {
  const auto entity = [](const std::string& name) {
    return name.empty() || name == "NONE" ? std::string() : " '" + Excerpt(name, 20) + "'";
  };
  return "#" + std::to_string(index) + " (" + ToString(function) + ", response" + entity(response_entity) + " " +
         ToString(response) + ", reference" + entity(reference_entity) + " " + ToString(reference) + ")";
}

std::vector<Uff58Record> ParseUff58(const std::string& bytes, const std::string& name) {
  std::vector<Uff58Record> records;
  Cursor c(bytes, name);
  std::string_view line;
  std::size_t datasets = 0, points = 0;
  while (c.Next(line)) {
    if (Trim(line).empty()) continue;
    if (!IsDelimiter(line))
      throw InputError(InputLocation{name, c.line(), 1, ""},
                       "expected the delimiter -1 that opens a dataset of a universal file, found " + Quoted(line));
    const int open_line = c.line();
    const std::size_t open_offset = c.line_start();
    if (++datasets > limits::kMaxUffDatasets)
      throw InputError(InputLocation{name, open_line, 1, ""},
                       "more than the " + std::to_string(limits::kMaxUffDatasets) + " datasets deb reads in one file");
    const int index = static_cast<int>(datasets);
    if (!c.Next(line))
      throw InputError(InputLocation{name, open_line, 1, ""},
                       "the file ends after the delimiter -1 that opens dataset #" + std::to_string(index));
    const std::vector<Field> head = SplitFields(line);
    std::string kind = head.empty() ? std::string() : std::string(head.front().text);
    const bool binary = !kind.empty() && (kind.back() == 'b' || kind.back() == 'B');
    long long number = 0;
    if (!ParseInt(binary ? std::string_view(kind).substr(0, kind.size() - 1) : std::string_view(kind), &number) ||
        number < 0)
      throw InputError(InputLocation{name, c.line(), head.empty() ? 1 : head.front().column, ""},
                       "dataset #" + std::to_string(index) + ": the line after the delimiter -1 must give the "
                       "dataset type (58, 58b, 2411, ...); found " + Quoted(line));
    Place at(name, index, kind);
    if (number != 58) {  // another dataset: skipped
      for (;;) {
        if (!c.Next(line)) at.Fail(c.line(), 1, 0, "the file ends without the delimiter -1 that closes the dataset");
        if (IsDelimiter(line)) break;
      }
      continue;
    }
    BinaryForm form;
    if (binary) form = ParseBinaryHeader(at, c.line(), line);
    else if (head.size() > 1)
      at.Fail(c.line(), head[1].column, 0, "the line of an ASCII dataset 58 holds its number only, found " + Quoted(line));

    Uff58Record r;
    r.index = index;
    r.offset = open_offset;
    r.line = open_line;
    r.binary = binary;
    std::size_t n = 0;
    for (int record = 1; record <= 11; ++record) {
      if (!c.Next(line) || IsDelimiter(line))
        at.Fail(c.line(), 1, record,
                "the dataset ends before record " + std::to_string(record) + " of the 11 header records (truncated)");
      if (record <= 5) r.id[static_cast<std::size_t>(record - 1)] = std::string(Trim(ToUtf8(line)));
      else if (record == 6) ParseRecord6(at, c.line(), line, r);
      else if (record == 7) n = ParseRecord7(at, c.line(), line, r);
      else ParseAxis(at, c.line(), record, line, record == 8 ? r.abscissa : record == 9 ? r.numerator
                                                                   : record == 10 ? r.denominator : r.z_axis);
    }
    if (points + n > limits::kMaxUffFilePoints)
      at.Fail(c.line(), 1, 7,
              "the file's datasets 58 hold more than the " + std::to_string(limits::kMaxUffFilePoints) +
                  " points deb reads in one file");
    points += n;
    if (binary) ReadBinaryData(c, bytes, at, form, n, r);
    else ReadAsciiData(c, at, n, r);
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(r.x[i]))
        at.Fail(r.line, 1, 7, "the abscissa of point " + std::to_string(i + 1) + " (minimum + increment x index) is not finite");
    records.push_back(std::move(r));
  }
  if (datasets == 0) throw InputError(InputLocation{name, 0, 0, ""}, "holds no dataset: a universal file starts with the delimiter -1");
  return records;
}

std::vector<Uff58Record> ReadUff58(const std::string& path) {
  return ParseUff58(ReadInputFile(path, "universal file", limits::kMaxTextFileBytes), path);
}

bool LooksLikeUff(const std::string& bytes) {
  std::size_t pos = 0;
  const auto next = [&](std::string_view& line) {
    if (pos >= bytes.size()) return false;
    std::size_t end = bytes.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = bytes.size();
    line = std::string_view(bytes).substr(pos, end - pos);
    pos = end;
    if (pos < bytes.size()) pos += (bytes[pos] == '\r' && pos + 1 < bytes.size() && bytes[pos + 1] == '\n') ? 2 : 1;
    return true;
  };
  std::string_view line;
  do {
    if (!next(line)) return false;
  } while (Trim(line).empty());
  if (!IsDelimiter(line) || !next(line)) return false;
  const std::vector<Field> head = SplitFields(line);
  if (head.empty()) return false;
  std::string_view kind = head.front().text;
  if (kind.back() == 'b' || kind.back() == 'B') kind.remove_suffix(1);
  long long number = 0;
  return ParseInt(kind, &number) && number >= 0;
}

bool FileLooksLikeUff(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;  // a FIFO would block
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return LooksLikeUff(head);
}

namespace {

bool IsNameByte(char ch) {
  const unsigned char c = static_cast<unsigned char>(ch);
  return std::isalpha(c) || ch == '_' || c >= 0x80;
}

void ReplaceAll(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
}

bool EndsWith(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

// X of X^2 when X is one name ("gravity", "mm") or a group in parentheses;
// nullopt otherwise ("m/s^2" is not the square of m/s).
std::optional<std::string> SquareRoot(std::string s) {
  s = std::string(Trim(s));
  std::string base;
  if (EndsWith(s, "^2")) base = s.substr(0, s.size() - 2);
  else if (EndsWith(s, "**2")) base = s.substr(0, s.size() - 3);
  else return std::nullopt;
  base = std::string(Trim(base));
  if (base.size() >= 2 && base.front() == '(' && base.back() == ')') {
    int depth = 0;
    for (std::size_t i = 0; i < base.size(); ++i) {
      depth += base[i] == '(' ? 1 : base[i] == ')' ? -1 : 0;
      if (depth == 0 && i + 1 < base.size()) return std::nullopt;  // "(a)/(b)"
    }
    base = std::string(Trim(base.substr(1, base.size() - 2)));
    return base.empty() ? std::nullopt : std::optional<std::string>(base);
  }
  if (base.empty() || !std::all_of(base.begin(), base.end(), IsNameByte)) return std::nullopt;
  return base;
}

bool IsSqrtHz(const std::string& s) {
  return s == "sqrt(Hz)" || s == "Hz^0.5" || s == "Hz^(1/2)" || s == "Hz^1/2";
}

}  // namespace

std::optional<std::string> UffUnitText(const std::string& units_label) {
  std::string s(Trim(units_label));
  std::string upper = s;
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (s.empty() || upper == "NONE") return std::nullopt;
  ReplaceAll(s, "\xC2\xB2", "^2");  // ²
  ReplaceAll(s, "\xC2\xB3", "^3");  // ³
  ReplaceAll(s, "\xC2\xB7", "*");   // · (middle dot)
  // √ before a name or a group: sqrt of it.
  for (std::size_t at = s.find("\xE2\x88\x9A"); at != std::string::npos; at = s.find("\xE2\x88\x9A", at)) {
    std::size_t end = at + 3;
    while (end < s.size() && s[end] == ' ') ++end;
    const std::size_t from = end;
    if (end < s.size() && s[end] == '(') {
      int depth = 0;
      for (; end < s.size(); ++end) {
        depth += s[end] == '(' ? 1 : s[end] == ')' ? -1 : 0;
        if (depth == 0) break;
      }
      end = std::min(end + 1, s.size());
    } else {
      while (end < s.size() && IsNameByte(s[end])) ++end;
    }
    std::string inner = s.substr(from, end - from);
    if (inner.size() >= 2 && inner.front() == '(' && inner.back() == ')') inner = inner.substr(1, inner.size() - 2);
    const std::string replaced = "sqrt(" + inner + ")";
    s.replace(at, end - at, replaced);
    at += replaced.size();
  }
  // g alone: standard gravity.
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    if (!IsNameByte(s[i])) {
      out += s[i++];
      continue;
    }
    std::size_t end = i;
    while (end < s.size() && IsNameByte(s[end])) ++end;
    const std::string name = s.substr(i, end - i);
    out += name == "g" ? "gravity" : name;
    i = end;
  }
  return out;
}

std::optional<std::string> UffOrdinateUnit(const Uff58Record& record) {
  const std::optional<std::string> num = UffUnitText(record.numerator.units);
  if (!num) return std::nullopt;
  const std::optional<std::string> den = UffUnitText(record.denominator.units);
  if (!den) return num;
  return "(" + *num + ")/(" + *den + ")";
}

std::optional<UffDensityUnit> UffDensity(const Uff58Record& record) {
  std::optional<std::string> num = UffUnitText(record.numerator.units);
  if (!num) return std::nullopt;
  const std::optional<std::string> den = UffUnitText(record.denominator.units);
  std::string signal, per;
  if (den) {
    signal = *num;
    per = std::string(Trim(*den));
  } else {
    const std::size_t slash = num->rfind('/');
    if (slash == std::string::npos) return std::nullopt;
    // the last '/' outside parentheses: "(m/s)^2/Hz", "gravity/sqrt(Hz)"
    std::size_t cut = std::string::npos;
    int depth = 0;
    for (std::size_t i = 0; i < num->size(); ++i) {
      const char ch = (*num)[i];
      depth += ch == '(' ? 1 : ch == ')' ? -1 : 0;
      if (ch == '/' && depth == 0) cut = i;
    }
    if (cut == std::string::npos) return std::nullopt;
    signal = num->substr(0, cut);
    per = std::string(Trim(num->substr(cut + 1)));
  }
  if (IsSqrtHz(per)) {
    std::string s(Trim(signal));
    if (s.empty()) return std::nullopt;
    return UffDensityUnit{s, true};
  }
  if (per != "Hz") return std::nullopt;
  const std::optional<std::string> root = SquareRoot(signal);
  if (!root) return std::nullopt;
  return UffDensityUnit{*root, false};
}

}  // namespace deb::formats
