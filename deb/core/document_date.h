// Internal: not part of the public API.
// The date a document of deb carries (report.pdf, report.md, index.html,
// compare.pdf, result.xlsx): now, or $SOURCE_DATE_EPOCH, seconds since 1970,
// when it is set to a whole number: then two runs write the same files, byte
// for byte, and record no wall time.
#pragma once

#include <ctime>
#include <optional>
#include <string>

namespace deb {

// $SOURCE_DATE_EPOCH if set to a whole number; none otherwise (unset, or
// not a number: ignored).
std::optional<std::time_t> SourceDateEpoch();

// Whether documents are reproducible (SourceDateEpoch is set).
inline bool Reproducible() { return SourceDateEpoch().has_value(); }

// SourceDateEpoch, or now.
std::time_t DocumentTime();

// `t` in UTC, formatted by strftime (e.g. "%Y-%m-%dT%H:%M:%SZ").
std::string UtcText(std::time_t t, const char* format);

}  // namespace deb
