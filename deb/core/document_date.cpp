#include "deb/core/document_date.h"

#include <cstdlib>

namespace deb {

std::optional<std::time_t> SourceDateEpoch() {
  const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
  if (epoch == nullptr) return std::nullopt;
  char* end = nullptr;
  const long long v = std::strtoll(epoch, &end, 10);
  if (end == nullptr || end == epoch || *end != '\0') return std::nullopt;
  return static_cast<std::time_t>(v);
}

std::time_t DocumentTime() { return SourceDateEpoch().value_or(std::time(nullptr)); }

std::string UtcText(std::time_t t, const char* format) {
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[64];
  const std::size_t n = std::strftime(text, sizeof text, format, &utc);
  return std::string(text, n);
}

}  // namespace deb
