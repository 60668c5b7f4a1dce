#include "deb/parameters/expression.h"

#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <string>

#include "deb/units/unit.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

using test::Contains;

constexpr double kPi = 3.14159265358979323846;

// The expression's value with parameters `p`; each reference value below is
// worked out by hand (stated next to it), compared at 1e-14 relative.
Quantity Eval(const std::string& text, const std::map<std::string, Quantity>& p = {}) {
  std::vector<std::string> names;
  for (const auto& [name, value] : p) names.push_back(name);
  return Expression::Parse(text).Evaluate(
      [&p](const std::string& name) -> const Quantity* {
        const auto it = p.find(name);
        return it == p.end() ? nullptr : &it->second;
      },
      names);
}

bool Near(double actual, double expected) { return std::abs(actual - expected) <= 1e-14 * std::abs(expected); }

// The ExpressionError `text` raises: its message and column.
std::pair<std::string, int> Failure(const std::string& text, const std::map<std::string, Quantity>& p = {}) {
  try {
    Eval(text, p);
  } catch (const ExpressionError& e) {
    return {e.what(), e.column_in_text()};
  }
  return {"no error", 0};
}

TEST_CASE("numbers with units are quantities in SI") {
  CHECK(Near(Eval("2100 kg").value, 2100.0));
  CHECK(Eval("2100 kg").dimension.Text() == "kg");
  CHECK(Near(Eval("5.2e4 N/m").value, 5.2e4));
  CHECK(Eval("5.2e4 N/m").dimension.Text() == "kg s-2");
  CHECK(Near(Eval("6e4N/m").value, 6e4));
  CHECK(Near(Eval("50 N/(m/s)").value, 50.0));
  CHECK(Eval("50 N/(m/s)").dimension.Text() == "kg s-1");
  CHECK(Near(Eval("210 mm").value, 0.21));
  CHECK(Near(ValueIn(Eval("0.5 um"), "nm"), 500.0));
  CHECK(Near(Eval("9.81 m s-2").value, 9.81));
  CHECK(Eval("9.81 m s-2").dimension.Text() == "m s-2");
  CHECK(Near(Eval("3 kg m2").value, 3.0));
  CHECK(Eval("3 kg m2").dimension.Text() == "m2 kg");
  CHECK(Near(Eval("1.5e-3").value, 1.5e-3));
  CHECK(Near(Eval(".5").value, 0.5));
  CHECK(Eval("0.02").dimension.IsNone());
  CHECK(Expression::Parse("2100 kg").IsLiteral());
  CHECK(Expression::Parse("-3 mm").LiteralUnit() == "mm");
  CHECK_FALSE(Expression::Parse("2*m").IsLiteral());
}

TEST_CASE("a quantity knows whether a unit made it: 0.5 rad is an angle, 0.5 a plain number") {
  CHECK(Eval("0.5 rad").has_unit);
  CHECK(Eval("0.5 rad").dimension.IsNone());
  CHECK(Eval("-2 mm * 3").has_unit);
  CHECK_FALSE(Eval("2*3 + 1").has_unit);
  CHECK_FALSE(Eval("sin(30 arc_degree)").has_unit);  // a function of an angle is a plain number
  CHECK(Near(Eval("sin(30 arc_degree)").value, 0.5));
  CHECK(Near(ValueIn(Eval("0.5 rad"), "arc_degree"), 0.5 * 180.0 / kPi));
}

TEST_CASE("precedence and associativity") {
  CHECK(Near(Eval("2*3+4").value, 10.0));
  CHECK(Near(Eval("2+3*4").value, 14.0));
  CHECK(Near(Eval("(1+2)*3").value, 9.0));
  CHECK(Near(Eval("10/4/5").value, 0.5));      // (10/4)/5
  CHECK(Near(Eval("2^3^2").value, 512.0));     // 2^(3^2)
  CHECK(Near(Eval("-2^2").value, -4.0));       // -(2^2)
  CHECK(Near(Eval("2^-1").value, 0.5));
  CHECK(Near(Eval("1 - 2 - 3").value, -4.0));  // (1-2)-3
  CHECK(Near(Eval("--3").value, 3.0));
}

