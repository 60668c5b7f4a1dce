// Universal file format (UFF) dataset 58: the function records test-rig
// software writes for frequency response functions, spectra and time
// histories, as text (58) or with binary data (58b). A universal file is a
// sequence of datasets, each between two delimiter lines "    -1", the first
// line inside naming the dataset type ("    58", "    58b", "  2411", ...).
// Datasets of other types are skipped by their delimiters.
//
// A dataset 58 is twelve records (Fortran formats):
//   1-5  five ID lines (A80): a description, a name, a date, ...
//   6    function type and DOFs, 2(I5,I10),2(1X,10A1,I10,I4): function type,
//        function id, version, load case, response entity name, node and
//        direction, reference entity name, node and direction
//   7    3I10,3E13.5: ordinate data type (2 real single, 4 real double,
//        5 complex single, 6 complex double), number of points, abscissa
//        spacing (1 even, 0 uneven), abscissa minimum, increment, z value
//   8-11 I10,3I5,2(1X,A20): abscissa, ordinate numerator, ordinate
//        denominator and z axis: specific data type, the exponents of
//        length, force and temperature in its unit, axis label, units label
//   12   the data: per point the abscissa (uneven spacing only), then the
//        value (complex: real and imaginary part)
// The data values are read as whitespace-separated numbers (Fortran E and D
// exponents), so a writer's field widths do not matter; two fields that
// touch ("1.2E-03-4.5E-03", E13.6 with a sign) are split at the sign, each
// part having a decimal point. Records 6 and 8-11 hold names and labels
// with blanks, so they are read by their columns, counted in characters.
//
// 58b: the dataset's first line is "    58b" followed by the byte order
// (1 little endian, 2 big endian), the floating point format (2 IEEE 754,
// the only one read), the number of ASCII lines that follow (11: records
// 1-11) and the number of bytes of data after them, which must equal the
// points times the values per point times 4 (single) or 8 (double) bytes.
// Every value of the data, the abscissa of uneven spacing included, has the
// ordinate's precision. The closing delimiter follows the data, on the same
// line or the next.
//
// Text: every ID line, name and label is returned as UTF-8. A line that is
// not UTF-8 is read as Latin-1 (ISO 8859-1), the code page of most test-rig
// software (byte 0xB2 is "²" in "g²/Hz"), and converted; control
// characters become blanks.
//
// The file is treated as possibly hostile (deb/core/input_file.h): it is
// read whole under limits::kMaxTextFileBytes, a dataset holds at most
// limits::kMaxGridPoints points, a file at most limits::kMaxUffDatasets
// datasets and limits::kMaxUffFilePoints points in all. Every rule broken
// is an InputError "file:line:column: dataset #K (58), record R: rule" (the
// line of an ASCII record; for binary data "file: byte N: ..."), K the
// dataset's position among all the datasets of the file.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace deb::formats {

// Record 6 field 1.
enum class UffFunction {
  kGeneral = 0,
  kTimeResponse = 1,
  kAutoSpectrum = 2,
  kCrossSpectrum = 3,
  kFrf = 4,
  kTransmissibility = 5,
  kCoherence = 6,
  kAutoCorrelation = 7,
  kCrossCorrelation = 8,
  kPsd = 9,
  kEsd = 10,
  kProbabilityDensity = 11,
  kSpectrum = 12,
  kCumulativeDistribution = 13,
  kPeaksValley = 14,
  kStressCycles = 15,
  kStrainCycles = 16,
  kOrbit = 17,
  kModeIndicator = 18,
  kForcePattern = 19,
  kPartialPower = 20,
  kPartialCoherence = 21,
  kEigenvalue = 22,
  kEigenvector = 23,
  kShockResponseSpectrum = 24,
  kFirFilter = 25,
  kMultipleCoherence = 26,
  kOrderFunction = 27,
  kPhaseCompensation = 28,
};
// "FRF", "PSD", "auto spectrum", ...
std::string ToString(UffFunction f);

// Record 7 field 1.
enum class UffOrdinate { kRealSingle = 2, kRealDouble = 4, kComplexSingle = 5, kComplexDouble = 6 };
std::string ToString(UffOrdinate o);

// Records 8-11: one axis.
struct UffAxis {
  int data_type = 0;  // specific data type: 0 unknown, 1 general, 8 displacement, 12 acceleration, 17 time, 18 frequency, ...
  int length_exponent = 0, force_exponent = 0, temperature_exponent = 0;
  std::string label;  // trimmed, UTF-8
  std::string units;  // trimmed, UTF-8 ("NONE" when the writer gave none)
};

