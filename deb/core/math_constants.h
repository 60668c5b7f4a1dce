// Internal: not part of the public API.
// pi and 2 pi as doubles, one definition for every file that converts
// between Hz and rad/s or degrees and radians.
#pragma once

namespace deb {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 6.28318530717958647693;  // exactly 2 kPi in double

}  // namespace deb
