// Internal: not part of the public API.
// The small text table every deb data file shares (measured spectra, measured
// frequency responses): numbers in rows, cells separated by commas (when a
// line has one) or by whitespace, '#' starting a comment, an optional header
// row of column names, and "# key: value" lines carrying metadata. The reader
// checks only what every such file needs: each cell a finite number, every
// row as long as the first. What the columns mean (a frequency that must
// increase, a value that must not be negative) is the caller's rule, and
// Fail() lets the caller report it at the cell's file:line:column.
#pragma once

#include <iosfwd>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace deb {

struct NumericTable {
  struct Row {
    int line = 0;                // 1-based line number in the file
    std::vector<double> values;  // one per column
    std::vector<int> columns;    // 1-based character position of each cell
    // With NumericTableOptions::names_in_first_column: the first cell's text
    // (values[0] is then 0 and means nothing); empty otherwise.
    std::string name;
  };
  struct Meta {
    std::string value;
    int line = 0, column = 0;    // position of the value
  };

  std::string name;                      // the file name, for messages
  std::vector<std::string> header;       // column names from a header row; empty if none
  std::vector<int> header_columns;       // 1-based character position of each name
  int header_line = 0;                   // its line, or 0
  std::vector<Row> rows;
  std::map<std::string, Meta> metadata;  // lower-case key -> value, for the keys asked for

  std::string unnamed_prefix = "column ";  // see NumericTableOptions

  std::size_t columns() const;  // cells per row (0 for an empty table)
  // Name of column c (0-based): from the header, else unnamed_prefix + c
  // ("column 1" is the second column: the first is the abscissa).
  std::string ColumnName(std::size_t c) const;
  // @throws InputError "name:line:column: message".
  [[noreturn]] void Fail(int line, int column, const std::string& message) const;
};

struct NumericTableOptions {
  std::set<std::string> metadata_keys;    // lower case: the "# key: value" lines to collect
  std::string first_column = "frequency";  // how messages name the first column
  std::string unnamed_prefix = "column ";  // column c >= 1 without a header: prefix + c
  // The first cell of every row is a name (a label such as a DOF), not a
  // number: it goes to Row::name, must not be empty, and the first
  // non-comment line is always the header row (required).
  bool names_in_first_column = false;
};

// Reads a table. Comments other than the metadata keys are ignored. A data line's trailing "# ..." is a
// comment. The first non-comment line is a header row if its first cell is
// not a number (always, with names_in_first_column).
// @throws InputError at file:line:column for a cell that is not a finite
//   number, a row with another number of cells than the first, an empty
//   column name, a metadata key given twice or without a value.
NumericTable ParseNumericTable(std::istream& in, const std::string& name, const NumericTableOptions& options);

// Same, from a file. @throws InputError if it cannot be opened.
NumericTable ReadNumericTable(const std::string& path, const NumericTableOptions& options,
                              const std::string& what = "data file");

}  // namespace deb
