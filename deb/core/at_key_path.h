// Internal: not part of the public API.
// Locating errors of library code that the caller described by key path: a
// function given "paths[2].of[1]" throws InputError(key_path, message) for a
// rule that part breaks, and the YAML loader turns the key path into
// file:line:col (deb/load). AtKeyPath gives the same location to errors of the
// functions it calls, which know no key paths.
#pragma once

#include <string>

#include "deb/core/error.h"

namespace deb {

// Runs f; an InputError without a key path is re-thrown at `key_path`
// (unless that is empty too).
template <typename F>
auto AtKeyPath(const std::string& key_path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    if (!e.key_path().empty() || key_path.empty()) throw;
    throw InputError(key_path, e.what());
  }
}

}  // namespace deb
