#include "deb/core/numeric_table.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"

namespace deb {
namespace {

struct Cell {
  std::string text;
  int column = 1;  // 1-based character position of the cell in its line
};

bool IsSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::string Trim(const std::string& text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && IsSpace(text[begin])) ++begin;
  while (end > begin && IsSpace(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// Splits on commas when the line has one, else on runs of whitespace.
std::vector<Cell> SplitCells(const std::string& line) {
  std::vector<Cell> cells;
  if (line.find(',') != std::string::npos) {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      const std::string raw = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      std::size_t lead = 0;
      while (lead < raw.size() && IsSpace(raw[lead])) ++lead;
      cells.push_back({Trim(raw), static_cast<int>(start + lead) + 1});
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  } else {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && IsSpace(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !IsSpace(line[i])) ++i;
      cells.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
  }
  return cells;
}

enum class NumberStatus { kOk, kNotANumber, kNotFinite, kOutOfRange };

NumberStatus ParseNumber(const std::string& text, double* value) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars rejects a leading '+'
  if (begin == end) return NumberStatus::kNotANumber;
  const auto result = std::from_chars(begin, end, *value);
  if (result.ptr != end) return NumberStatus::kNotANumber;
  if (result.ec == std::errc::result_out_of_range) return NumberStatus::kOutOfRange;
  if (result.ec != std::errc()) return NumberStatus::kNotANumber;
  if (!std::isfinite(*value)) return NumberStatus::kNotFinite;
  return NumberStatus::kOk;
}

// "# key: value" with a requested key adds metadata; anything else is a comment.
void Comment(NumericTable& table, const std::set<std::string>& keys, const std::string& line, std::size_t hash,
             int line_no) {
  const std::string body = line.substr(hash + 1);
  const std::size_t colon = body.find(':');
  if (colon == std::string::npos) return;
  const std::string key = Lower(Trim(body.substr(0, colon)));
  if (!keys.count(key)) return;
  std::size_t lead = colon + 1;
  while (lead < body.size() && IsSpace(body[lead])) ++lead;
  const int column = static_cast<int>(hash + 1 + lead) + 1;
  if (table.metadata.count(key)) table.Fail(line_no, column, "'# " + key + ":' is given twice; give it once");
  const std::string value = Trim(body.substr(colon + 1));
  if (value.empty()) table.Fail(line_no, column, "'# " + key + ":' has no value");
  if (const std::string problem = Utf8Problem(value); !problem.empty())
    table.Fail(line_no, column, "'# " + key + ":' " + problem + "; save the file as UTF-8 text");
  table.metadata[key] = {value, line_no, column};
}

void Row(NumericTable& table, const std::vector<Cell>& cells, int line_no, const std::string& line,
         const NumericTableOptions& options) {
  const std::string& first_column = options.first_column;
  double probe = 0.0;
  const bool first = table.rows.empty() && table.header_line == 0;
  if (first && (options.names_in_first_column ||
                ParseNumber(cells.front().text, &probe) == NumberStatus::kNotANumber)) {
    for (const Cell& c : cells) {
      if (c.text.empty()) table.Fail(line_no, c.column, "empty column name");
      if (const std::string problem = Utf8Problem(c.text); !problem.empty())
        table.Fail(line_no, c.column, "column name '" + Excerpt(c.text) + "': " + problem + "; save the file as UTF-8 text");
      table.header.push_back(c.text);
      table.header_columns.push_back(c.column);
    }
    table.header_line = line_no;
    return;
  }
  const std::size_t expected = table.columns();
  if (!first && cells.size() != expected) {
    const int column = cells.size() > expected ? cells[expected].column : static_cast<int>(line.size()) + 1;
    const int reference = table.header_line ? table.header_line : table.rows.front().line;
    table.Fail(line_no, column,
               "row has " + std::to_string(cells.size()) + " cells; expected " + std::to_string(expected) +
                   " as on line " + std::to_string(reference));
  }
  NumericTable::Row row;
  row.line = line_no;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const Cell& cell = cells[c];
    if (c == 0 && options.names_in_first_column) {
      if (cell.text.empty()) table.Fail(line_no, cell.column, first_column + ": empty cell; every row starts with a name");
      if (const std::string problem = Utf8Problem(cell.text); !problem.empty())
        table.Fail(line_no, cell.column, first_column + " '" + Excerpt(cell.text) + "': " + problem + "; save the file as UTF-8 text");
      row.name = cell.text;
      row.values.push_back(0.0);
      row.columns.push_back(cell.column);
      continue;
    }
    const std::string what = c == 0 ? first_column : "column '" + table.ColumnName(c) + "'";
    double value = 0.0;
    switch (ParseNumber(cell.text, &value)) {
      case NumberStatus::kOk: break;
      case NumberStatus::kNotANumber:
        table.Fail(line_no, cell.column,
                   cell.text.empty() ? what + ": empty cell; every cell needs a number"
                                     : what + ": '" + Excerpt(cell.text) + "' is not a number");
      case NumberStatus::kNotFinite:
        table.Fail(line_no, cell.column, what + ": '" + Excerpt(cell.text) + "' is not finite; values must be finite");
      case NumberStatus::kOutOfRange:
        table.Fail(line_no, cell.column, what + ": '" + Excerpt(cell.text) + "' is outside the range of a double");
    }
    row.values.push_back(value);
    row.columns.push_back(cell.column);
  }
  table.rows.push_back(std::move(row));
}

}  // namespace

std::size_t NumericTable::columns() const {
  if (!header.empty()) return header.size();
  return rows.empty() ? 0 : rows.front().values.size();
}

std::string NumericTable::ColumnName(std::size_t c) const {
  return c < header.size() ? header[c] : unnamed_prefix + std::to_string(c);
}

void NumericTable::Fail(int line, int column, const std::string& message) const {
  throw InputError(name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message);
}

namespace {

NumericTable ParseText(const std::string& text, const std::string& name, const NumericTableOptions& options) {
  NumericTable table;
  table.name = name;
  table.unnamed_prefix = options.unnamed_prefix;
  TextLines lines(text, name);
  std::string line;
  while (lines.Next(line)) {
    const int line_no = lines.line_number();
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) {
      if (Trim(line.substr(0, hash)).empty()) {
        Comment(table, options.metadata_keys, line, hash, line_no);
        continue;
      }
      line.erase(hash);  // trailing comment after data
    }
    if (Trim(line).empty()) continue;
    Row(table, SplitCells(line), line_no, line, options);
  }
  return table;
}

}  // namespace

NumericTable ParseNumericTable(std::istream& in, const std::string& name, const NumericTableOptions& options) {
  return ParseText(ReadBoundedStream(in, name, limits::kMaxTextFileBytes), name, options);
}

NumericTable ReadNumericTable(const std::string& path, const NumericTableOptions& options,
                              const std::string& what) {
  return ParseText(ReadInputFile(path, what, limits::kMaxTextFileBytes), path, options);
}

}  // namespace deb
