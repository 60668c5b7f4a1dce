// Reads the cited data tables under spectra/ ('#' comments, then CSV rows)
// so tests can compare them with the tables compiled into deb.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace deb::test {

struct DataFile {
  bool opened = false;
  std::string comments;                        // every '#' line, newline-terminated
  std::vector<std::vector<std::string>> rows;  // header row first
};

inline DataFile ReadDataFile(const std::string& path) {
  DataFile file;
  std::ifstream in(path);
  file.opened = in.good();
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      file.comments += line + "\n";
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream cells_in(line);
    std::string cell;
    while (std::getline(cells_in, cell, ',')) cells.push_back(cell);
    file.rows.push_back(cells);
  }
  return file;
}

}  // namespace deb::test
