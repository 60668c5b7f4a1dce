// Whether an error message (or any text) holds a part: the one helper the
// suites share for assertions on messages.
#pragma once

#include <string>

namespace deb::test {

inline bool Contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace deb::test
