#include "deb/budget/comparison.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace deb {
namespace {

ResultFigures Example(double floor_scale) {
  ResultFigures r;
  r.label = "x";
  ResultFigures::Output o;
  o.name = "z";
  o.unit = "um/s";
  o.contributors = {{"floor", 4.0 * floor_scale}, {"sensor", 1.0}};
  o.variance = 4.0 * floor_scale + 1.0;
  o.bands = {{1.0, 10.0, 3.0 * floor_scale + 0.5, {3.0 * floor_scale, 0.5}},
             {10.0, 100.0, 1.0 * floor_scale + 0.5, {1.0 * floor_scale, 0.5}}};
  r.outputs = {o};
  return r;
}

}  // namespace

TEST_CASE("parameters that differ are listed, with those only one side has") {
  ResultFigures a, b;
  a.label = "A";
  b.label = "B";
  ParameterOutline m{"m", "2100 kg", "", false, 2100.0, "kg"};
  ParameterOutline k{"k_iso", "5.2e4 N/m", "", false, 5.2e4, "N/m"};
  ParameterOutline f{"f_susp", "sqrt(4*k_iso/m)/(2*pi)", "", true, 1.58395249, "s-1"};
  a.parameters = {m, k, f};
  ParameterOutline k2 = k, f2 = f, extra{"zeta", "0.02", "", false, 0.02, ""};
  k2.expression = "6e4 N/m";
  k2.value = 6e4;
  f2.value = 1.70139;
  b.parameters = {m, k2, f2, extra};
  const Comparison cmp = Compare(a, b);
  REQUIRE(cmp.parameters.size() == 3);  // m is the same on both sides
  CHECK(cmp.parameters[0].name == "k_iso");
  CHECK(cmp.parameters[0].a == "52000 N/m");
  CHECK(cmp.parameters[0].b == "60000 N/m");
  CHECK(cmp.parameters[1].name == "f_susp");
  CHECK(cmp.parameters[1].a == "1.58395 s-1 = sqrt(4*k_iso/m)/(2*pi)");
  CHECK(cmp.parameters[2].name == "zeta");
  CHECK(cmp.parameters[2].a.empty());
  CHECK(cmp.parameters[2].b == "0.02");
  CHECK(Compare(a, a).parameters.empty());
}

TEST_CASE("a result compared with itself shows zero differences and ratio 1 everywhere") {
  const Comparison cmp = Compare(Example(1.0), Example(1.0));
  REQUIRE(cmp.figures.size() == 1 + 2 + 2 * 3);  // total, contributors, two bands x (total + 2)
  for (const ComparedFigure& f : cmp.figures) {
    CHECK(f.difference == 0.0);
    REQUIRE(f.ratio.has_value());
    CHECK(*f.ratio == 1.0);
    CHECK(f.variance_change_of_total == 0.0);
  }
  CHECK(cmp.unmatched.empty());
}

