// The data of a figure's CSV as the plot tests read it: blocks apart by two
// blank lines (gnuplot's `index`), comment and header lines skipped.
#pragma once

#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace deb::test {

// The data rows of block `index`, each split at its commas: the lines that
// start with a number (a digit, '-', or 'N' of NaN).
inline std::vector<std::vector<std::string>> CsvBlockRows(const std::string& csv, int index) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(csv);
  std::string line;
  int block = 0, blank = 0;
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (++blank == 2) ++block;
      continue;
    }
    blank = 0;
    if (block != index || !(std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-' || line[0] == 'N'))
      continue;
    std::vector<std::string> row;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(f);
    rows.push_back(row);
  }
  return rows;
}

// Column `column` (0-based) of block `index`'s rows, as numbers.
inline std::vector<double> CsvBlockColumn(const std::string& csv, int index, std::size_t column) {
  std::vector<double> v;
  for (const auto& row : CsvBlockRows(csv, index))
    if (column < row.size()) v.push_back(std::stod(row[column]));
  return v;
}

}  // namespace deb::test
