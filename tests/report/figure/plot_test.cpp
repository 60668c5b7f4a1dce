#include "deb/report/figure/plot.h"

#include <doctest/doctest.h>

namespace deb::report {

TEST_CASE("gnuplot strings are single-quoted with doubled quotes and no line breaks") {
  CHECK(Quote("plain") == "'plain'");
  CHECK(Quote("it's") == "'it''s'");
  CHECK(Quote("two\nlines") == "'two lines'");
}

TEST_CASE("several lines are single-quoted strings joined by a line break, so no user text is double-quoted") {
  CHECK(QuoteLines("two\nlines") == "('two'.\"\\n\".'lines')");
  CHECK(QuoteLines("say \"hi\" it's `x`") == "('say \"hi\" it''s `x`')");
  CHECK(QuoteLines(Enhanced("a_b")) == "('a\\_b')");  // gnuplot reads a\_b, as from Quote
  CHECK(Quote("a\rb\tc\x01") == "'a b c '");  // control characters would break the command
}

TEST_CASE("names are escaped for enhanced text so that underscores are not subscripts") {
  CHECK(Enhanced("sensor_noise") == "sensor\\_noise");
  CHECK(Enhanced("a^b{c}@&~") == "a\\^b\\{c\\}\\@\\&\\~");
  CHECK(Enhanced("plain text 1.5") == "plain text 1.5");
}

TEST_CASE("units are labelled with the micro sign, superscript exponents and a root sign") {
  CHECK(UnitLabel("um/s") == "µm/s");
  CHECK(UnitLabel("(um/s)^2/Hz") == "(µm/s)^{2}/Hz");
  CHECK(UnitLabel("nm/sqrt(Hz)") == "nm/√Hz");
  CHECK(UnitLabel("m s^-2") == "m s^{-2}");
  CHECK(UnitLabel("urad") == "µrad");
  CHECK(UnitLabel("us_1") == "µs\\_1");
  CHECK(UnitLabel("ux") == "ux");     // not a unit symbol after the u
  CHECK(UnitText("(um/s)^2") == "(µm/s)^2");
  CHECK(VarianceUnit("um/s") == "(um/s)^2");
  CHECK(VarianceUnit("nm") == "nm^2");
  CHECK(VarianceUnit("1") == "1");
}

TEST_CASE("numbers keep their significant digits in fixed notation over a readable range") {
  CHECK(Sig(14.0348) == "14.0");
  CHECK(Sig(0.0168874) == "0.0169");
  CHECK(Sig(1620.63) == "1621");
  CHECK(Sig(9.996) == "10.0");
  CHECK(Sig(123456.0) == "1.23e+05");
  CHECK(Sig(2.5e-7) == "2.50e-07");
  CHECK(Sig(0.0) == "0");
  CHECK(SigLabel(2.5e-7) == "2.50·10^{-7}");
  CHECK(SigLabel(3.25) == "3.25");
  CHECK(HzLabel(1e8) == "10^{8}");
  CHECK(HzLabel(1e-4) == "10^{-4}");
  CHECK(HzLabel(1000) == "1000");
  CHECK(HzLabel(0.5) == "0.5");
  CHECK(Short(20.0) == "20");
  CHECK(Short(0.1) == "0.1");
  CHECK(Share(1.0, 4.0) == "25.0 %");
  CHECK(Share(1e-6, 1.0) == "< 0.01 %");
  CHECK(HzText(1e8) == "10⁸");  // nizamoglu2015_h0's grid and last band read "1e+08 Hz"
  CHECK(HzText(1e-12) == "10⁻¹²");
  CHECK(HzText(1000.0) == "1000");
  CHECK(HzText(2.5e6) == "2.5e+06");
  CHECK(Share(-1.76e-6, 1.0) == "< 0.01 %");  // metrology_frame's mode 16 read "-1.76e-04 %", then "> −0.01 %"
  CHECK(Share(-0.25, 1.0) == "-25.0 %");
  CHECK(Share(1.0, 0.0) == "–");
}

TEST_CASE("file stems and CSV fields are safe") {
  CHECK(FileStem("z velocity/µ") == "z_velocity___");
  CHECK(FileStem("") == "_");
  CHECK(CsvField("plain") == "plain");
  CHECK(CsvField("a,b") == "\"a,b\"");
  CHECK(CsvField("say \"x\"") == "\"say \"\"x\"\"\"");
  CHECK(CsvNumber(0.1) == "0.1");
}

}  // namespace deb::report
