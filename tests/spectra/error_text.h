// The message of the InputError an action throws, so tests can check that an
// error says where, what value and which rule.
#pragma once

#include <functional>
#include <string>

#include "deb/core/error.h"

namespace deb {

inline std::string InputErrorText(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no InputError thrown)";
}

}  // namespace deb
