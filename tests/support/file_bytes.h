// A file's bytes, whole, for tests that read back or damage what a writer made.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace deb::test {

// "" if the file cannot be read.
inline std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace deb::test
