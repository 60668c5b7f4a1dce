// Three failure channels, as in the rest of deb:
//  - InputError: the user's input (budget file, data file, parameters) breaks a
//    rule. Thrown, caught by the CLI, reported with where/what/rule, exit 3.
//  - WriteError: deb cannot write its output (a report directory, a CSV, a
//    plot): the target is not deb's to replace, the disk is full, gnuplot is
//    missing or fails. Exit 4.
//  - DEB_DEMAND: a programming error (a broken internal invariant). Aborts with
//    file:line, because continuing would produce wrong numbers.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace deb {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // key_path locates the offending value in the budget, e.g.
  // "contributors[1].source"; the YAML loader turns it into file:line:col.
  InputError(std::string key_path, const std::string& message)
      : std::runtime_error(message), key_path_(std::move(key_path)) {}

  const std::string& key_path() const { return key_path_; }

 private:
  std::string key_path_;
};

class WriteError : public std::runtime_error {
 public:
  explicit WriteError(const std::string& message) : std::runtime_error(message) {}
};

[[noreturn]] void DemandFailed(const char* condition, const char* file, int line);

}  // namespace deb

#define DEB_DEMAND(condition) \
  do { if (!(condition)) ::deb::DemandFailed(#condition, __FILE__, __LINE__); } while (0)
