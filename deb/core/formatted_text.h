// Internal: not part of the public API.
// printf onto the end of a string: the console texts (deb run's summary, deb
// check's description) are built as strings, so that a test reads them and
// a command prints them in one piece, with printf's column formats.
#pragma once

#include <string>

namespace deb {

// Appends the text printf(format, ...) would print to `out`.
__attribute__((format(printf, 2, 3))) void AppendFormatted(std::string& out, const char* format, ...);

}  // namespace deb
