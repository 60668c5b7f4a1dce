#include "deb/core/key_positions.h"

namespace deb {

void KeyPositions::Record(const std::string& key_path, int line, int column) {
  positions_.emplace(key_path, std::make_pair(line, column));
}

InputLocation KeyPositions::Locate(const std::string& key_path) const {
  std::string k = key_path;
  while (true) {
    const auto it = positions_.find(k);
    if (it != positions_.end()) return {file_, it->second.first, it->second.second, key_path};
    const auto cut = k.find_last_of(".[");
    if (cut == std::string::npos) break;
    k.resize(cut);
  }
  return {file_, 0, 0, key_path};
}

InputError KeyPositions::Located(const InputError& e, const std::string& note) const {
  if (e.key_path().empty() || !e.file().empty()) return e;
  return InputError(Locate(e.key_path()), note.empty() ? e.message() : note + ": " + e.message());
}

}  // namespace deb
