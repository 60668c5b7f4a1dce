// The table of spectra/iso_building_curves.csv, compiled in. Keep the two
// identical: tests/spectra/building_criteria_test.cpp compares them.
#include "deb/spectra/building_criteria.h"

namespace deb {

const std::vector<IsoBuildingCriterion>& IsoBuildingCriteria() {
  static const std::vector<IsoBuildingCriterion> table = {
      {"ISO-workshop", 800.0, 32000.0, 8.0, 80.0, 8.0},
      {"ISO-office", 400.0, 16000.0, 8.0, 80.0, 4.0},
      {"ISO-residential-day", 200.0, 8000.0, 8.0, 80.0, 2.0},
      {"ISO-operating-theatre", 100.0, 4000.0, 8.0, 80.0, 1.0},
  };
  return table;
}

}  // namespace deb
