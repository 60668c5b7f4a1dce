// A closed interval of frequencies [lo_hz, hi_hz], such as the range over
// which tabulated data (a measured spectrum, a measured frequency response)
// may be evaluated when extrapolating it is an error.
#pragma once

#include <algorithm>
#include <optional>

namespace deb {

struct FrequencyInterval {
  double lo_hz = 0.0;
  double hi_hz = 0.0;

  bool Contains(double lo, double hi) const { return lo >= lo_hz && hi <= hi_hz; }
};

// The intersection of two optional intervals (nullopt: unlimited); empty
// (lo_hz > hi_hz) when they do not overlap.
inline std::optional<FrequencyInterval> Intersect(const std::optional<FrequencyInterval>& a,
                                                  const std::optional<FrequencyInterval>& b) {
  if (!a) return b;
  if (!b) return a;
  return FrequencyInterval{std::max(a->lo_hz, b->lo_hz), std::min(a->hi_hz, b->hi_hz)};
}

}  // namespace deb
