#include "deb/core/enum_names.h"

#include <cctype>
#include <cstring>

namespace deb::enum_names {

bool Matches(const std::string& text, const char* name, NameCase name_case) {
  if (name_case == NameCase::kExact) return text == name;
  if (text.size() != std::strlen(name)) return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[i])) != std::tolower(static_cast<unsigned char>(name[i])))
      return false;
  }
  return true;
}

void ThrowUnknown(const std::string& what, const std::string& text, const std::string& allowed,
                  const std::string& key_path) {
  const std::string message = "unknown " + what + " '" + text + "'; allowed: " + allowed;
  if (key_path.empty()) throw InputError(message);
  throw InputError(key_path, message);
}

}  // namespace deb::enum_names
