// Internal: not part of the public API.
// The one rule for text that becomes part of a file or directory name
// (a budget's name, an output's CSV, a plot's file, a group's or a compared
// label's directory): ASCII letters, digits, '_', '-' and '.', nothing that
// a shell, a path or another system could read otherwise.
#pragma once

#include <string>

namespace deb {

// True for a character a file-name word may hold.
constexpr bool IsFileNameCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == '.';
}

// `text` with every character IsFileNameCharacter refuses replaced by '_'
// ("stage/amplifier" -> "stage_amplifier"). Not shortened; "" stays "".
std::string FileNameWord(const std::string& text);

}  // namespace deb
