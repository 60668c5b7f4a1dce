#include "deb/report/budget/band_text.h"

#include <doctest/doctest.h>

namespace deb::report {

TEST_CASE("band labels are short") {
  CHECK(BandText(0.1, 1.0) == "0.1–1 Hz");
  CHECK(BandText(100, 1000) == "100–1000 Hz");
}

}  // namespace deb::report
