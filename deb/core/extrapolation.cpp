#include "deb/core/extrapolation.h"

#include "deb/core/error.h"

namespace deb {

std::string ToString(Extrapolation extrapolation) {
  switch (extrapolation) {
    case Extrapolation::kError: return "error";
    case Extrapolation::kZero: return "zero";
    case Extrapolation::kHold: return "hold";
  }
  DEB_DEMAND(false);
  return {};
}

Extrapolation ParseExtrapolation(const std::string& text) {
  for (auto e : {Extrapolation::kError, Extrapolation::kZero, Extrapolation::kHold}) {
    if (text == ToString(e)) return e;
  }
  throw InputError("unknown extrapolation '" + text + "'; allowed: error, zero, hold");
}

}  // namespace deb
