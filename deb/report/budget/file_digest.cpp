#include "deb/report/budget/file_digest.h"

#include <nettle/sha2.h>

#include <array>
#include <fstream>

#include "deb/core/error.h"

namespace deb::report {
namespace {

std::string Finish(sha256_ctx* ctx) {
  std::array<unsigned char, SHA256_DIGEST_SIZE> digest{};
  sha256_digest(ctx, digest.size(), digest.data());
  constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * digest.size());
  for (const unsigned char byte : digest) {
    hex += kHex[byte >> 4];
    hex += kHex[byte & 0xf];
  }
  return hex;
}

}  // namespace

std::string Sha256(const std::string& bytes) {
  sha256_ctx ctx;
  sha256_init(&ctx);
  sha256_update(&ctx, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  return Finish(&ctx);
}

std::string FileSha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path + " to compute its SHA-256");
  sha256_ctx ctx;
  sha256_init(&ctx);
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0)
      sha256_update(&ctx, static_cast<std::size_t>(in.gcount()), reinterpret_cast<const std::uint8_t*>(buffer.data()));
  }
  if (in.bad()) throw InputError("cannot read " + path + " to compute its SHA-256");
  return Finish(&ctx);
}

}  // namespace deb::report
