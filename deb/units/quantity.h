// A physical quantity: a value in coherent SI units and its dimension
// (dimension.h). What an expression (deb/parameters/expression.h) evaluates
// to, and what a budget field converts to the unit it expects.
#pragma once

#include <string>

#include "deb/units/dimension.h"

namespace deb {

struct Quantity {
  double value = 0.0;  // in the coherent SI unit of `dimension` (kg s-2 for N/m)
  Dimension dimension;
  // Made with a unit ("0.5 rad", "2 kHz"), not from plain numbers alone: a
  // plain number given where a unit is expected is in that unit (45 in a
  // field in degrees), a dimensionless quantity with a unit is converted
  // (0.5 rad there is 28.6).
  bool has_unit = false;
};

// `number` in `unit` ("210", "mm": 0.21 m).
// @throws InputError for an invalid unit (unit.h's ValidateUnit).
Quantity QuantityOf(double number, const std::string& unit);

// The quantity's value in `unit` (0.21 m in "mm": 210).
// @throws InputError "a quantity in kg cannot be given in nm" when the
// dimensions differ, or for an invalid unit.
double ValueIn(const Quantity& quantity, const std::string& unit);

// "52000 kg s-2", "0.02": the value in SI base units, for messages and
// reports.
std::string Describe(const Quantity& quantity);

}  // namespace deb
