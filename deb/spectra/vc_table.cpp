// The VC table of spectra/vc_curves.csv, compiled in so that deb needs no data
// files at run time. Keep the two identical: tests/spectra/vc_curve_test.cpp
// compares them.
#include "deb/core/error.h"
#include "deb/spectra/vc_curve.h"

namespace deb {

const std::vector<VcCriterion>& VcCriteria() {
  static const std::vector<VcCriterion> table = {
      {VcClass::kA, "VC-A", 50.0, 2000.0, 8.0, 80.0, "G91"},
      {VcClass::kB, "VC-B", 25.0, 1000.0, 8.0, 80.0, "G91"},
      {VcClass::kC, "VC-C", 12.5, 500.0, 8.0, 80.0, "G91"},
      {VcClass::kD, "VC-D", 6.25, 250.0, 8.0, 80.0, "G91"},
      {VcClass::kE, "VC-E", 3.12, 125.0, 8.0, 80.0, "G91"},
      {VcClass::kF, "VC-F", 1.56, 62.5, 8.0, 80.0, "A05"},
      {VcClass::kG, "VC-G", 0.78, 31.3, 8.0, 80.0, "A05"},
  };
  return table;
}

const VcCriterion& VcCriterionOf(VcClass vc_class) {
  for (const VcCriterion& row : VcCriteria()) {
    if (row.vc_class == vc_class) return row;
  }
  DEB_DEMAND(false);
  return VcCriteria().front();
}

}  // namespace deb
