// What tabulated data (a measured spectrum, a measured frequency response)
// does at a frequency outside its range. The default is an error: a budget
// must not silently invent data, so holding or zeroing is the user's choice.
#pragma once

#include <string>

namespace deb {

enum class Extrapolation {
  kError,  // throw InputError naming the frequency and the data range
  kZero,   // zero outside the data
  kHold,   // the value at the nearest end of the data
};

// "error", "zero", "hold".
std::string ToString(Extrapolation extrapolation);
// @throws InputError naming the text and listing the allowed values.
Extrapolation ParseExtrapolation(const std::string& text);

}  // namespace deb
