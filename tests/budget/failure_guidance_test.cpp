#include "deb/budget/failure_guidance.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/support/flat_output.h"

namespace deb {
namespace {

using test::FlatOutput;


const FrequencyGrid kGrid{std::vector<double>{1.0, 2.0}};

// The variance left after removing the contributors in `mask` (bit c: c).
double Left(const std::vector<double>& v, unsigned mask) {
  double left = 0.0;
  for (std::size_t c = 0; c < v.size(); ++c)
    if (!(mask & (1u << c))) left += v[c];
  return left;
}

}  // namespace

TEST_CASE("variances 49, 25, 16, 10 against a limit of 6: fail factor, greedy set and factors in closed form") {
  const std::vector<double> v = {49.0, 25.0, 16.0, 10.0};
  const OutputResult o = FlatOutput(v, 6.0);
  const auto g = GuideFailure(o, kGrid);
  REQUIRE(g);
  REQUIRE(g->overall);
  const RequirementGuidance& r = *g->overall;
  CHECK(r.fail_factor == doctest::Approx(10.0 / 6.0).epsilon(1e-12));
  CHECK(r.dominant == 0);
  CHECK(r.dominant_share == doctest::Approx(0.49).epsilon(1e-12));
  // Removing 49 leaves 51 > 36; removing 49 and 25 leaves 26 <= 36.
  CHECK(r.remove == std::vector<std::size_t>{0, 1});
  REQUIRE(r.reduce.size() == 2);
  CHECK(r.reduce[0].contributors == std::vector<std::size_t>{0, 1});
  // 26 + 74 / r^2 = 36  ->  r = sqrt(7.4)
  REQUIRE(r.reduce[0].rms_factor);
  CHECK(*r.reduce[0].rms_factor == doctest::Approx(std::sqrt(7.4)).epsilon(1e-12));
  // One more: 10 + 90 / r^2 = 36  ->  r = sqrt(90 / 26)
  CHECK(r.reduce[1].contributors == std::vector<std::size_t>{0, 1, 2});
  REQUIRE(r.reduce[1].rms_factor);
  CHECK(*r.reduce[1].rms_factor == doctest::Approx(std::sqrt(90.0 / 26.0)).epsilon(1e-12));
  // Flat total PSD 100 from 1 Hz: the CPS reaches 36 at 1.36 Hz.
  REQUIRE(r.cps_crossing_hz);
  CHECK(*r.cps_crossing_hz == doctest::Approx(1.36).epsilon(1e-12));
  CHECK(g->bands.empty());
}

TEST_CASE("the greedy set is the smallest removal that meets the limit, and its factor the least of its size (all subsets)") {
  const std::vector<std::vector<double>> cases = {
      {49, 25, 16, 10}, {10, 49, 16, 25}, {30, 30, 30, 1, 9}, {5, 4, 3, 2, 1, 0.5}, {90, 5, 5}};
  for (const auto& v : cases) {
    for (double limit : {1.0, 3.0, 5.0, 7.0}) {
      const OutputResult o = FlatOutput(v, limit);
      const auto g = GuideFailure(o, kGrid);
      if (o.pass()) {
        CHECK(!g);
        continue;
      }
      REQUIRE(g);
      const std::size_t m = g->overall->remove.size();
      const double limit2 = limit * limit;
      double best_r = std::numeric_limits<double>::infinity();
      for (unsigned mask = 0; mask < (1u << v.size()); ++mask) {
        const std::size_t size = static_cast<std::size_t>(__builtin_popcount(mask));
        const double left = Left(v, mask);
        if (size < m) CHECK(left > limit2);  // no smaller removal meets it
        if (size == m && left < limit2) {
          const double own = o.variance - left;
          best_r = std::min(best_r, std::sqrt(own / (limit2 - left)));
        }
      }
      CHECK(Left(v, [&] {
              unsigned mask = 0;
              for (std::size_t c : g->overall->remove) mask |= 1u << c;
              return mask;
            }()) <= limit2);
      if (g->overall->reduce[0].rms_factor) CHECK(*g->overall->reduce[0].rms_factor == doctest::Approx(best_r).epsilon(1e-12));
    }
  }
}

TEST_CASE("one contributor alone can meet the limit: its factor, and the pair's, in the sentence") {
  OutputResult o = FlatOutput({80.0, 10.0, 10.0}, 6.0);
  BandResult low, high;  // a holds 30 of its 80 below 1.5 Hz, 50 above
  low.band = {1.0, 1.5};
  low.contributor_variance = {30.0, 5.0, 5.0};
  high.band = {1.5, 2.0};
  high.contributor_variance = {50.0, 5.0, 5.0};
  o.bands = {low, high};
  const auto g = GuideFailure(o, kGrid);
  REQUIRE(g);
  const RequirementGuidance& r = *g->overall;
  CHECK(r.remove == std::vector<std::size_t>{0});
  // 20 + 80 / r^2 = 36 -> sqrt(5); 10 + 90 / r^2 = 36 -> sqrt(90 / 26)
  CHECK(*r.reduce[0].rms_factor == doctest::Approx(std::sqrt(5.0)).epsilon(1e-12));
  CHECK(*r.reduce[1].rms_factor == doctest::Approx(std::sqrt(90.0 / 26.0)).epsilon(1e-12));
  REQUIRE(r.dominant_band);
  CHECK(r.dominant_band->lo_hz == 1.5);
  CHECK(g->sentence ==
        "position fails by 1.667×: a (80 %, 1.5–2 Hz) must drop 2.236×, or a and b 1.861× each; "
        "the cumulative RMS reaches 6 nm at 1.36 Hz");
}

TEST_CASE("when removing the set meets the limit exactly, the set must go; every contributor when all are needed") {
  const auto exact = GuideFailure(FlatOutput({64.0, 36.0}, 6.0), kGrid);
  REQUIRE(exact);
  CHECK(exact->overall->remove == std::vector<std::size_t>{0});
  CHECK(!exact->overall->reduce[0].rms_factor);
  CHECK(*exact->overall->reduce[1].rms_factor == doctest::Approx(10.0 / 6.0).epsilon(1e-12));
  CHECK(exact->sentence.find("a (64 %) must be removed, or a and b 1.667× each") != std::string::npos);

  const auto all = GuideFailure(FlatOutput({50.0, 50.0}, 5.0), kGrid);
  REQUIRE(all);
  CHECK(all->overall->remove.size() == 2);
  CHECK(all->overall->reduce.size() == 1);
  CHECK(*all->overall->reduce[0].rms_factor == doctest::Approx(2.0).epsilon(1e-12));  // = fail factor
  CHECK(all->sentence.rfind("position fails by 2×: every contributor must drop 2× (the largest: a (50 %))", 0) == 0);
}

TEST_CASE("a failing band requirement: fail factor, largest contributor in the band and its own factor") {
  OutputResult o = FlatOutput({40.0, 6.0, 4.0}, std::nullopt);  // no whole-grid requirement
  BandRequirementResult b;
  b.requirement = {1.0, 1.5, 4.0};
  b.variance = 25.0;  // half of each flat PSD: 20 + 3 + 2
  o.band_requirements = {b};
  const auto g = GuideFailure(o, kGrid);
  REQUIRE(g);
  CHECK(!g->overall);
  REQUIRE(g->bands.size() == 1);
  const BandGuidance& bg = g->bands[0];
  CHECK(bg.fail_factor == doctest::Approx(5.0 / 4.0).epsilon(1e-12));
  CHECK(bg.largest == 0);
  CHECK(bg.largest_share == doctest::Approx(20.0 / 25.0).epsilon(1e-12));
  // 5 + 20 / r^2 = 16 -> r = sqrt(20 / 11)
  REQUIRE(bg.largest_rms_factor);
  CHECK(*bg.largest_rms_factor == doctest::Approx(std::sqrt(20.0 / 11.0)).epsilon(1e-12));
  CHECK(g->sentence == "position fails in band 1–1.5 Hz by 1.25× (largest: a, 80 % of the band, must drop 1.348×)");
}

TEST_CASE("a shared source: the factor per contributor, applied to the source, is sufficient (not exact)") {
  OutputResult o = FlatOutput({80.0, 10.0, 10.0}, 6.0);
  o.contributors[1].source = o.contributors[0].source;  // a and b draw on one source
  const auto g = GuideFailure(o, kGrid);
  REQUIRE(g);
  const double r = *g->overall->reduce[0].rms_factor;
  CHECK(r == doctest::Approx(std::sqrt(5.0)).epsilon(1e-12));  // as if a's source were its own
  // Dividing the shared source by r lowers b too: 80/5 + 10/5 + 10 = 28 <= 36.
  const double variance = (80.0 + 10.0) / (r * r) + 10.0;
  CHECK(variance == doctest::Approx(28.0).epsilon(1e-12));
  CHECK(variance <= 36.0);
}

TEST_CASE("an output that meets its requirements, or has none, gets no guidance") {
  CHECK(!GuideFailure(FlatOutput({20.0, 16.0}, 6.0), kGrid));  // rms exactly at the limit
  CHECK(!GuideFailure(FlatOutput({20.0, 10.0}, 6.0), kGrid));
  CHECK(!GuideFailure(FlatOutput({20.0, 10.0}, std::nullopt), kGrid));
}

TEST_CASE("the CPS crossing of a flat PSD is linear, of a 1/f^2 PSD hyperbolic, exactly between grid points") {
  std::vector<double> f;
  for (int i = 0; i <= 30; ++i) f.push_back(0.5 * std::pow(10.0, i / 10.0));
  // Flat S0: CPS = S0 (f - f0), reaching X at f0 + X / S0.
  const double s0 = 2.5;
  std::vector<double> flat(f.size(), s0), cps_flat;
  for (double x : f) cps_flat.push_back(s0 * (x - f.front()));
  for (double x : {1.0, 7.3, 123.4, 1234.0}) {
    const auto hz = CpsCrossingHz(f, flat, cps_flat, x);
    REQUIRE(hz);
    CHECK(*hz == doctest::Approx(f.front() + x / s0).epsilon(1e-12));
  }
  // S = f^-2: CPS = 1/f0 - 1/f, reaching X at 1 / (1/f0 - X).
  std::vector<double> falling, cps_falling;
  for (double x : f) {
    falling.push_back(1.0 / (x * x));
    cps_falling.push_back(1.0 / f.front() - 1.0 / x);
  }
  for (double x : {0.1, 1.0, 1.9}) {
    const auto hz = CpsCrossingHz(f, falling, cps_falling, x);
    REQUIRE(hz);
    CHECK(*hz == doctest::Approx(1.0 / (1.0 / f.front() - x)).epsilon(1e-12));
  }
  CHECK(!CpsCrossingHz(f, falling, cps_falling, 2.0));  // 1/f0 - 1/f < 2 everywhere
  CHECK(*CpsCrossingHz(f, flat, cps_flat, cps_flat[7]) == f[7]);  // at a grid point: that point
}

}  // namespace deb
