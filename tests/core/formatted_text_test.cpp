#include "deb/core/formatted_text.h"

#include <doctest/doctest.h>

#include <string>

namespace deb {

TEST_CASE("formatted text is appended as printf prints it, however long") {
  std::string text = "a";
  AppendFormatted(text, " %-4s|%6.2f%%", "x", 12.345);
  CHECK(text == "a x   | 12.35%");
  AppendFormatted(text, "%s", "");
  CHECK(text == "a x   | 12.35%");
  const std::string long_name(5000, 'n');
  AppendFormatted(text, "[%s]", long_name.c_str());
  CHECK(text.size() == 14 + 5002);
  CHECK(text.back() == ']');
}

}  // namespace deb
