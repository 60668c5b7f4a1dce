#include "deb/core/process_heap.h"

#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

namespace deb {
namespace {

// The kernel's THP mode, the word in brackets of
// /sys/kernel/mm/transparent_hugepage/enabled ("" where there is none).
std::string ThpMode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

// The "THPeligible:" value of the mapping that holds `address`, -1 if none.
int ThpEligible(const void* address) {
  std::ifstream in("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= a && a < hi;
    } else if (inside && line.rfind("THPeligible:", 0) == 0) {
      return std::stoi(line.substr(12));
    }
  }
  return -1;
}

TEST_CASE("after UseHugePagesForHeap the heap's new blocks lie in memory advised for huge pages") {
  const bool advised = UseHugePagesForHeap();
  const std::size_t size = 512 * 1024;
  char* block = static_cast<char*>(std::malloc(size));
  REQUIRE(block != nullptr);
  std::memset(block, 1, size);  // usable memory
  CHECK(block[size - 1] == 1);
  const std::string mode = ThpMode();
  if (!advised) {
    MESSAGE("the heap was not advised here (no glibc heap, or AddressSanitizer's allocator)");
  } else if (mode != "madvise" && mode != "always") {
    MESSAGE("transparent huge pages are '" << mode << "' here: nothing to advise");
  } else {
    // (The block's first bytes may share a page with the heap below.)
    CHECK(ThpEligible(block + 4096) == 1);
    CHECK(ThpEligible(block + size - 1) == 1);
  }
  std::free(block);
}

TEST_CASE("UseHugePagesForHeap may be called again and leaves malloc working") {
  UseHugePagesForHeap();
  CHECK_FALSE(UseHugePagesForHeap(2));  // below the smallest step: does nothing
  for (int i = 0; i < 1000; ++i) {
    char* p = static_cast<char*>(std::malloc(1000 + i));
    REQUIRE(p != nullptr);
    p[0] = 'x';
    std::free(p);
  }
}

}  // namespace
}  // namespace deb
