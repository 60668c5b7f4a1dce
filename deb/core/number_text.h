// Internal: not part of the public API.
// Shortest decimal text that reads back to the same double, for error
// messages and Describe(): a message must quote the value the user wrote
// (0.1, not 0.10000000000000001) and still tell two close values apart; and
// for data files, whose numbers then read back exactly.
#pragma once

#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

namespace deb {

inline std::string NumberText(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// The same appended to `out` (no temporary string: data tables hold 10^5..10^6
// numbers).
inline void AppendNumberText(std::string& out, double value) {
  char buffer[32];
  out.append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), value).ptr);
}

// `value` to `digits` significant digits (printf's %g: "0.3127", "1.234e-05"),
// for figures a reader compares rather than reads back.
inline std::string SignificantText(double value, int digits = 4) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
  return buffer;
}

// `text` with its digits and minus signs as superscripts ("-12" -> "⁻¹²"),
// anything else as it is: exponents and note marks in a document's text.
inline std::string SuperscriptText(std::string_view text) {
  static const char* const kDigits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out;
  for (const char c : text) {
    if (c >= '0' && c <= '9') out += kDigits[c - '0'];
    else if (c == '-') out += "⁻";
    else out += c;
  }
  return out;
}

}  // namespace deb
