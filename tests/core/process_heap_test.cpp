#include "deb/core/process_heap.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#endif

#if defined(__SANITIZE_ADDRESS__)
#define DEB_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DEB_TEST_ASAN 1
#endif
#endif

namespace deb {
namespace {

#if defined(__linux__) && defined(__GLIBC__) && !defined(DEB_TEST_ASAN)
TEST_CASE("with the heap kept for large blocks, a 2000 x 2000 matrix comes from the heap and its pages stay after free") {
  REQUIRE(KeepHeapForLargeBlocks());
  // glibc's default serves 30.5 MiB (a dense 1000-mode model's n x n
  // matrix of doubles) from a mapping of its own (hblks counts them); kept,
  // from the heap.
  const std::size_t bytes = std::size_t{2000} * 2000 * sizeof(double);
  const auto mapped_before = mallinfo2().hblks;
  char* const block = static_cast<char*>(std::malloc(bytes));
  REQUIRE(block != nullptr);
  std::memset(block, 1, bytes);
  CHECK(mallinfo2().hblks == mapped_before);
  const std::size_t arena = mallinfo2().arena;
  std::free(block);
  // Not trimmed: the heap keeps its size (below the 128 MiB trim threshold).
  CHECK(mallinfo2().arena == arena);
}
#endif

}  // namespace
}  // namespace deb
