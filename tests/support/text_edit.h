// Breaking one rule at a time: a text (a budget, a data file) with one part
// replaced, and the message of the InputError a loader throws for it. The
// helpers the suites share instead of a copy each.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "deb/core/error.h"

namespace deb::test {

// `text` with the first `from` replaced by `to`; the test stops, naming
// `from`, if it is not there.
inline std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, from);
  return text.replace(at, from.size(), to);
}

// The message of the InputError fn() throws, or "(no error)".
template <typename Fn>
std::string InputErrorOf(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace deb::test
