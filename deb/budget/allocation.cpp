#include "deb/budget/allocation.h"

#include <cmath>
#include <sstream>

#include "deb/core/error.h"

namespace deb {

Allocation AllocationFactor(const OutputResult& output, std::size_t contributor) {
  DEB_DEMAND(contributor < output.contributors.size());
  Allocation a;
  if (!output.rms_max) {
    a.note = "no requirement";
    return a;
  }
  const double limit2 = *output.rms_max * *output.rms_max;
  const double own = output.contributors[contributor].variance;
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
