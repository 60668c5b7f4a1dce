// Whether a part of a variance is zero but for rounding, and the part as a
// reader is shown it: one rule for the report's tables, keys and bars and
// for `deb compare`'s figures.
#pragma once

namespace deb {

// At most 1e-24 of its whole (an RMS 1e-12 of the whole's), e.g. a source
// channel that a symmetric model does not couple to the output, computed as
// 1e-16 of the others. Tables, the console and comparisons show it as 0.
inline bool RoundingZero(double part_variance, double whole_variance) {
  return part_variance <= 1e-24 * whole_variance;
}

// The part as tables, keys, bars and comparisons show it: 0 where RoundingZero.
inline double WithoutRounding(double part_variance, double whole_variance) {
  return RoundingZero(part_variance, whole_variance) ? 0.0 : part_variance;
}

}  // namespace deb
