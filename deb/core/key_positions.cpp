#include "deb/core/key_positions.h"

namespace deb {

void KeyPositions::Record(const std::string& key_path, int line, int column) {
  positions_.emplace(key_path, Position{0, line, column});
}

void KeyPositions::Inherit(const KeyPositions& base) {
  std::vector<std::size_t> index_of;  // base's file index -> ours
  for (const std::string& f : base.files_) {
    std::size_t i = 0;
    while (i < files_.size() && files_[i] != f) ++i;
    if (i == files_.size()) files_.push_back(f);
    index_of.push_back(i);
  }
  for (const auto& [key, at] : base.positions_) positions_.emplace(key, Position{index_of[at.file], at.line, at.column});
}

InputLocation KeyPositions::Locate(const std::string& key_path) const {
  std::string k = key_path;
  while (true) {
    const auto it = positions_.find(k);
    if (it != positions_.end()) return {files_[it->second.file], it->second.line, it->second.column, key_path};
    const auto cut = k.find_last_of(".[");
    if (cut == std::string::npos) break;
    k.resize(cut);
  }
  return {file(), 0, 0, key_path};
}

InputError KeyPositions::Located(const InputError& e, const std::string& note) const {
  if (e.key_path().empty() || !e.file().empty()) return e;
  return InputError(Locate(e.key_path()), note.empty() ? e.message() : note + ": " + e.message());
}

}  // namespace deb
