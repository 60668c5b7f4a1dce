// Writes a Nastran punch file of real eigenvectors (the layout of
// deb/formats/nastran_punch.cpp: 72 columns of data and a sequence number),
// for the readers' tests: one $EIGENVECTOR block per mode, each grid a line
// of T1 T2 T3 and a -CONT- line of R1 R2 R3, printed as Nastran prints them
// (E13.6), so that a value is read back as the text says.
#pragma once

#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace deb::test {

// `eigenvalues[k]` and `shapes[k]` (grid -> T1..R3) of mode k + 1.
inline void WritePunchModes(const std::string& path, const std::vector<double>& eigenvalues,
                            const std::vector<std::map<long long, std::vector<double>>>& shapes) {
  std::ofstream out(path);
  int line = 0;
  char buffer[128], text[100];
  const auto put = [&](const char* t) {
    std::snprintf(buffer, sizeof(buffer), "%-72s%8d\n", t, ++line);
    out << buffer;
  };
  for (std::size_t k = 0; k < eigenvalues.size(); ++k) {
    put("$TITLE   = SIMPLE BEAM EXAMPLE");
    put("$SUBTITLE= MODES");
    put("$LABEL   =");
    put("$EIGENVECTOR");
    put("$REAL OUTPUT");
    put("$SUBCASE ID =           1");
    std::snprintf(text, sizeof(text), "$EIGENVALUE = %14.7E  MODE = %5zu", eigenvalues[k], k + 1);
    put(text);
    for (const auto& [grid, v] : shapes[k]) {
      std::snprintf(text, sizeof(text), "%10lld       G     %13.6E     %13.6E     %13.6E", grid, v[0], v[1], v[2]);
      put(text);
      std::snprintf(text, sizeof(text), "-CONT-                 %13.6E     %13.6E     %13.6E", v[3], v[4], v[5]);
      put(text);
    }
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace deb::test