// A DOF of record 6: node and direction (0 scalar, +-1..3 translations
// X, Y, Z, +-4..6 rotations about them).
struct UffDof {
  int node = 0;
  int direction = 0;
  bool operator==(const UffDof& o) const { return node == o.node && direction == o.direction; }
};
// "1:+Z", "12:-RX", "0:scalar".
std::string ToString(const UffDof& dof);
// The inverse of ToString: NODE:DIRECTION with a direction scalar, X, Y, Z,
// RX, RY, RZ (a sign + or -, + if none; letters in either case).
// @throws InputError quoting the text and the form.
UffDof ParseUffDof(const std::string& text);

struct Uff58Record {
  int index = 0;            // position among the file's datasets, 1-based
  std::size_t offset = 0;   // byte offset of its opening delimiter
  int line = 0;             // line of its opening delimiter, 1-based
  bool binary = false;      // 58b
  std::array<std::string, 5> id;  // records 1-5, trimmed, UTF-8
  UffFunction function = UffFunction::kGeneral;
  int function_id = 0, version = 0, load_case = 0;
  std::string response_entity, reference_entity;  // trimmed, UTF-8
  UffDof response, reference;
  UffOrdinate ordinate = UffOrdinate::kRealSingle;
  bool even_spacing = true;
  double abscissa_min = 0.0, abscissa_increment = 0.0, z_value = 0.0;
  UffAxis abscissa, numerator, denominator, z_axis;
  // One per point: the abscissa (computed min + i * increment for even
  // spacing, read for uneven) and the ordinate (imaginary part 0 for real
  // data). Every value finite.
  std::vector<double> x;
  std::vector<std::complex<double>> y;

  bool is_complex() const { return ordinate == UffOrdinate::kComplexSingle || ordinate == UffOrdinate::kComplexDouble; }
  std::size_t points() const { return x.size(); }
  std::vector<double> RealValues() const;  // the real parts of y
  // "#3 (PSD, 1:+Z / 0:scalar)", for messages and lists of records.
  std::string Describe() const;
};

// Every dataset 58 and 58b of the universal file at `path`, in file order.
// @throws InputError (see above) if the file cannot be read or breaks a rule:
//   text outside a dataset, a dataset without its closing delimiter, a
//   truncated record, a field that is not a number where one is expected, a
//   value that is not finite, an unknown function type, direction or
//   ordinate data type, a point count that disagrees with the data, a 58b
//   header that is not IEEE 754 or whose byte count disagrees with its
//   points or runs past the end of the file, more than the limits allow.
std::vector<Uff58Record> ReadUff58(const std::string& path);
// The same from the file's bytes; `name` stands for the file in messages.
std::vector<Uff58Record> ParseUff58(const std::string& bytes, const std::string& name);

// Whether `bytes` begins as a universal file: its first line that is not
// blank is the delimiter "-1" and the next one a dataset number ("58",
// "58b", "2411", ...). Used to tell a .uff file from a text table.
bool LooksLikeUff(const std::string& bytes);
// The same for the first bytes of the file at `path`; false if it is not a
// regular file or cannot be read (its reader then says why).
bool FileLooksLikeUff(const std::string& path);

// A units label of records 8-11 as deb's unit layer (UDUNITS-2 syntax,
// deb/units/unit.h) reads it, or nullopt for a label that gives no unit
// (blank or NONE). The rules:
//  - the symbol g standing alone (g, g^2/Hz, m/s^2/g) is the standard
//    acceleration of gravity, 9.80665 m/s^2, as in every vibration file,
//    not the gram: it becomes "gravity" (kg and other names with a g in
//    them are untouched);
//  - the superscripts ² and ³ become ^2 and ^3, √ before a name becomes sqrt
//    of it ("√Hz" -> "sqrt(Hz)", which only UffDensityUnit reads).
std::optional<std::string> UffUnitText(const std::string& units_label);

// The unit of a record's ordinate: UffUnitText of the numerator (record 9)
// divided by that of the denominator (record 10) when it gives one
// ("(m/s^2)/(N)"), or nullopt when the numerator gives none.
std::optional<std::string> UffOrdinateUnit(const Uff58Record& record);

// A spectrum's ordinate unit read as a density: the unit of the signal and
// whether the values are an amplitude spectral density (unit/sqrt(Hz), to be
// squared) rather than a power spectral density (unit^2/Hz). Forms read,
// from the numerator and denominator together: X^2/Hz, X²/Hz, (X)^2/Hz,
// X/sqrt(Hz), X/√Hz, X/Hz^0.5, X/Hz^(1/2).
struct UffDensityUnit {
  std::string signal_unit;  // UDUNITS-2 syntax, as UffUnitText
  bool amplitude = false;   // an ASD
};
// nullopt if the ordinate unit is not of these forms (no density: a power
// or amplitude spectrum, or no unit given).
std::optional<UffDensityUnit> UffDensity(const Uff58Record& record);

}  // namespace deb::formats
