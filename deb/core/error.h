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

// Where an input error is; every part is optional.
struct InputLocation {
  std::string file;      // the input file; "" if unknown
  int line = 0;          // 1-based; 0 if unknown (then column is unknown too)
  int column = 0;        // 1-based
  std::string key_path;  // in a budget, e.g. "contributors[1].source"; "" if none
};

// "file:line:col: key.path: message", leaving out the parts not known.
std::string FormatInputError(const InputLocation& where, const std::string& message);

class InputError : public std::runtime_error {
 public:
  // A message that says where by itself (or needs no place).
  explicit InputError(const std::string& message) : InputError(InputLocation{}, message) {}
  // key_path locates the offending value in the budget; the budget's
  // KeyPositions (deb/core/key_positions.h) turn it into file:line:col.
  InputError(std::string key_path, const std::string& message)
      : InputError(InputLocation{"", 0, 0, std::move(key_path)}, message) {}
  InputError(InputLocation where, const std::string& message)
      : std::runtime_error(FormatInputError(where, message)), where_(std::move(where)), message_(message) {}

  // what() is FormatInputError(location(), message()).
  const InputLocation& location() const { return where_; }
  const std::string& file() const { return where_.file; }
  int line() const { return where_.line; }
  int column() const { return where_.column; }
  const std::string& key_path() const { return where_.key_path; }
  // It names a file or a key path (else only its message may say where).
  bool located() const { return !where_.file.empty() || !where_.key_path.empty(); }
  // The rule that was broken, without the location.
  const std::string& message() const { return message_; }

 private:
  InputLocation where_;
  std::string message_;
};

class WriteError : public std::runtime_error {
 public:
  explicit WriteError(const std::string& message) : std::runtime_error(message) {}
};

[[noreturn]] void DemandFailed(const char* condition, const char* file, int line);

}  // namespace deb

#define DEB_DEMAND(condition) \
  do { if (!(condition)) ::deb::DemandFailed(#condition, __FILE__, __LINE__); } while (0)
