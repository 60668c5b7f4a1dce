// Internal: not part of the public API.
// SHA-256 of a file, so that a report names exactly the budget it was made
// from. The only code in deb that uses Nettle (Debian: nettle-dev), a
// maintained implementation rather than a hand-written one. Nettle, not
// OpenSSL's libcrypto: one hash needs no provider lookup and no library-wide
// initialisation, which cost libcrypto about 5 million instructions (a sixth
// of a thesis budget's run) and a third of deb's binary.
#pragma once

#include <string>

namespace deb::report {

// Lower-case hexadecimal SHA-256 of the bytes of `path` (64 characters).
// @throws InputError if the file cannot be read.
std::string FileSha256(const std::string& path);

// The same of a byte string.
std::string Sha256(const std::string& bytes);

}  // namespace deb::report
