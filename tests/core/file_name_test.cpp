#include "deb/core/file_name.h"

#include <doctest/doctest.h>

namespace deb {
namespace {

TEST_CASE("a file-name word keeps ASCII letters, digits, '_', '-' and '.' and turns everything else into '_'") {
  CHECK(FileNameWord("stage/amplifier") == "stage_amplifier");
  CHECK(FileNameWord("z_v-1.2") == "z_v-1.2");
  CHECK(FileNameWord("a b|c;d'e\"f`g$h") == "a_b_c_d_e_f_g_h");
  CHECK(FileNameWord("\xc3\xa9") == "__");  // UTF-8 'é': two bytes, two '_'
  CHECK(FileNameWord("") == "");
  CHECK(FileNameWord("..") == "..");  // a word, not a path check: the callers refuse "." and ".."
  for (int c = 0; c < 256; ++c) {
    const char ch = static_cast<char>(c);
    const bool expected = (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' ||
                          c == '-' || c == '.';
    CHECK_MESSAGE(IsFileNameCharacter(ch) == expected, "character ", c);
  }
}

}  // namespace
}  // namespace deb
