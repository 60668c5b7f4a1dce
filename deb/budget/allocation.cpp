#include "deb/budget/allocation.h"

#include <cmath>
#include <sstream>

#include "deb/core/error.h"

namespace deb {

Allocation AllocationFactor(const OutputResult& output, std::size_t contributor) {
  return SourceAllocationFactor(output, {contributor});
}

Allocation SourceAllocationFactor(const OutputResult& output, const std::vector<std::size_t>& group) {
  DEB_DEMAND(!group.empty());
  Allocation a;
  if (!output.rms_max) {
    a.note = "no requirement";
    return a;
  }
  const double limit2 = *output.rms_max * *output.rms_max;
  double own = 0.0;
  for (std::size_t i = 0; i < group.size(); ++i) {
    DEB_DEMAND(group[i] < output.contributors.size());
    for (std::size_t j = 0; j < i; ++j) DEB_DEMAND(group[j] != group[i]);
    own += output.contributors[group[i]].variance;
  }
  const double others = output.variance - own;
  if (others >= limit2) {
    std::ostringstream os;
    os << "the other contributors alone give rms " << std::sqrt(others) << ", at or above the limit "
       << *output.rms_max;
    a.note = os.str();
    return a;
  }
  if (!(own > 0.0)) {
    a.note = "contributes no variance: its level does not change the output";
    return a;
  }
  a.factor = (limit2 - others) / own;
  return a;
}

}  // namespace deb
