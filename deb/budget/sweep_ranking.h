// Which variant of a sweep to take to a design review: per output the
// variant with the lowest total RMS, and all variants ranked by how well
// they meet the budget's requirements. A sweep of 32 variants is read from
// its best few, not row by row.
#pragma once

#include <cstddef>
#include <vector>

#include "deb/budget/result.h"

namespace deb {

// How one variant meets the requirements of all outputs.
struct VariantScore {
  std::size_t variant = 0;
  int failing = 0;  // outputs that fail a requirement (whole grid or band)
  // Largest RMS / requirement over every requirement (whole grid and band);
  // 0 when the budget has none. Below 1: every requirement is met.
  double worst_utilisation = 0.0;
  // Sum over outputs of RMS / the highest RMS of that output in the sweep:
  // each output weighs at most 1, whatever its unit, and an output that is
  // near zero in one variant (a decoupled axis) does not swamp the rest.
  double relative_rms = 0.0;
};

// The variant with the lowest total RMS of output `output` (the first of
// equals). DEB_DEMANDs a non-empty results and a valid output index.
std::size_t BestVariant(const std::vector<BudgetResult>& results, std::size_t output);

// Every variant, best first: fewest failing outputs, then the lowest worst
// utilisation, then the lowest relative_rms, then sweep order.
std::vector<VariantScore> RankVariants(const std::vector<BudgetResult>& results);

}  // namespace deb
