// Requirement allocation: how far one contributor may move before its output
// meets (or fails) the requirement. Contributors are uncorrelated, so the
// output variance is sigma^2 = sum of sigma_c^2, and scaling contributor c's
// source PSD by k scales sigma_c^2 by k. The output then meets rms_max when
//   k <= (rms_max^2 - (sigma^2 - sigma_c^2)) / sigma_c^2.
// k > 1: the source may grow by that factor; k < 1: it must shrink to it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "deb/budget/engine.h"

namespace deb {

struct Allocation {
  std::optional<double> factor;  // k, or none (then `note` says why)
  std::string note;
};

// The allocation factor of contributor `contributor` (index into
// output.contributors) against output.rms_max, from the grid (CPS) variances.
// None when the output has no requirement, when the contributor adds no
// variance (any level meets the limit, or none does), or when the other
// contributors alone reach the limit (k <= 0).
// DEB_DEMANDs a valid index.
Allocation AllocationFactor(const OutputResult& output, std::size_t contributor);

}  // namespace deb
