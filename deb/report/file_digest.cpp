#include "deb/report/file_digest.h"

#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>

#include "deb/core/error.h"

namespace deb::report {
namespace {

using Context = std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)>;

Context NewContext() {
  Context ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  DEB_DEMAND(ctx && EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) == 1);
  return ctx;
}

std::string Finish(EVP_MD_CTX* ctx) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int size = 0;
  DEB_DEMAND(EVP_DigestFinal_ex(ctx, digest.data(), &size) == 1 && size == 32);
  std::string hex;
  char byte[3];
  for (unsigned int i = 0; i < size; ++i) {
    std::snprintf(byte, sizeof(byte), "%02x", digest[i]);
    hex += byte;
  }
  return hex;
}

}  // namespace

std::string Sha256(const std::string& bytes) {
  Context ctx = NewContext();
  DEB_DEMAND(EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size()) == 1);
  return Finish(ctx.get());
}

std::string FileSha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path + " to compute its SHA-256");
  Context ctx = NewContext();
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0) DEB_DEMAND(EVP_DigestUpdate(ctx.get(), buffer.data(), static_cast<std::size_t>(in.gcount())) == 1);
  }
  if (in.bad()) throw InputError("cannot read " + path + " to compute its SHA-256");
  return Finish(ctx.get());
}

}  // namespace deb::report