TEST_CASE("a unit follows its number; a parameter is multiplied with *") {
  const std::map<std::string, Quantity> p{{"m", QuantityOf(2100.0, "kg")}, {"x", QuantityOf(4.0, "1")}};
  CHECK(Eval("2 m").dimension.Text() == "m");          // two metres
  CHECK(Eval("2*m", p).dimension.Text() == "kg");      // two times the mass
  CHECK(Near(Eval("2*m", p).value, 4200.0));
  CHECK(Near(Eval("2 m / x", p).value, 0.5));          // (2 m) / x
  CHECK(Eval("2 m / x", p).dimension.Text() == "m");
  CHECK(Near(Eval("(2 m)^2").value, 4.0));
  CHECK(Eval("(2 m)^2").dimension.Text() == "m2");
  CHECK(Near(Eval("3 mm*2").value, 0.006));
  CHECK(Near(Eval("1 m/(2*x)", p).value, 0.125));  // the unit stops before "/("
  CHECK(Near(Eval("2 pi").value, 2 * kPi));        // UDUNITS-2's unit pi
  CHECK(Near(Eval("4 um/s").value, 4e-6));
  CHECK(Near(Eval("1 mm + 2 um").value, 1.002e-3));
}

TEST_CASE("the issue's derived parameter: f = sqrt(4 k / m) / (2 pi)") {
  // sqrt(4 * 5.2e4 / 2100) / (2 pi) = sqrt(99.047619...) / 6.2831853... Hz.
  const std::map<std::string, Quantity> p{{"m", QuantityOf(2100.0, "kg")}, {"k_iso", QuantityOf(5.2e4, "N/m")}};
  const Quantity f = Eval("sqrt(4*k_iso/m)/(2*pi)", p);
  CHECK(f.dimension.Text() == "s-1");
  CHECK(Near(ValueIn(f, "Hz"), std::sqrt(4.0 * 5.2e4 / 2100.0) / (2.0 * kPi)));
}

TEST_CASE("functions") {
  CHECK(Near(Eval("log10(1000)").value, 3.0));
  CHECK(Near(Eval("exp(0)").value, 1.0));
  CHECK(Near(Eval("log(exp(2))").value, 2.0));
  CHECK(Near(Eval("sin(pi/2)").value, 1.0));
  CHECK(Near(Eval("cos(0)").value, 1.0));
  CHECK(std::abs(Eval("tan(pi/4)").value - 1.0) <= 2e-16);
  CHECK(Near(Eval("min(2 m, 300 mm)").value, 0.3));
  CHECK(Near(Eval("max(2 m, 300 mm, 1 km)").value, 1000.0));
  CHECK(Near(Eval("abs(-3 N)").value, 3.0));
  CHECK(Eval("abs(-3 N)").dimension.Text() == "m kg s-2");
  const Quantity asd = Eval("sqrt(4e-18 m^2/Hz)");  // 2e-9 m/sqrt(Hz)
  CHECK(Near(asd.value, 2e-9));
  CHECK(asd.dimension.Text() == "m s1/2");
  CHECK(Near(Eval("(9 m^2)^0.5").value, 3.0));
}

