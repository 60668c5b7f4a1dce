#include "deb/core/formatted_text.h"

#include <cstdarg>
#include <cstdio>

namespace deb {

void AppendFormatted(std::string& out, const char* format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  if (n > 0) {
    const std::size_t end = out.size();
    out.resize(end + static_cast<std::size_t>(n) + 1);  // vsnprintf writes the terminating NUL too
    std::vsnprintf(&out[end], static_cast<std::size_t>(n) + 1, format, again);
    out.resize(end + static_cast<std::size_t>(n));
  }
  va_end(again);
}

}  // namespace deb
