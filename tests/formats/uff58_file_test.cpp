// Universal file format dataset 58 (deb/formats/uff58_file.h), on files
// written by test-rig software (tests/data/uff, from the pyuff project's
// sample data, MIT licence in LICENSE-pyuff.txt there):
//  - sample_dataset58_psd.uff: one PSD (function type 9) of 3201 points,
//    complex single precision, uneven spacing (0 to 3200 Hz in 1 Hz steps,
//    written beside each value), in g²/Hz written in Latin-1;
//  - Sample_UFF58_ascii.uff and Sample_UFF58b_bin.uff: the same time
//    response (function type 1, a microphone 'Mic 01' in Pa over time in s,
//    79292 points of real single precision, evenly spaced by 1.52588e-05 s),
//    as text (E13.5: 6 significant digits) and as 58b binary data (little
//    endian IEEE 754 floats, with CRLF line ends).
// Tolerances: a value printed in the file is compared with the same text
// parsed as a double (exact); binary values exactly (0). The text file's
// digits are the binary floats rounded to 6 significant digits by their
// writer: the two agree within half a unit of the last printed digit plus
// one rounding of a float (2^-24 relative).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "deb/core/error.h"
#include "deb/formats/uff58_file.h"
#include "tests/support/contains.h"
#include "tests/support/file_bytes.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using formats::ParseUff58;
using formats::ReadUff58;
using formats::Uff58Record;
using formats::UffFunction;
using formats::UffOrdinate;
using test::Contains;
using test::InputErrorOf;
using test::Replace;

const std::string kDir = std::string(DEB_TEST_DATA_DIR) + "/uff/";
const std::string kPsd = kDir + "sample_dataset58_psd.uff";
const std::string kAscii = kDir + "Sample_UFF58_ascii.uff";
const std::string kBinary = kDir + "Sample_UFF58b_bin.uff";

// The byte offset where the binary data of the first 58b dataset starts:
// after the 12th line end (the -1 line, the 58b line, records 1-11).
std::size_t BinaryDataStart(const std::string& bytes) {
  std::size_t at = 0;
  for (int k = 0; k < 13; ++k) at = bytes.find('\n', at) + 1;
  return at;
}

TEST_CASE("a PSD dataset 58 reads as its header and data lines say, its Latin-1 unit as UTF-8") {
  const std::vector<Uff58Record> records = ReadUff58(kPsd);
  REQUIRE(records.size() == 1);
  const Uff58Record& r = records[0];
  CHECK(r.index == 1);
  CHECK(r.line == 1);
  CHECK(r.offset == 0);
  CHECK_FALSE(r.binary);
  CHECK(r.id[0] == "Power Spectral Density (PSD)");
  CHECK(r.id[1] == "VibControl Random");
  CHECK(r.id[2] == "13-Apr-23 09:57:51");
  CHECK(r.id[3] == "Channel 1");
  CHECK(r.id[4] == "NONE");
  // "    9         0    0         0 Pilot 1            0   0 NONE               0   0"
  CHECK(r.function == UffFunction::kPsd);
  CHECK(r.response_entity == "Pilot 1");
  CHECK(r.response.node == 0);
  CHECK(r.response.direction == 0);
  CHECK(r.reference_entity == "NONE");
  // "         5      3201         0 0.000000E+00 0.000000E+00 0.000000E+00"
  CHECK(r.ordinate == UffOrdinate::kComplexSingle);
  CHECK(r.points() == 3201);
  CHECK_FALSE(r.even_spacing);
  CHECK(r.abscissa_min == 0.0);
  CHECK(r.abscissa_increment == 0.0);
  CHECK(r.z_value == 0.0);
  CHECK(r.abscissa.units == "Hz");
  CHECK(r.abscissa.label == "Hz");
  CHECK(r.numerator.units == "g\xC2\xB2/Hz");  // byte 0xB2 in the file
  CHECK(r.numerator.label == "g\xC2\xB2/Hz");
  CHECK(r.denominator.units == "NONE");
  CHECK(r.z_axis.data_type == 0);
  // Data lines, three values per point (f, re, im):
  //  1: " 0.000000E+00 0.000000E+00 0.000000E+00 1.000000E+00 1.255863E-06 0.000000E+00"
  //  2: " 2.000000E+00 4.311770E-07 0.000000E+00 3.000000E+00 3.803099E-06 0.000000E+00"
  // 87: " 1.720000E+02 1.236371E-04 0.000000E+00 1.730000E+02 1.089986E-04 0.000000E+00"
  // 987: " 1.972000E+03 3.485255E-05 0.000000E+00 1.973000E+03 3.360279E-05 0.000000E+00"
  // last: " 3.200000E+03 2.634827E-10 0.000000E+00"
  CHECK(r.x[0] == 0.0);
  CHECK(r.y[0] == std::complex<double>(0.0, 0.0));
  CHECK(r.x[1] == 1.0);
  CHECK(r.y[1].real() == 1.255863E-06);
  CHECK(r.y[2].real() == 4.311770E-07);
  CHECK(r.y[3].real() == 3.803099E-06);
  CHECK(r.x[172] == 172.0);
  CHECK(r.y[172].real() == 1.236371E-04);
  CHECK(r.y[173].real() == 1.089986E-04);
  CHECK(r.y[1972].real() == 3.485255E-05);
  CHECK(r.y[1973].real() == 3.360279E-05);
  CHECK(r.x[3200] == 3200.0);
  CHECK(r.y[3200].real() == 2.634827E-10);
  std::size_t off_grid = 0, complex = 0;
  for (std::size_t i = 0; i < r.points(); ++i) {
    off_grid += r.x[i] != static_cast<double>(i);
    complex += r.y[i].imag() != 0.0;
  }
  CHECK(off_grid == 0);
  CHECK(complex == 0);
  CHECK(r.RealValues()[172] == 1.236371E-04);
  CHECK(formats::UffOrdinateUnit(r) == std::optional<std::string>("gravity^2/Hz"));
  const auto density = formats::UffDensity(r);
  REQUIRE(density);
  CHECK(density->signal_unit == "gravity");
  CHECK_FALSE(density->amplitude);
}

