#include "deb/report/budget/file_digest.h"

#include <doctest/doctest.h>

#include "deb/core/error.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("SHA-256 matches the FIPS 180-2 test vectors") {
  CHECK(Sha256("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(Sha256("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(Sha256("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST_CASE("the SHA-256 of a file is that of its bytes, also across read buffers") {
  const auto dir = test::TempDir("digest");
  const std::string bytes(200000, 'a');
  test::WriteFile(dir / "a.txt", bytes);
  CHECK(FileSha256((dir / "a.txt").string()) == Sha256(bytes));
  CHECK_THROWS_WITH_AS(FileSha256((dir / "missing").string()), doctest::Contains("cannot read"), InputError);
}

}  // namespace deb::report
