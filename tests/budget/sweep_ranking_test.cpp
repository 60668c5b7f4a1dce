#include "deb/budget/sweep_ranking.h"

#include <doctest/doctest.h>

#include <vector>

namespace deb {
namespace {

// A variant of two outputs with these RMS values; requirements 10 and 5.
BudgetResult Variant(double rms_x, double rms_y) {
  BudgetResult r;
  OutputResult x, y;
  x.name = "x";
  x.variance = rms_x * rms_x;
  x.rms_max = 10.0;
  y.name = "y";
  y.variance = rms_y * rms_y;
  y.rms_max = 5.0;
  r.outputs = {x, y};
  return r;
}

}  // namespace

TEST_CASE("the best variant of an output has its lowest total RMS, the first of equals") {
  const std::vector<BudgetResult> results = {Variant(12, 1), Variant(8, 4), Variant(8, 2), Variant(9, 1)};
  CHECK(BestVariant(results, 0) == 1);
  CHECK(BestVariant(results, 1) == 0);
}

TEST_CASE("variants rank by failing outputs, then by the worst RMS / requirement, then by relative RMS") {
  // 0 fails x; 1 passes both at worst 0.8 (y 4/5); 2 at 0.8 (x 8/10) with lower y; 3 at 0.9.
  const std::vector<BudgetResult> results = {Variant(12, 1), Variant(8, 4), Variant(8, 2), Variant(9, 1)};
  const auto ranked = RankVariants(results);
  REQUIRE(ranked.size() == 4);
  CHECK(ranked[0].variant == 2);  // ties 1 at 0.8, but y is 2 not 4: relative RMS 8/12 + 2/4 < 8/12 + 4/4
  CHECK(ranked[1].variant == 1);
  CHECK(ranked[2].variant == 3);
  CHECK(ranked[3].variant == 0);
  CHECK(ranked[3].failing == 1);
  CHECK(ranked[0].failing == 0);
  CHECK(ranked[0].worst_utilisation == doctest::Approx(0.8));
  CHECK(ranked[0].relative_rms == doctest::Approx(8.0 / 12.0 + 2.0 / 4.0));
}

TEST_CASE("without requirements, an output near zero in one variant does not decide the ranking") {
  // y is 1e-11 in variant 0 (a decoupled axis): relative to y's lowest, every
  // other variant would be 1e10 times worse; relative to its highest, x decides.
  std::vector<BudgetResult> results = {Variant(60, 1e-11), Variant(10, 0.2), Variant(12, 1)};
  for (BudgetResult& r : results)
    for (OutputResult& o : r.outputs) o.rms_max.reset();
  const auto ranked = RankVariants(results);
  CHECK(ranked[0].variant == 1);  // 10/60 + 0.2/1 < 60/60 + 1e-11 < 12/60 + 1/1
  CHECK(ranked[1].variant == 0);
  CHECK(ranked[0].worst_utilisation == 0.0);
}

}  // namespace deb