TEST_CASE("the ASCII and the 58b sample hold the same time response, within the printed digits") {
  const std::vector<Uff58Record> text = ReadUff58(kAscii), binary = ReadUff58(kBinary);
  REQUIRE(text.size() == 1);
  REQUIRE(binary.size() == 1);
  const Uff58Record &a = text[0], &b = binary[0];
  CHECK(b.binary);
  CHECK_FALSE(a.binary);
  CHECK(a.function == UffFunction::kTimeResponse);
  CHECK(a.response_entity == "Mic 01");
  CHECK(formats::ToString(a.response) == "0:+X");
  CHECK(a.ordinate == UffOrdinate::kRealSingle);
  CHECK(a.even_spacing);
  CHECK(a.abscissa_increment == 1.52588E-05);
  CHECK(a.abscissa.units == "s");
  CHECK(a.abscissa.data_type == 17);
  CHECK(a.numerator.units == "Pa");
  CHECK(a.numerator.label == "Pressure");
  CHECK(a.numerator.data_type == 21);
  CHECK(a.id == b.id);
  CHECK(a.response == b.response);
  CHECK(a.reference == b.reference);
  CHECK(a.abscissa.units == b.abscissa.units);
  CHECK(a.numerator.units == b.numerator.units);
  CHECK(a.abscissa_increment == b.abscissa_increment);
  REQUIRE(a.points() == 79292);
  REQUIRE(b.points() == 79292);
  // First and last data lines of the text:
  //  " -1.47553E-02 -1.72957E-02 -1.66101E-02 ..."   "  4.43632E-04 -4.31469E-03"
  CHECK(a.y[0].real() == -1.47553E-02);
  CHECK(a.y[1].real() == -1.72957E-02);
  CHECK(a.y[79290].real() == 4.43632E-04);
  CHECK(a.y[79291].real() == -4.31469E-03);
  CHECK(a.x[79291] == 79291 * 1.52588E-05);
  double worst = 0.0;  // |a - b| in units of the tolerance
  std::size_t other_x = 0, not_float = 0;
  for (std::size_t i = 0; i < a.points(); ++i) {
    other_x += a.x[i] != b.x[i];
    const double printed = a.y[i].real(), exact = b.y[i].real();
    not_float += static_cast<double>(static_cast<float>(exact)) != exact;
    const double half_unit = 0.5 * std::pow(10.0, std::floor(std::log10(std::abs(printed))) - 5);
    const double tolerance = half_unit + std::ldexp(std::abs(exact), -24);
    worst = std::max(worst, std::abs(printed - exact) / tolerance);
  }
  MESSAGE("text vs binary: largest difference ", worst, " of the tolerance");
  CHECK(worst <= 1.0);
  CHECK(other_x == 0);
  CHECK(not_float == 0);
}

