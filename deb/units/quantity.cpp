#include "deb/units/quantity.h"

#include <cstdio>

#include "deb/core/error.h"
#include "deb/units/unit.h"

namespace deb {

Quantity QuantityOf(double number, const std::string& unit) {
  const SiBaseUnits si = InSiBaseUnits(unit);
  return {number * si.scale, si.dimension, true};
}

double ValueIn(const Quantity& quantity, const std::string& unit) {
  const SiBaseUnits si = InSiBaseUnits(unit);
  if (si.dimension != quantity.dimension) {
    throw InputError("a quantity in " + quantity.dimension.Text() + " cannot be given in " + DisplayUnit(unit) +
                     " (" + si.dimension.Text() + ")");
  }
  return quantity.value / si.scale;
}

std::string Describe(const Quantity& quantity) {
  char number[32];
  std::snprintf(number, sizeof number, "%.6g", quantity.value);
  return quantity.dimension.IsNone() ? std::string(number) : std::string(number) + " " + quantity.dimension.Text();
}

}  // namespace deb
