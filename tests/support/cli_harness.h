// What the CLI and report tests share: running the deb binary (DEB_BINARY)
// and other commands with stdout and stderr captured, temporary directories
// unique to this process, reading and writing files.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/file_bytes.h"

namespace deb::test {

namespace fs = std::filesystem;

struct Command {
  int exit_code = -1;  // -1: killed by a signal
  std::string out, err;
};

inline fs::path WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The directories TempDir made, removed when the test process exits (kept
// when DEB_KEEP_TEST_DIRS is set, to look at after a failure).
class TempDirs {
 public:
  void Add(const fs::path& d) {
    std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(d);
  }
  ~TempDirs() {
    if (std::getenv("DEB_KEEP_TEST_DIRS")) return;
    std::error_code ec;
    for (const fs::path& d : dirs_) fs::remove_all(d, ec);
  }

 private:
  std::mutex mutex_;
  std::vector<fs::path> dirs_;
};

// A fresh, empty directory: the process id and a counter make it unique to
// this call, so concurrent test processes never share one.
inline fs::path TempDir(const std::string& name) {
  static std::atomic<int> counter{0};
  static TempDirs made;
  const fs::path d = fs::temp_directory_path() /
                     ("deb_test_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::remove_all(d);
  fs::create_directories(d);
  made.Add(d);
  return d;
}

// The exit code of a std::system status; -1 if the command did not exit.
inline int ExitCode(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }

// Runs a shell command line, capturing stdout and stderr.
inline Command Shell(const std::string& command_line) {
  static const fs::path dir = TempDir("io");
  const fs::path out = dir / "stdout", err = dir / "stderr";
  const std::string cmd = command_line + " > \"" + out.string() + "\" 2> \"" + err.string() + "\"";
  Command r;
  r.exit_code = ExitCode(std::system(cmd.c_str()));
  r.out = ReadAll(out);
  r.err = ReadAll(err);
  return r;
}

// deb with arguments (shell syntax); `env` is prepended (e.g. "DEB_GNUPLOT=/nonexistent").
inline Command RunDeb(const std::string& args, const std::string& env = "") {
  return Shell((env.empty() ? "" : env + " ") + "\"" + DEB_BINARY + "\" " + args);
}

// deb run in `dir` (relative paths in args are relative to it).
inline Command RunDebIn(const fs::path& dir, const std::string& args, const std::string& env = "") {
  return Shell("cd \"" + dir.string() + "\" && " + (env.empty() ? "" : env + " ") + "\"" + DEB_BINARY + "\" " + args);
}

// A budget shipped in budgets/.
inline std::string ExampleBudget(const std::string& file = "single_axis_isolator.yaml") {
  return std::string(DEB_SOURCE_DIR) + "/budgets/" + file;
}

// Page count of a PDF according to pdfinfo (poppler-utils), -1 on failure.
inline int PdfPages(const fs::path& pdf) {
  const Command r = Shell("pdfinfo \"" + pdf.string() + "\"");
  if (r.exit_code != 0) return -1;
  std::istringstream lines(r.out);
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind("Pages:", 0) == 0) return std::stoi(line.substr(6));
  return -1;
}

// Entries of `dir` whose name starts with `prefix` (left-over temporaries).
inline int CountWithPrefix(const fs::path& dir, const std::string& prefix) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(prefix, 0) == 0) ++n;
  return n;
}

// The files of directory `a` (recursively) whose bytes differ in `b`, or
// that `b` lacks; *count the files of `a`.
inline std::vector<std::string> FilesDiffering(const fs::path& a, const fs::path& b, std::size_t* count) {
  std::vector<std::string> differ;
  *count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), a);
    if (!fs::exists(b / rel) || ReadAll(entry.path()) != ReadAll(b / rel)) differ.push_back(rel.string());
    ++*count;
  }
  return differ;
}

}  // namespace deb::test