TEST_CASE("bad expressions: the rule broken and the column where") {
  const std::map<std::string, Quantity> p{{"m", QuantityOf(2100.0, "kg")},
                                          {"k_iso", QuantityOf(5.2e4, "N/m")},
                                          {"zeta", QuantityOf(0.02, "1")}};
  struct Case {
    const char* text;
    const char* says;
    int column;
  };
  const Case cases[] = {
      {"k_iso + m", "cannot add kg s-2 and kg", 7},
      {"1 m - 1 s", "cannot subtract m and s", 5},
      {"1/0", "division by zero", 2},
      {"1 m/(2-2)", "division by zero", 4},
      {"sqrt(-1)", "sqrt of a negative number", 1},
      {"log(0)", "log of a number that is not positive", 1},
      {"log10(-2)", "log10 of a number that is not positive", 1},
      {"exp(1 m)", "exp takes a dimensionless argument, not one in m", 1},
      {"sin(k_iso)", "sin takes a dimensionless argument", 1},
      {"2^(1 s)", "an exponent takes a dimensionless argument", 4},
      {"(1 m)^0.3", "has no unit (powers of units must be multiples of 1/2)", 6},
      {"(-8)^0.5", "a negative number to a power that is not whole", 5},
      {"0^-1", "zero to a negative power", 2},
      {"min(1 m, 1 s)", "cannot compare m and s", 10},
      {"2 sqrt(4)", "a unit follows its number: write '*' to multiply by sqrt", 3},
      {"2 zeta", "unknown unit 'zeta'", 3},
      {"3 zorks", "unknown unit 'zorks'", 3},
      {"kiso", "unknown name 'kiso' (did you mean 'k_iso'?)", 1},
      {"zeta + mm", "unknown name 'mm'", 8},
      {"foo(1)", "unknown function 'foo'", 1},
      {"sqrt 4", "function sqrt needs its argument in parentheses", 1},
      {"sqrt(1, 2)", "sqrt takes 1 argument, not 2", 1},
      {"max(1)", "max takes at least 2 arguments, not 1", 1},
      {"(1+2", "'(' is not closed", 1},
      {"1+2)", "')' without a matching '('", 4},
      {"1 +", "expected a number, a name or '(' but the expression ends", 4},
      {"", "expected a number, a name or '(' but the expression ends", 1},
      {"2 * * 3", "unexpected '*'", 5},
      {"1e400", "beyond the range of numbers", 1},
      {"1e300 * 1e300", "the result is not finite", 7},
      {"1.2.3", "'1.2.3' is not a number", 1},
      {"exp(1000)", "the result is not finite", 1},
      {"2 N/(m", "'(' is not closed", 5},
      {"1 N/(m/s", "'(' is not closed", 5},
      {"#", "unexpected '#'", 1},
      {"1\n+1", "a control character", 2},
  };
  for (const Case& c : cases) {
    const std::string text = c.text;
    CAPTURE(text);
    const std::pair<std::string, int> failure = Failure(c.text, p);
    CAPTURE(failure.first);
    CHECK(Contains(failure.first, c.says));
    CHECK(failure.second == c.column);
    CHECK(Contains(failure.first, "expression '"));
  }
}

TEST_CASE("sizes are bounded: length and nesting") {
  const std::string long_text(1 << 20, '1');
  const std::pair<std::string, int> failure = Failure(long_text);
  CHECK(Contains(failure.first, "longer than 4096 bytes (1048576)"));
  CHECK(failure.second == 1);
  // Within the length, 100 nested parentheses are refused by depth, not by
  // the stack.
  const std::string nested = std::string(100, '(') + "1" + std::string(100, ')');
  CHECK(Contains(Failure(nested).first, "nested deeper than 64 levels"));
  const std::string signs = std::string(3000, '-') + "1";
  CHECK(Contains(Failure(signs).first, "nested deeper than 64 levels"));
  CHECK(Near(Eval(std::string(60, '(') + "2" + std::string(60, ')')).value, 2.0));
}

TEST_CASE("names() lists the parameters used, once each, with their first offset") {
  const Expression e = Expression::Parse("sqrt(4*k/m)/(2*pi) + k*0");
  REQUIRE(e.names().size() == 2);
  CHECK(e.names()[0].first == "k");
  CHECK(e.names()[0].second == 7);
  CHECK(e.names()[1].first == "m");
}

}  // namespace
}  // namespace deb
