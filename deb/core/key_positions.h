// Where every key path of a loaded file stands. The loader records each node
// once, as it first parses the file, and the positions stay with what was
// loaded (Budget::positions): an error found later that knows only its key
// path (the engine's, the report's) is reported at file:line:col without
// reading the file again. A budget that extends another (`extends:`) keeps
// each key path's position in the file that gave it.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "deb/core/error.h"

namespace deb {

class KeyPositions {
 public:
  explicit KeyPositions(std::string file) : files_{std::move(file)} {}

  // The file that was loaded (of a budget that extends another, the last).
  const std::string& file() const { return files_.front(); }
  // A position in file(); line and column 1-based; the first record of a key
  // path stays.
  void Record(const std::string& key_path, int line, int column);
  // Every position of `base` whose key path is not recorded here, in its own
  // file: the positions of a budget that extends `base` (what it does not
  // give itself comes from there).
  void Inherit(const KeyPositions& base);
  std::size_t size() const { return positions_.size(); }

  // key_path at its own position, or at its closest recorded parent's
  // ("a.b[2].c", "a.b[2]", "a.b", "a"); at the file alone if none is recorded
  // (a key the file does not have, e.g. the grid of a budget without one).
  InputLocation Locate(const std::string& key_path) const;
  // e at Locate(e.key_path()), its message prefixed by `note` if one is given
  // ("sweep variant 2 (...)"); e unchanged if it has no key path or a file already.
  InputError Located(const InputError& e, const std::string& note = "") const;

 private:
  struct Position {
    std::size_t file;  // index into files_
    int line, column;
  };
  std::vector<std::string> files_;  // files_[0] is file()
  std::unordered_map<std::string, Position> positions_;
};

}  // namespace deb
