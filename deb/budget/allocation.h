// Requirement allocation: how far one contributor may move before its output
// meets (or fails) the requirement. Contributors are uncorrelated, so the
// output variance is sigma^2 = sum of sigma_c^2, and scaling contributor c's
// source PSD by k scales sigma_c^2 by k. The output then meets rms_max when
//   k <= (rms_max^2 - (sigma^2 - sigma_c^2)) / sigma_c^2.
// k > 1: the source may grow by that factor; k < 1: it must shrink to it.
// That reads "this contributor's source" only if no other contributor
// draws on the same source: scaling a shared source scales all of its
// contributors, whose joint factor is SourceAllocationFactor.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/result.h"

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

// The factor k on the PSD of a source that feeds the contributors `group`
// (indices into output.contributors) together: sigma_g^2 = sum over the
// group, k = (rms_max^2 - (sigma^2 - sigma_g^2)) / sigma_g^2, with the same
// cases without a factor as above. AllocationFactor is the group of one.
// DEB_DEMANDs valid, distinct indices and a non-empty group.
Allocation SourceAllocationFactor(const OutputResult& output, const std::vector<std::size_t>& group);

}  // namespace deb
