#include "deb/units/quantity.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "deb/core/error.h"
#include "deb/units/unit.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

using test::Contains;

TEST_CASE("units in SI base units: the scale and the powers UDUNITS-2 defines") {
  // Scales from the SI brochure and the international pound (0.45359237 kg);
  // 1e-15 relative.
  struct Case {
    const char* unit;
    double scale;
    const char* dimension;
  };
  const Case cases[] = {{"um/s", 1e-6, "m s-1"},   {"N/m", 1.0, "kg s-2"},      {"N/(m/s)", 1.0, "kg s-1"},
                        {"g", 1e-3, "kg"},         {"mm", 1e-3, "m"},           {"rad/s", 1.0, "s-1"},
                        {"Hz", 1.0, "s-1"},        {"m^2/Hz", 1.0, "m2 s"},     {"1", 1.0, "1"},
                        {"lb", 0.45359237, "kg"},  {"gravity", 9.80665, "m s-2"}, {"W", 1.0, "m2 kg s-3"},
                        {"urad", 1e-6, "1"},       {"kg m2", 1.0, "m2 kg"}};
  for (const Case& c : cases) {
    CAPTURE(c.unit);
    const SiBaseUnits si = InSiBaseUnits(c.unit);
    CHECK(std::abs(si.scale - c.scale) <= 1e-15 * c.scale);
    CHECK(si.dimension.Text() == c.dimension);
  }
}

TEST_CASE("a quantity converts to a unit of its dimension, and only to one") {
  const Quantity half_micron = QuantityOf(0.5, "um");
  CHECK(std::abs(ValueIn(half_micron, "nm") - 500.0) <= 1e-12 * 500.0);
  CHECK(std::abs(ValueIn(QuantityOf(5.2e4, "N/m"), "N/mm") - 52.0) <= 1e-12 * 52.0);
  try {
    ValueIn(QuantityOf(2100.0, "kg"), "nm");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(Contains(e.what(), "a quantity in kg cannot be given in nm (m)"));
  }
  CHECK_THROWS_AS(InSiBaseUnits("zorks"), InputError);
}

TEST_CASE("dimensions: products, quotients and half powers") {
  const Dimension m = Dimension::Of(0, 1), s = Dimension::Of(2, 1);
  CHECK((m / s / s).Text() == "m s-2");
  Dimension root;
  CHECK((m * m / s).RaisedTo(1, &root));
  CHECK(root.Text() == "m s-1/2");
  Dimension quarter;
  CHECK_FALSE(root.RaisedTo(1, &quarter));  // s^(-1/4) is not a multiple of 1/2
  CHECK((m / m).IsNone());
}

}  // namespace
}  // namespace deb