// The binary record's values written as an ASCII dataset 58 with 17
// significant digits (which read back to the same double), under the binary
// file's own header lines: the two readers agree exactly.
TEST_CASE("an ASCII dataset written from the binary values reads back to them exactly") {
  const std::string bytes = test::ReadAll(kBinary);
  const Uff58Record b = ReadUff58(kBinary).at(0);
  const std::size_t data = BinaryDataStart(bytes);
  std::string text = Replace(bytes.substr(0, data), "    58b     1     2          11      317168     0     0           0           0", "    58");
  for (std::size_t i = 0; i < b.points(); ++i) {
    char cell[32];
    std::snprintf(cell, sizeof cell, "%25.17E", b.y[i].real());
    text += cell;
    if (i % 5 == 4 || i + 1 == b.points()) text += "\r\n";
  }
  text += "    -1\r\n";
  const std::vector<Uff58Record> a = ParseUff58(text, "written.uff");
  REQUIRE(a.size() == 1);
  REQUIRE(a[0].points() == b.points());
  CHECK_FALSE(a[0].binary);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < b.points(); ++i) differ += a[0].x[i] != b.x[i] || a[0].y[i] != b.y[i];
  CHECK(differ == 0);
}

// The little-endian sample turned big endian: byte order 2 in its 58b line
// and each 4-byte float reversed.
TEST_CASE("a big-endian 58b dataset reads as the little-endian one") {
  std::string bytes = test::ReadAll(kBinary);
  const std::vector<Uff58Record> little = ReadUff58(kBinary);
  const std::size_t data = BinaryDataStart(bytes);
  bytes = Replace(bytes, "    58b     1     2", "    58b     2     2");
  for (std::size_t k = data; k < data + 317168; k += 4) {
    std::swap(bytes[k], bytes[k + 3]);
    std::swap(bytes[k + 1], bytes[k + 2]);
  }
  const std::vector<Uff58Record> big = ParseUff58(bytes, "big.uff");
  REQUIRE(big.size() == 1);
  REQUIRE(big[0].points() == little[0].points());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < big[0].points(); ++i) differ += big[0].y[i] != little[0].y[i] || big[0].x[i] != little[0].x[i];
  CHECK(differ == 0);
}

TEST_CASE("complex double data in 58b, with uneven spacing, reads exactly in either byte order") {
  const std::vector<double> values = {1.0, 0.5, -0.25, 2.0, 1e-300, 3.0, 4.0, -1.5, 7.0};  // x, re, im per point
  for (const int order : {1, 2}) {
    std::string bytes = "    -1\n    58b     " + std::to_string(order) + "     2          11          72     0     0           0           0\n";
    bytes += "FRF\nNONE\nNONE\nNONE\nNONE\n";
    bytes += "    4         1    1         0 stage              1   3 shaker             2   1\n";
    bytes += "         6         3         0  0.00000E+00  0.00000E+00  0.00000E+00\n";
    bytes += "        18    0    0    0 Frequency            Hz                  \n";
    bytes += "        12    1    0   -2 Acceleration         m/s^2               \n";
    bytes += "        13    0    1    0 Force                N                   \n";
    bytes += "         0    0    0    0 NONE                 NONE                \n";
    for (const double v : values) {
      unsigned char b[8];
      std::memcpy(b, &v, 8);
      if (order == 2) std::reverse(b, b + 8);
      bytes.append(reinterpret_cast<const char*>(b), 8);
    }
    bytes += "\n    -1\n";
    const std::vector<Uff58Record> r = ParseUff58(bytes, "frf.uff");
    REQUIRE(r.size() == 1);
    CHECK(r[0].function == UffFunction::kFrf);
    CHECK(formats::ToString(r[0].response) == "1:+Z");
    CHECK(formats::ToString(r[0].reference) == "2:+X");
    CHECK(r[0].x == std::vector<double>{1.0, 2.0, 4.0});
    CHECK(r[0].y[0] == std::complex<double>(0.5, -0.25));
    CHECK(r[0].y[1] == std::complex<double>(1e-300, 3.0));
    CHECK(r[0].y[2] == std::complex<double>(-1.5, 7.0));
    CHECK(formats::UffOrdinateUnit(r[0]) == std::optional<std::string>("(m/s^2)/(N)"));
  }
}

