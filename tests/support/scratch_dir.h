// A directory of a test's own files, named after the test and its process,
// made empty when created and removed with everything in it when the test
// ends; Write puts a file in it (subdirectories made as needed).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace deb::test {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : dir_(std::filesystem::temp_directory_path() / ("deb_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() { std::filesystem::remove_all(dir_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& bytes) const {
    std::filesystem::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return Path(name);
  }

 private:
  std::filesystem::path dir_;
};

}  // namespace deb::test
