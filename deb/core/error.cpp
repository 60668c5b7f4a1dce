#include "deb/core/error.h"

#include <cstdio>
#include <cstdlib>

namespace deb {

void DemandFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "deb: internal error: %s failed at %s:%d\n", condition, file, line);
  std::abort();
}

}  // namespace deb