TEST_CASE("datasets of other types are skipped, and touching fields are split at their sign") {
  const std::string text =
      "    -1\n   151\nmodel\nNONE\n    -1\n"
      "    -1\n    58\nT\nNONE\nNONE\nNONE\nNONE\n"
      "    1         0    0         0 NONE               3  -3 NONE               0   0\n"
      "         4         3         1 -1.000000E+00 5.000000E-01 0.000000E+00\n"
      "        17    0    0    0 Time                 s                   \n"
      "        12    0    0    0 Acceleration         g                   \n"
      "         0    0    0    0 NONE                 NONE                \n"
      "         0    0    0    0 NONE                 NONE                \n"
      " 1.234567E-04-2.345678E-04\n  3.0D+00\n    -1\n";
  const std::vector<Uff58Record> r = ParseUff58(text, "two.uff");
  REQUIRE(r.size() == 1);
  CHECK(r[0].index == 2);
  CHECK(r[0].line == 6);
  CHECK(r[0].x == std::vector<double>{-1.0, -0.5, 0.0});
  CHECK(r[0].y[0].real() == 1.234567E-04);
  CHECK(r[0].y[1].real() == -2.345678E-04);
  CHECK(r[0].y[2].real() == 3.0);
  CHECK(formats::ToString(r[0].response) == "3:-Z");
  CHECK(formats::UffOrdinateUnit(r[0]) == std::optional<std::string>("gravity"));
  CHECK_FALSE(formats::UffDensity(r[0]));
}

TEST_CASE("units labels: g is standard gravity, superscripts and roots as UDUNITS-2 reads them") {
  using formats::UffUnitText;
  CHECK(UffUnitText("g") == std::optional<std::string>("gravity"));
  CHECK(UffUnitText(" g\xC2\xB2/Hz ") == std::optional<std::string>("gravity^2/Hz"));
  CHECK(UffUnitText("m/s^2/g") == std::optional<std::string>("m/s^2/gravity"));
  CHECK(UffUnitText("kg") == std::optional<std::string>("kg"));
  CHECK(UffUnitText("deg") == std::optional<std::string>("deg"));
  CHECK(UffUnitText("g/\xE2\x88\x9AHz") == std::optional<std::string>("gravity/sqrt(Hz)"));
  CHECK(UffUnitText("(m/s)\xC2\xB2/Hz") == std::optional<std::string>("(m/s)^2/Hz"));
  CHECK_FALSE(UffUnitText("NONE"));
  CHECK_FALSE(UffUnitText("none"));
  CHECK_FALSE(UffUnitText("  "));

  Uff58Record r;
  const auto density = [&](const std::string& num, const std::string& den) {
    r.numerator.units = num;
    r.denominator.units = den;
    return formats::UffDensity(r);
  };
  CHECK(density("g\xC2\xB2/Hz", "NONE")->signal_unit == "gravity");
  CHECK(density("(m/s)^2/Hz", "NONE")->signal_unit == "m/s");
  CHECK(density("um^2", "Hz")->signal_unit == "um");
  CHECK(density("g/\xE2\x88\x9AHz", "NONE")->amplitude);
  CHECK(density("m/s^2/sqrt(Hz)", "NONE")->signal_unit == "m/s^2");
  CHECK(density("V", "Hz^0.5")->amplitude);
  CHECK_FALSE(density("m/s^2/Hz", "NONE"));  // not the square of a unit
  CHECK_FALSE(density("g^2", "NONE"));       // a power spectrum, not a density
  CHECK_FALSE(density("g", "NONE"));
  CHECK_FALSE(density("NONE", "Hz"));
}

