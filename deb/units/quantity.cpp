#include "deb/units/quantity.h"

#include "deb/core/error.h"
#include "deb/core/number_text.h"
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
  const std::string number = SignificantText(quantity.value, 6);
  return quantity.dimension.IsNone() ? number : number + " " + quantity.dimension.Text();
}

}  // namespace deb
