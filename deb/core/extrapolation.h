// What tabulated data (a measured spectrum, a measured frequency response)
// does at a frequency outside its range. The default is an error: a budget
// must not silently invent data, so holding or zeroing is the user's choice.
#pragma once

#include <string>

#include "deb/core/enum_names.h"

namespace deb {

enum class Extrapolation {
  kError,  // throw InputError naming the frequency and the data range
  kZero,   // zero outside the data
  kHold,   // the value at the nearest end of the data
};

inline constexpr EnumName<Extrapolation> kExtrapolationNames[] = {
    {Extrapolation::kError, "error"}, {Extrapolation::kZero, "zero"}, {Extrapolation::kHold, "hold"}};
constexpr EnumNames<Extrapolation> NamesOf(Extrapolation) { return kExtrapolationNames; }

// @throws InputError naming the text and listing the allowed values.
inline Extrapolation ParseExtrapolation(const std::string& text) {
  return ParseEnum<Extrapolation>(text, "extrapolation");
}

}  // namespace deb