TEST_CASE("a changed contributor shows its RMS ratio and leads the largest changes") {
  const Comparison cmp = Compare(Example(1.0), Example(0.25));  // floor PSD / 4: floor RMS / 2
  const auto largest = cmp.LargestChanges(1);
  REQUIRE(largest.size() == 1);
  CHECK(largest[0].contributor == "floor");
  CHECK(*largest[0].ratio == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(largest[0].difference == doctest::Approx(-1.0).epsilon(1e-15));
  CHECK(largest[0].variance_change_of_total == doctest::Approx(-3.0 / 5.0).epsilon(1e-15));
  for (const ComparedFigure& f : cmp.figures)
    if (f.contributor == "sensor") CHECK(*f.ratio == 1.0);
  const auto total = cmp.figures.front();
  CHECK(total.contributor == "total");
  CHECK(*total.ratio == doctest::Approx(std::sqrt(2.0 / 5.0)).epsilon(1e-15));
}

TEST_CASE("a negligible term has no ratio: 0/0, from about zero, and not a regression") {
  // floor at 5.9e-13 of the total in A, a real term in B: no B / A = 1e12.
  const Comparison cmp = Compare(Example(5.9e-13 / 4.0), Example(1.0));
  const ComparedFigure* floor = nullptr;
  for (const ComparedFigure& f : cmp.figures)
    if (f.contributor == "floor" && f.band.empty()) floor = &f;
  REQUIRE(floor != nullptr);
  CHECK(floor->negligible_a);
  CHECK_FALSE(floor->negligible_b);
  CHECK_FALSE(floor->ratio.has_value());
  CHECK(floor->MovedBy(1e6));  // appeared: moved by any tolerance
  // Both sides below 1e-3 of their totals (and 0/0): no ratio, not moved.
  const Comparison tiny = Compare(Example(1e-9), Example(4e-9));
  for (const ComparedFigure& f : tiny.figures)
    if (f.contributor == "floor") {
      CHECK(f.negligible_a);
      CHECK(f.negligible_b);
      CHECK_FALSE(f.ratio.has_value());
      CHECK_FALSE(f.MovedBy(0.0));
    }
  // A band's total is judged against itself, its contributors against it:
  // the sensor's 0.5 in a band of 0.5 + 3e-9 is the band.
  for (const ComparedFigure& f : tiny.figures)
    if (!f.band.empty() && f.contributor != "floor") {
      CHECK_FALSE(f.negligible_a);
      CHECK(f.ratio.has_value());
    }
  const Comparison zero = Compare(Example(0.0), Example(0.0));
  CHECK_FALSE(zero.figures[1].ratio.has_value());  // floor: 0 / 0
  CHECK(zero.Moved(0.0).empty());
}

TEST_CASE("a band's total is judged against itself, its contributors against the band, not the whole grid") {
  // A quiet band: 1e-4 of the output's variance, +27 % RMS in B.
  ResultFigures a = Example(1.0), b = Example(1.0);
  a.outputs[0].bands[1] = {10.0, 100.0, 5e-4, {4e-4, 1e-4}};
  b.outputs[0].bands[1] = {10.0, 100.0, 8e-4, {7e-4, 1e-4}};
  const Comparison cmp = Compare(a, b);
  for (const ComparedFigure& f : cmp.figures)
    if (f.band == "10-100 Hz") {
      CAPTURE(f.contributor);
      CHECK(f.band_lo_hz == 10.0);  // the edges, for documents to print as they print bands
      CHECK(f.band_hi_hz == 100.0);
      CHECK_FALSE(f.negligible_a);
      CHECK(f.ratio.has_value());
    }
  CHECK(cmp.Moved(0.2).size() == 2);  // the band's total (+26 %) and floor in it (+32 %)
}

TEST_CASE("the figures that moved by more than a relative tolerance are listed in table order") {
  const Comparison cmp = Compare(Example(1.0), Example(1.1));  // floor RMS x sqrt(1.1) = +4.9 %
  // The floor moves by 4.9 %, the total by sqrt(5.4/5) - 1 = 3.9 %, the sensor not at all.
  const auto moved = cmp.Moved(0.045);
  REQUIRE(moved.size() == 3);  // floor over the grid, in band 1-10 Hz and 10-100 Hz
  for (const ComparedFigure& f : moved) CHECK(f.contributor == "floor");
  // Totals: whole grid sqrt(5.4 / 5) - 1 = 3.9 %, band 1-10 Hz 4.2 %, band 10-100 Hz 3.3 %.
  CHECK(cmp.Moved(0.035).size() == 3 + 2);
  CHECK(cmp.Moved(0.03).size() == 3 + 3);
  CHECK(cmp.Moved(0.05).empty());
}

TEST_CASE("outputs, contributors and units present on one side only are listed, not compared") {
  ResultFigures b = Example(1.0);
  b.label = "y";
  b.outputs[0].contributors[1].name = "actuator";
  ResultFigures::Output extra = b.outputs[0];
  extra.name = "x";
  b.outputs.push_back(extra);
  const Comparison cmp = Compare(Example(1.0), b);
  CHECK(cmp.unmatched.size() == 3);  // sensor only in A, actuator only in B, output x only in B
  ResultFigures c = Example(1.0);
  c.outputs[0].unit = "nm";
  const Comparison units = Compare(Example(1.0), c);
  CHECK(units.figures.empty());
  REQUIRE(units.unmatched.size() == 1);
  CHECK(units.unmatched[0].find("um/s") != std::string::npos);
}

TEST_CASE("a band on one side only is listed as only in that side, whichever side it is on") {
  ResultFigures b = Example(1.0);
  b.label = "y";
  b.outputs[0].bands[1].lo_hz = 100.0;
  b.outputs[0].bands[1].hi_hz = 1000.0;
  const Comparison cmp = Compare(Example(1.0), b);
  CHECK(cmp.figures.size() == 1 + 2 + 3);  // total, contributors, the 1-10 Hz band x (total + 2)
  REQUIRE(cmp.unmatched.size() == 2);
  CHECK(cmp.unmatched[0] == "band 10-100 Hz of output 'z' is only in x");
  CHECK(cmp.unmatched[1] == "band 100-1000 Hz of output 'z' is only in y");
  const Comparison reversed = Compare(b, Example(1.0));
  REQUIRE(reversed.unmatched.size() == 2);
  CHECK(reversed.unmatched[0] == "band 100-1000 Hz of output 'z' is only in y");
  CHECK(reversed.unmatched[1] == "band 10-100 Hz of output 'z' is only in x");
}

}  // namespace deb

namespace deb {

TEST_CASE("a part computed as rounding compares as 0, as the run report shows it") {
  // nizamoglu2015_h0's floor on beta_velocity is 6.1e-13 urad/s of 22
  // (rounding: the model leaves it uncoupled); compare.pdf read 6.144e-13
  // where the run report reads 0. Here a floor of 1e-26 of the total.
  const Comparison cmp = Compare(Example(1e-26 / 4.0 * 1.0), Example(1.0));
  const ComparedFigure* floor = nullptr;
  for (const ComparedFigure& f : cmp.figures)
    if (f.contributor == "floor" && f.band.empty()) floor = &f;
  REQUIRE(floor != nullptr);
  CHECK(floor->rms_a == 0.0);
  CHECK(floor->rms_b == doctest::Approx(2.0));
  CHECK(floor->difference == doctest::Approx(2.0));
  // 1e-20 of the total is not rounding: it stays (as data, negligible).
  const Comparison small = Compare(Example(1e-20 / 4.0 * 1.0), Example(1.0));
  for (const ComparedFigure& f : small.figures)
    if (f.contributor == "floor" && f.band.empty()) CHECK(f.rms_a == doctest::Approx(1e-10));
}

}  // namespace deb
