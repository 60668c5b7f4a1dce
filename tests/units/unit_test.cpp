#include "deb/units/unit.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "deb/core/error.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Relative closeness; the tolerance is stated at every call.
bool Near(double actual, double expected, double rel_tol) {
  return std::abs(actual - expected) <= rel_tol * std::abs(expected);
}

// The message of the InputError `f` throws; fails the test if it throws none.
template <typename F>
std::string InputErrorMessage(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("expected an InputError");
  return {};
}

using test::Contains;

TEST_CASE("the unit spellings users write are accepted") {
  for (const char* unit : {"um/s", "µm/s", "μm/s", "um", "nm", "mm", "m/s^2", "m s-2", "m.s-2",
                           "urad", "mrad", "rad", "N", "g", "gravity", "1", "", "-", "  um/s \t",
                           "Hz", "kg m2", "degC"}) {
    CAPTURE(unit);
    CHECK_NOTHROW(ValidateUnit(unit));
  }
}

TEST_CASE("um is the micrometre, and both micro signs mean the same") {
  // Exact decimal scales: rel 1e-12.
  CHECK(Near(ConvertUnit("um", "m").scale, 1e-6, 1e-12));
  CHECK(Near(ConvertUnit("µm", "um").scale, 1.0, 1e-12));  // U+00B5 micro sign
  CHECK(Near(ConvertUnit("μm", "um").scale, 1.0, 1e-12));  // U+03BC Greek mu
  CHECK(Near(ConvertUnit("m s-2", "m/s^2").scale, 1.0, 1e-12));
}

TEST_CASE("um/s to m/s is a pure scale of 1e-6") {
  const UnitConversion c = ConvertUnit("um/s", "m/s");
  CHECK(c.derivative_order == 0);
  CHECK(c.IsPureScale());
  CHECK(Near(c.scale, 1e-6, 1e-12));
  CHECK(UnitsCommensurate("um/s", "m/s"));
}

TEST_CASE("velocity to displacement integrates once and its PSD factor is scale^2 at omega = 1") {
  const UnitConversion c = ConvertUnit("um/s", "nm");
  CHECK(c.derivative_order == -1);
  CHECK(Near(c.scale, 1e3, 1e-12));
  CHECK_FALSE(c.IsPureScale());
  // At f = 1/(2 pi) Hz, (2 pi f)^(2n) = 1; rel 1e-12 covers rounding of 2 pi f.
  CHECK(Near(c.PsdFactor(1.0 / (2.0 * kPi)), 1e6, 1e-12));
  // At 10 Hz: 1e6 / (2 pi 10)^2, rel 1e-12.
  CHECK(Near(c.PsdFactor(10.0), 1e6 / std::pow(20.0 * kPi, 2), 1e-12));
}

TEST_CASE("acceleration to displacement integrates twice") {
  const UnitConversion c = ConvertUnit("m/s^2", "nm");
  CHECK(c.derivative_order == -2);
  CHECK(Near(c.scale, 1e9, 1e-12));
  const UnitConversion um = ConvertUnit("m/s^2", "um");
  CHECK(um.derivative_order == -2);
  CHECK(Near(um.scale, 1e6, 1e-12));
  // PSD: scale^2 (2 pi f)^-4 at 2 Hz, rel 1e-12.
  CHECK(Near(c.PsdFactor(2.0), 1e18 / std::pow(4.0 * kPi, 4), 1e-12));
}

TEST_CASE("displacement to velocity differentiates once") {
  const UnitConversion c = ConvertUnit("nm", "um/s");
  CHECK(c.derivative_order == 1);
  CHECK(Near(c.scale, 1e-3, 1e-12));
  CHECK(Near(c.PsdFactor(5.0), 1e-6 * std::pow(10.0 * kPi, 2), 1e-12));
}

TEST_CASE("the response factor is scale (j 2 pi f)^n") {
  // Integration: 1e3 / (j 2 pi f) = -j 1e3 / (2 pi f); abs tolerance 1e-12 of the magnitude.
  const std::complex<double> integrate = ConvertUnit("um/s", "nm").ResponseFactor(1.0);
  CHECK(std::abs(integrate - std::complex<double>(0.0, -1e3 / (2.0 * kPi))) <=
        1e-12 * 1e3 / (2.0 * kPi));
  // Two derivatives: -(2 pi f)^2, real and negative.
  const std::complex<double> twice = ConvertUnit("m", "m/s^2").ResponseFactor(1.0);
  CHECK(std::abs(twice - std::complex<double>(-4.0 * kPi * kPi, 0.0)) <= 1e-12 * 4.0 * kPi * kPi);
}

