#include "deb/core/process_heap.h"

#include <cstdlib>  // defines __GLIBC__ where it is glibc

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#define DEB_GLIBC_HEAP 1
#else
#define DEB_GLIBC_HEAP 0
#endif

namespace deb {

bool KeepHeapForLargeBlocks() {
#if DEB_GLIBC_HEAP
  constexpr int kMiB = 1 << 20;
  return mallopt(M_MMAP_THRESHOLD, 32 * kMiB) == 1 && mallopt(M_TRIM_THRESHOLD, 128 * kMiB) == 1 &&
         mallopt(M_TOP_PAD, 8 * kMiB) == 1;
#else
  return false;
#endif
}

}  // namespace deb
