// Physical units of signals, spectra and paths. A budget mixes sources, paths
// and outputs declared in different units (a geophone in um/s, a floor in
// m/s^2, an output in nm); this module decides whether two units describe the
// same quantity, or quantities related by time derivatives, and with which
// scale. It is the only place in deb that talks to UDUNITS-2.
//
// Unit strings follow UDUNITS-2 syntax: `um/s`, `µm/s`, `nm`, `m/s^2`, `m s-2`,
// `urad`, `N`, `kg m2`. Surrounding whitespace is ignored. Things to know:
//  - Dimensionless: "", "1" and "-" all mean the number one.
//  - Angles are dimensionless: `urad` is commensurate with `1` (1 = 1e6 urad),
//    and `rad/s` with `Hz` at scale 1, not 2 pi. `urad` never converts to `um`.
//  - `g` is the gram. Standard acceleration of free fall is `gravity`
//    (9.80665 m/s^2).
//  - Units with an offset (`degC`, `degF`) convert by their slope only: deb
//    converts fluctuations, whose spectra do not see a constant offset.
//  - Reciprocal units (m and 1/m) are different quantities here, although
//    UDUNITS-2 alone would convert them by y = 1/x.
//  - Logarithmic units (`lg(re 1 mW)`) are rejected.
#pragma once

#include <complex>
#include <string>

#include "deb/units/dimension.h"

namespace deb {

// How to express a signal given in unit `from` as a signal in unit `to`:
//   y_to(t) = scale * (d/dt)^derivative_order y_from(t).
// Examples: um/s -> nm: scale 1e3, order -1 (one integration);
//           m/s^2 -> um: 1e6, -2;   nm -> um/s: 1e-3, +1;   um/s -> m/s: 1e-6, 0.
struct UnitConversion {
  double scale = 1.0;
  int derivative_order = 0;

  // Factor on a PSD: S_to(f) = scale^2 (2 pi f)^(2 n) S_from(f), f_hz > 0.
  double PsdFactor(double f_hz) const;

  // Factor on a frequency response or Fourier amplitude:
  // H_to(f) = scale (j 2 pi f)^n H_from(f), f_hz > 0.
  std::complex<double> ResponseFactor(double f_hz) const;

  bool IsPureScale() const { return derivative_order == 0; }

  // One line for reports, e.g. "scale 1000, integrated once in time".
  std::string Describe() const;
};

// Checks that UDUNITS-2 can parse `unit`.
// @throws InputError quoting the string and the reason, e.g.
//   "unknown unit 'umm/s': a name or prefix in it is not in the UDUNITS-2 database".
// @throws InputError if the UDUNITS-2 database cannot be loaded (names the package).
void ValidateUnit(const std::string& unit);

// Finds n in [-2, 2] such that `to` is commensurate with `from`·s^(-n), and the
// scale of that relation (see UnitConversion).
// @throws InputError for an invalid unit string (as ValidateUnit).
// @throws InputError "cannot convert 'um/s' to 'rad': not the same quantity, nor
//   related by time derivatives ..." when no such n exists.
// @throws InputError when UDUNITS-2 relates the units non-linearly.
UnitConversion ConvertUnit(const std::string& from, const std::string& to);

// True when a value in `a` converts to `b` by a pure scale (derivative order 0).
// @throws InputError for an invalid unit string (as ValidateUnit).
bool UnitsCommensurate(const std::string& a, const std::string& b);

// The unit as written, for reports: whitespace trimmed and collapsed, and the
// dimensionless spellings "" and "-" shown as "1". Does not validate.
std::string DisplayUnit(const std::string& unit);

// UDUNITS-2's definition of `unit` in SI base units, e.g. "1e-06 m.s-1" for
// "um/s". The result parses back to the same unit.
// @throws InputError for an invalid unit string (as ValidateUnit).
std::string UnitDefinition(const std::string& unit);

// A unit in the SI base units: a value v in `unit` is v * scale in the
// coherent SI unit of `dimension` ("um/s": scale 1e-6, m s-1; "N/m": 1,
// kg s-2; "deg": pi/180, none). An offset (degC) is dropped, as in
// ConvertUnit.
struct SiBaseUnits {
  double scale = 1.0;
  Dimension dimension;
};
// @throws InputError for an invalid unit string (as ValidateUnit), or a
// logarithmic or time-stamp unit.
SiBaseUnits InSiBaseUnits(const std::string& unit);

// Label of a PSD in `unit`: "um/s" -> "(um/s)^2/Hz", "nm" -> "nm^2/Hz",
// "1" -> "1/Hz". UDUNITS-2 parses it. Does not validate.
std::string PsdUnitLabel(const std::string& unit);

// Label of an ASD in `unit`: "um/s" -> "(um/s)/sqrt(Hz)", "nm" -> "nm/sqrt(Hz)".
// For display only: UDUNITS-2 has no square root in its syntax.
std::string AsdUnitLabel(const std::string& unit);

// The product of two units as a string UDUNITS-2 parses, e.g.
// UnitProduct("um/s", "s") -> "(um/s) s", which equals um. Used when a
// weighting filter carries a unit.
// @throws InputError for an invalid unit string (as ValidateUnit).
std::string UnitProduct(const std::string& a, const std::string& b);

}  // namespace deb