TEST_CASE("a conversion describes itself in words") {
  CHECK(ConvertUnit("um/s", "nm").Describe() == "scale 1000, integrated once in time");
  CHECK(ConvertUnit("nm", "um/s").Describe() == "scale 0.001, differentiated once in time");
  CHECK(ConvertUnit("um/s", "m/s").Describe() == "scale 1e-06");
}

TEST_CASE("incompatible units throw an InputError naming both units") {
  const std::string velocity_force = InputErrorMessage([] { ConvertUnit("um/s", "N"); });
  CHECK(Contains(velocity_force, "'um/s'"));
  CHECK(Contains(velocity_force, "'N'"));
  CHECK(Contains(velocity_force, "not the same quantity, nor related by"));
  const std::string length_temperature = InputErrorMessage([] { ConvertUnit("um", "K"); });
  CHECK(Contains(length_temperature, "'um'"));
  CHECK(Contains(length_temperature, "'K'"));
  CHECK_FALSE(UnitsCommensurate("um", "K"));
}

TEST_CASE("reciprocal units are different quantities") {
  // UDUNITS-2 itself would convert m to 1/m and s to Hz by y = 1/x.
  CHECK_FALSE(UnitsCommensurate("m", "1/m"));
  CHECK_FALSE(UnitsCommensurate("s", "Hz"));
  const std::string message = InputErrorMessage([] { ConvertUnit("m", "1/m"); });
  CHECK(Contains(message, "not the same quantity"));
}

TEST_CASE("relations beyond two time derivatives are rejected") {
  const std::string message = InputErrorMessage([] { ConvertUnit("m/s^3", "m"); });
  CHECK(Contains(message, "'m/s^3'"));
}

TEST_CASE("an unknown unit throws with the string quoted") {
  const std::string unknown = InputErrorMessage([] { ValidateUnit("umm/s"); });
  CHECK(Contains(unknown, "unknown unit 'umm/s'"));
  CHECK(Contains(unknown, "not in the UDUNITS-2 database"));
  const std::string syntax = InputErrorMessage([] { ValidateUnit("m//s"); });
  CHECK(Contains(syntax, "'m//s'"));
  CHECK(Contains(syntax, "syntax"));
  CHECK(Contains(InputErrorMessage([] { ConvertUnit("nm", "furlongz"); }), "'furlongz'"));
  CHECK(Contains(InputErrorMessage([] { UnitsCommensurate("nm", "UM"); }), "'UM'"));
}

TEST_CASE("empty, 1 and - all mean dimensionless") {
  // Exact: rel 1e-12.
  CHECK(Near(ConvertUnit("", "1").scale, 1.0, 1e-12));
  CHECK(Near(ConvertUnit("-", "").scale, 1.0, 1e-12));
  CHECK(Near(ConvertUnit("1", "ppm").scale, 1e6, 1e-12));
  CHECK(DisplayUnit("") == "1");
  CHECK(DisplayUnit("-") == "1");
  CHECK(DisplayUnit("  m   s-2 ") == "m s-2");
}

TEST_CASE("angles are dimensionless but never convert to lengths") {
  CHECK(UnitsCommensurate("urad", "1"));
  CHECK(Near(ConvertUnit("1", "urad").scale, 1e6, 1e-12));
  CHECK_FALSE(UnitsCommensurate("urad", "um"));
  CHECK_THROWS_AS(ConvertUnit("urad", "um"), InputError);
  // Angular rate: urad -> mrad/s differentiates once.
  const UnitConversion rate = ConvertUnit("urad", "mrad/s");
  CHECK(rate.derivative_order == 1);
  CHECK(Near(rate.scale, 1e-3, 1e-12));
  // The radian being one, rad/s and Hz are the same unit to UDUNITS-2 (no 2 pi).
  CHECK(Near(ConvertUnit("rad/s", "Hz").scale, 1.0, 1e-12));
}

TEST_CASE("g is the gram, and the error for gravity says so") {
  CHECK(Near(ConvertUnit("g", "kg").scale, 1e-3, 1e-12));
  CHECK(Near(ConvertUnit("gravity", "m/s^2").scale, 9.80665, 1e-12));
  CHECK(Contains(InputErrorMessage([] { ConvertUnit("g", "m/s^2"); }), "gram"));
}

TEST_CASE("offset units convert fluctuations by their slope") {
  // degC -> K is 1 (the 273.15 offset dropped); degF -> degC is 5/9. rel 1e-12.
  CHECK(Near(ConvertUnit("degC", "K").scale, 1.0, 1e-12));
  CHECK(Near(ConvertUnit("degF", "degC").scale, 5.0 / 9.0, 1e-12));
  CHECK(UnitsCommensurate("degC", "mK"));
}

