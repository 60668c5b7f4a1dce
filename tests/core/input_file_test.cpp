// deb/core/input_file.h: the UTF-8 rule every text read from a file obeys
// (RFC 3629's well-formed sequences, nothing else), and Excerpt, which
// quotes a file's text in a message: at most the cap, never half a
// character, no control byte and no byte that is not UTF-8.
#include <doctest/doctest.h>

#include <string>

#include "deb/core/input_file.h"

namespace deb {
namespace {

TEST_CASE("UTF-8 is accepted in every length of sequence; what RFC 3629 excludes is refused at its byte") {
  CHECK(FirstNonUtf8("") == std::string::npos);
  CHECK(FirstNonUtf8("plain ASCII, 0-9") == std::string::npos);
  CHECK(FirstNonUtf8("\xC2\xB5m/s \xE2\x80\x93 \xF0\x9F\x98\x80") == std::string::npos);  // µ, en dash, U+1F600
  CHECK(FirstNonUtf8("caf\xE9") == 3);                  // Latin-1 é
  CHECK(FirstNonUtf8("x\xFF") == 1);                    // never in UTF-8
  CHECK(FirstNonUtf8("\xC0\xAF") == 0);                 // overlong '/'
  CHECK(FirstNonUtf8("\xE0\x80\xAF") == 0);             // overlong, 3 bytes
  CHECK(FirstNonUtf8("a\xED\xA0\x80") == 1);            // a UTF-16 surrogate
  CHECK(FirstNonUtf8("\xF4\x90\x80\x80") == 0);         // above U+10FFFF
  CHECK(FirstNonUtf8("ok\xE2\x82") == 2);               // cut short
  CHECK(FirstNonUtf8("\x80") == 0);                     // a lone continuation byte
  CHECK(Utf8Problem("caf\xE9") == "byte 0xe9 at character 4 is not UTF-8");
  CHECK(Utf8Problem("caf\xC3\xA9").empty());
}

TEST_CASE("an excerpt keeps whole characters, caps the length and shows other bytes as '?'") {
  CHECK(Excerpt("short") == "short");
  CHECK(Excerpt(std::string(50, 'a')) == std::string(40, 'a') + "…");
  CHECK(Excerpt("\x1b[31mred\a") == "?[31mred?");
  CHECK(Excerpt("caf\xE9") == "caf?");
  CHECK(Excerpt("caf\xC3\xA9") == "caf\xC3\xA9");
  // A two-byte character across the cap is left out whole.
  CHECK(Excerpt("abc\xC3\xA9", 4) == "abc…");
}

}  // namespace
}  // namespace deb
