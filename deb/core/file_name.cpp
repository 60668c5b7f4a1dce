#include "deb/core/file_name.h"

namespace deb {

std::string FileNameWord(const std::string& text) {
  std::string word = text;
  for (char& c : word)
    if (!IsFileNameCharacter(c)) c = '_';
  return word;
}

}  // namespace deb