TEST_CASE("logarithmic units are rejected") {
  const std::string message = InputErrorMessage([] { ConvertUnit("lg(re 1 mW)", "W"); });
  CHECK(Contains(message, "non-linear"));
  CHECK_FALSE(UnitsCommensurate("lg(re 1 mW)", "W"));
}

TEST_CASE("PSD and ASD labels parenthesise compound units") {
  CHECK(PsdUnitLabel("um/s") == "(um/s)^2/Hz");
  CHECK(AsdUnitLabel("um/s") == "(um/s)/sqrt(Hz)");
  CHECK(PsdUnitLabel("nm") == "nm^2/Hz");
  CHECK(AsdUnitLabel("nm") == "nm/sqrt(Hz)");
  CHECK(PsdUnitLabel("µm") == "µm^2/Hz");
  CHECK(PsdUnitLabel("m2") == "(m2)^2/Hz");
  CHECK(PsdUnitLabel("") == "1/Hz");
  CHECK(AsdUnitLabel("1") == "1/sqrt(Hz)");
  // The PSD label is a unit UDUNITS-2 parses: (um/s)^2/Hz = 1e-12 m^2/s, rel 1e-12.
  CHECK(Near(ConvertUnit(PsdUnitLabel("um/s"), "m^2/s").scale, 1e-12, 1e-12));
  CHECK(Near(ConvertUnit(PsdUnitLabel("nm"), "m^2 s").scale, 1e-18, 1e-12));
}

TEST_CASE("UDUNITS-2 definitions are in SI base units and parse back") {
  CHECK(UnitDefinition("um/s") == "1e-06 m.s-1");
  CHECK(UnitDefinition("N") == "m.kg.s-2");
  CHECK(Near(ConvertUnit(UnitDefinition("um/s"), "um/s").scale, 1.0, 1e-12));
}

TEST_CASE("the product of um/s and s is commensurate with um at scale 1") {
  const std::string product = UnitProduct("um/s", "s");
  CHECK(product == "(um/s) s");
  CHECK(UnitsCommensurate(product, "um"));
  CHECK(Near(ConvertUnit(product, "um").scale, 1.0, 1e-12));
  CHECK(UnitProduct("N", "m") == "N m");
  CHECK(UnitProduct("", "nm") == "nm");
  CHECK(UnitProduct("nm", "1") == "nm");
  CHECK(Near(ConvertUnit(UnitProduct("m/s^2", "s^2"), "mm").scale, 1e3, 1e-12));
  CHECK_THROWS_AS(UnitProduct("umm", "s"), InputError);
}

TEST_CASE("conversions from several threads agree with a single-threaded one") {
  const UnitConversion reference = ConvertUnit("m/s^2", "nm");
  constexpr int kThreads = 8;
  constexpr int kRepeats = 200;
  std::vector<int> mismatches(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([t, &mismatches, &reference] {
      for (int i = 0; i < kRepeats; ++i) {
        const UnitConversion c = ConvertUnit("m/s^2", "nm");
        // Same library, same inputs: bitwise equal.
        if (c.scale != reference.scale || c.derivative_order != reference.derivative_order) {
          ++mismatches[t];
        }
        if (!UnitsCommensurate("um/s", "m/s")) ++mismatches[t];
      }
    });
  }
  for (auto& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) CHECK(mismatches[t] == 0);
}

TEST_CASE("answers are remembered by their arguments, failures are not") {
  // The same question, spelt with different whitespace, gets the same answer
  // as the first time; an invalid unit fails every time, also after a valid
  // spelling of its neighbour was remembered.
  const UnitConversion first = ConvertUnit("um/s", "nm");
  const UnitConversion again = ConvertUnit("  um/s ", "nm ");
  CHECK(again.scale == first.scale);
  CHECK(again.derivative_order == first.derivative_order);
  CHECK(UnitDefinition("um/s") == UnitDefinition(" um/s"));
  CHECK(UnitProduct("N", "m") == UnitProduct(" N", "m "));
  for (int i = 0; i < 2; ++i) {
    CHECK_THROWS_AS(ValidateUnit("umm/s"), InputError);
    CHECK_THROWS_AS(ConvertUnit("um/s", "rad"), InputError);
    CHECK_THROWS_AS(UnitsCommensurate("umm/s", "m/s"), InputError);
  }
  CHECK_FALSE(UnitsCommensurate("um/s", "nm"));
  CHECK_FALSE(UnitsCommensurate("um/s", "nm"));
}

}  // namespace
}  // namespace deb
