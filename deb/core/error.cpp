#include "deb/core/error.h"

#include <cstdio>
#include <cstdlib>

namespace deb {

std::string FormatInputError(const InputLocation& where, const std::string& message) {
  std::string s = where.file;
  if (!s.empty() && where.line > 0) s += ":" + std::to_string(where.line) + ":" + std::to_string(where.column);
  if (!where.key_path.empty()) s += (s.empty() ? "" : ": ") + where.key_path;
  return s.empty() ? message : s + ": " + message;
}

void DemandFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "deb: internal error: %s failed at %s:%d\n", condition, file, line);
  std::abort();
}

}  // namespace deb
