// What every fuzz target shares: the harness rule and a private temp file.
//
// Harness rule: an InputError is the reader's expected answer to bad input
// and is ignored; any other exception escaping the reader is a finding, so
// it is printed and the process aborts (libFuzzer then saves the input).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "deb/core/error.h"

namespace deb_fuzz {

// Inputs larger than this are skipped: the readers' files are small, and
// huge inputs only slow the search down.
constexpr std::size_t kMaxInput = 1 << 20;

template <class Read>
void ExpectOnlyInputError(const char* what, Read read) {
  try {
    read();
  } catch (const deb::InputError&) {
    // Bad input, reported as such: the expected answer.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: %s threw a non-InputError exception: %s\n", what, e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "FINDING: %s threw a non-std::exception\n", what);
    std::abort();
  }
}

// A directory only this process uses (mkdtemp, created on first use and
// removed at a normal exit; a crash leaves it in /tmp), so parallel fuzzing
// processes never share files.
inline const char* PrivateDir() {
  static char dir[] = "/tmp/deb_fuzz_XXXXXX";  // a plain array: still there when atexit runs
  static const bool made = [] {
    if (!mkdtemp(dir)) {
      std::perror("deb fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] { std::error_code ignored; std::filesystem::remove_all(dir, ignored); });
    return true;
  }();
  (void)made;
  return dir;
}

// Writes data to PrivateDir()/file_name (replacing it) and returns the path.
inline std::string WriteTempFile(const std::string& file_name, const std::uint8_t* data, std::size_t size) {
  const std::string path = std::string(PrivateDir()) + "/" + file_name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) {
    std::perror("deb fuzz: writing the temp file");
    std::abort();
  }
  return path;
}

}  // namespace deb_fuzz
