#include "deb/core/process_heap.h"

#include <cstdint>
#include <cstdlib>

// AddressSanitizer brings its own allocator: the C library's heap settings
// would not apply to it.
#if defined(__SANITIZE_ADDRESS__)
#define DEB_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DEB_ADDRESS_SANITIZER 1
#endif
#endif
#ifndef DEB_ADDRESS_SANITIZER
#define DEB_ADDRESS_SANITIZER 0
#endif

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

#if defined(__linux__) && defined(__GLIBC__) && defined(MADV_HUGEPAGE) && !DEB_ADDRESS_SANITIZER
#define DEB_ADVISE_HEAP 1
#else
#define DEB_ADVISE_HEAP 0
#endif

namespace deb {
namespace {

#if DEB_ADVISE_HEAP
// Volatile: an allocation nobody reads may otherwise be optimised away.
void* volatile below_first_huge_page = nullptr;
#endif

}  // namespace

bool UseHugePagesForHeap(int step_mib) {
#if DEB_ADVISE_HEAP
  if (step_mib < 4) return false;
  const std::size_t step = static_cast<std::size_t>(step_mib) << 20;
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  // Keep what is freed (trimming would give the pages back, to be faulted
  // again), and serve blocks up to the step from the heap, not from mmap.
  if (mallopt(M_TRIM_THRESHOLD, static_cast<int>(4 * step)) != 1) return false;
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(2 * step));
  // A block of one step extends the heap untouched but for its header below
  // it and the top's header above it: the 2 MiB pages strictly inside it have
  // no small page yet, which the kernel needs to give a huge one on a fault.
  char* const probe = static_cast<char*>(std::malloc(step));
  if (probe == nullptr) return false;
  const auto at = reinterpret_cast<std::uintptr_t>(probe);
  const auto begin = (at + kHuge - 1) & ~(kHuge - 1);
  const auto end = (at + step) & ~(kHuge - 1);
  std::free(probe);
  if (end <= begin || madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE) != 0) return false;
  // The run's allocations start at the first huge page: the heap below it is
  // held by a block that is never touched (no resident memory) nor freed.
  if (begin - at > 64) below_first_huge_page = std::malloc(begin - at - 64);
  // Later growth comes in steps too.
  mallopt(M_TOP_PAD, static_cast<int>(step));
  return true;
#else
  (void)step_mib;
  return false;
#endif
}

}  // namespace deb