TEST_CASE("DOFs read and print as NODE:DIRECTION") {
  CHECK(formats::ToString(formats::ParseUffDof("1:+Z")) == "1:+Z");
  CHECK(formats::ToString(formats::ParseUffDof("12:-rx")) == "12:-RX");
  CHECK(formats::ToString(formats::ParseUffDof("3:Y")) == "3:+Y");
  CHECK(formats::ToString(formats::ParseUffDof("0:scalar")) == "0:scalar");
  CHECK(Contains(InputErrorOf([] { formats::ParseUffDof("1+Z"); }), "is not a DOF NODE:DIRECTION"));
  CHECK(Contains(InputErrorOf([] { formats::ParseUffDof("1:W"); }), "is not a DOF"));
  CHECK(Contains(InputErrorOf([] { formats::ParseUffDof("-1:X"); }), "is not a DOF"));
}

TEST_CASE("a universal file is told from a text table by its first lines") {
  CHECK(formats::LooksLikeUff("    -1\n    58\n"));
  CHECK(formats::LooksLikeUff("\n    -1\r\n    58b     1     2\r\n"));
  CHECK(formats::LooksLikeUff("    -1\n  2411\n"));
  CHECK_FALSE(formats::LooksLikeUff("f_hz, x/F.re, x/F.im\n1, 2, 3\n"));
  CHECK_FALSE(formats::LooksLikeUff("    -1\n"));
  CHECK_FALSE(formats::LooksLikeUff(""));
  CHECK(formats::FileLooksLikeUff(kPsd));
  CHECK(formats::FileLooksLikeUff(kBinary));
  CHECK_FALSE(formats::FileLooksLikeUff(kDir + "LICENSE-pyuff.txt"));
}

