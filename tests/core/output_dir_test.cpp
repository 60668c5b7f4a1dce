#include "deb/core/output_dir.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "deb/core/error.h"
#include "tests/support/scratch_dir.h"

namespace deb {

TEST_CASE("a text file written piece by piece holds the pieces in order; a failing producer leaves no file") {
  const test::ScratchDir dir("write_text_from");
  const std::string path = dir.Path("table.csv");
  WriteTextFileFrom(path, [](const TextSink& put) {
    put("a,b\n");
    for (int i = 0; i < 3; ++i) put(std::to_string(i) + "," + std::to_string(i * i) + "\n");
  });
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str() == "a,b\n0,0\n1,1\n2,4\n");
  const std::string broken = dir.Path("broken.csv");
  CHECK_THROWS_WITH_AS(WriteTextFileFrom(broken,
                                         [](const TextSink& put) {
                                           put("half");
                                           throw std::runtime_error("producer failed");
                                         }),
                       "producer failed", std::runtime_error);
  CHECK_FALSE(std::filesystem::exists(broken));
  // A directory that is not there: the WriteError names the file.
  const std::string nowhere = dir.Path("missing/table.csv");
  CHECK_THROWS_AS(WriteTextFileFrom(nowhere, [](const TextSink& put) { put("x"); }), WriteError);
  try {
    WriteTextFileFrom(nowhere, [](const TextSink& put) { put("x"); });
  } catch (const WriteError& e) {
    CHECK(std::string(e.what()).find("cannot write " + nowhere) != std::string::npos);
  }
}

TEST_CASE("a write that fails on a device leaves the device: only a partial regular file is removed") {
  // /dev/full takes the open and fails every write with ENOSPC. An earlier
  // WriteTextFile removed whatever path it had failed on, device nodes too.
  if (!std::filesystem::exists("/dev/full")) return;
  CHECK_THROWS_WITH_AS(WriteTextFile("/dev/full", std::string(1 << 16, 'x')),
                       doctest::Contains("No space left on device"), WriteError);
  CHECK(std::filesystem::exists("/dev/full"));
  CHECK_THROWS_AS(WriteTextFileFrom("/dev/full", [](const TextSink& put) { put(std::string(1 << 16, 'x')); }),
                  WriteError);
  CHECK(std::filesystem::exists("/dev/full"));
}

}  // namespace deb