// Every bad input: an InputError naming the file, the line or byte, the
// dataset and (where one is to blame) the record.
TEST_CASE("bad input is an error naming the file, the line or byte, the dataset and the rule") {
  const std::string psd = test::ReadAll(kPsd);
  const std::string bin = test::ReadAll(kBinary);
  const auto error = [](const std::string& bytes) { return InputErrorOf([&] { ParseUff58(bytes, "bad.uff"); }); };
  const auto check = [&](const std::string& bytes, const std::string& where, const std::string& rule) {
    const std::string e = error(bytes);
    CHECK_MESSAGE(Contains(e, "bad.uff:" + where), e);
    CHECK_MESSAGE(Contains(e, rule), e);
  };

  SUBCASE("truncated at several offsets") {
    // In record 6, after record 7, inside the data, before the closing delimiter.
    check(psd.substr(0, psd.find("Pilot 1")), "8:42: dataset #1 (58), record 6:", "(response node) are blank");
    check(psd.substr(0, psd.find("         0    0    0    0 Hz")), "9:1: dataset #1 (58), record 8:",
          "the dataset ends before record 8 of the 11 header records (truncated)");
    check(psd.substr(0, psd.find(" 1.720000E+02")), "99:1: dataset #1 (58), record 12:",
          "the file ends after 516 of the 9603 values");
    check(psd.substr(0, psd.rfind("    -1")), "1614:1: dataset #1 (58), record 12:",
          "the file ends without the delimiter -1 that closes the dataset");
    check(psd.substr(0, 7), "1:1:", "the file ends after the delimiter -1 that opens dataset #1");
    check(bin.substr(0, BinaryDataStart(bin) + 1000), " byte 572: dataset #1 (58b), record 12:",
          "the file ends 1000 bytes after record 11 (the dataset is truncated)");
  }
  SUBCASE("unknown function type") {
    check(Replace(psd, "    9         0", "   99         0"), "8:1: dataset #1 (58), record 6:", "function type 99 is unknown");
  }
  SUBCASE("unknown ordinate data type or direction") {
    check(Replace(psd, "         5      3201", "         3      3201"), "9:1: dataset #1 (58), record 7:",
          "ordinate data type 3 is unknown");
    check(Replace(psd, "Pilot 1            0   0", "Pilot 1            0   7"), "8:52: dataset #1 (58), record 6:",
          "response direction 7 is not a direction");
  }
  SUBCASE("a point count that disagrees with the data") {
    check(Replace(psd, "      3201", "      3202"), "1615:1: dataset #1 (58), record 12:",
          "holds 9603 values, but 3202 point(s) of complex single precision with their abscissae need 9606");
    check(Replace(psd, "      3201", "      3200"), "1614:2: dataset #1 (58), record 12:",
          "more values than the 9600 that 3200 point(s)");
  }
  SUBCASE("a field that is not a number, or not finite") {
    check(Replace(psd, "1.255863E-06", "1.2558x3E-06"), "14:54: dataset #1 (58), record 12:", "'1.2558x3E-06' is not a number");
    CHECK(error(Replace(psd, "1.255863E-06", "1.255863E+99")) == "(no error)");
    check(Replace(psd, "1.255863E-06", "1.2558E+999"), "14:54: dataset #1 (58), record 12:", "is not a finite number");
    check(Replace(psd, "1.255863E-06", "         nan"), "14:63: dataset #1 (58), record 12:", "'nan' is not a finite number");
    check(Replace(psd, "      3201         0", "      32x1         0"), "9:17: dataset #1 (58), record 7:",
          "'32x1' is not a number");
    check(Replace(psd, "         0    0    0    0 Hz", "         x    0    0    0 Hz"), "10:1: dataset #1 (58), record 8:",
          "columns 1-10 (specific data type) hold 'x', not an integer");
  }
  SUBCASE("a missing delimiter") {
    check(Replace(psd, "Power Spectral", "    -1\n    58\nPower Spectral").substr(7), "1:1:",
          "expected the delimiter -1 that opens a dataset");
    check(psd + "\n    -1\n    58\nX\n", "1618:1: dataset #2 (58), record 2:", "the dataset ends before record 2");
    check(Replace(psd, "    -1\n    58\n", "    58\n"), "1:1:", "expected the delimiter -1 that opens a dataset");
  }
  SUBCASE("a 58b header that lies about its byte count, or is not IEEE 754") {
    check(Replace(bin, "317168", "317172"), " byte 572: dataset #1 (58b), record 12:",
          "the 58b header announces 317172 bytes of data, but 79292 point(s) of real single precision take 317168 bytes");
    check(Replace(bin, "     2          11", "     3          11"), "2:19: dataset #1 (58b):",
          "floating-point format 3: deb reads 2 (IEEE 754) only");
    check(Replace(bin, "    58b     1", "    58b     5"), "2:13: dataset #1 (58b):", "byte order 5 is neither 1");
    // The data one point shorter than announced, the count too: the
    // delimiter is not where the bytes end.
    std::string shorter = Replace(bin, "         2     79292", "         2     79291");
    shorter = Replace(shorter, "317168", "317164");
    check(shorter, " byte 317736: dataset #1 (58b):", "the delimiter -1 must follow the 317164 bytes of data");
  }
  SUBCASE("a binary value that is not finite") {
    std::string nan = bin;
    const std::size_t at = BinaryDataStart(bin) + 8;
    nan.replace(at, 4, std::string("\x00\x00\xC0\x7F", 4));
    check(nan, " byte 580: dataset #1 (58b), record 12:", "value 3 (point 3) is not finite");
  }
  SUBCASE("no dataset at all, or text outside the datasets") {
    check("f_hz, x\n1, 2\n", "1:1:", "expected the delimiter -1 that opens a dataset of a universal file");
    CHECK(Contains(error(""), "bad.uff: holds no dataset"));
    check(psd + "\nextra\n", "1616:1:", "expected the delimiter -1");
  }
  SUBCASE("a file that is not there, through ReadUff58") {
    CHECK(Contains(InputErrorOf([&] { ReadUff58(kDir + "missing.uff"); }), "missing.uff: cannot open universal file"));
  }
}

TEST_CASE("an error in a file names the file") {
  const fs::path dir = fs::temp_directory_path() / ("deb_uff_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "cut.uff").string();
  std::ofstream(path, std::ios::binary) << test::ReadAll(kPsd).substr(0, 2000);
  const std::string e = InputErrorOf([&] { ReadUff58(path); });
  fs::remove_all(dir);
  CHECK_MESSAGE(Contains(e, path + ":"), e);
  CHECK_MESSAGE(Contains(e, "dataset #1 (58), record 12: the file ends after"), e);
}

}  // namespace
}  // namespace deb
