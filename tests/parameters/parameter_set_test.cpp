#include "deb/parameters/parameter_set.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "deb/units/unit.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

using test::Contains;

constexpr double kPi = 3.14159265358979323846;

ParameterDefinition Def(const std::string& name, const std::string& expression) {
  return {name, expression, "", "parameters." + name, ""};
}

std::string ErrorOf(const std::vector<ParameterDefinition>& defs, std::string* key_path = nullptr) {
  try {
    ParameterSet::Evaluate(defs);
  } catch (const InputError& e) {
    if (key_path) *key_path = e.key_path();
    return e.what();
  }
  return "no error";
}

TEST_CASE("derived parameters are evaluated after the ones they use, in any order written") {
  // f_susp = sqrt(4 k / m) / (2 pi), written before k_iso and m.
  const ParameterSet set = ParameterSet::Evaluate({Def("f_susp", "sqrt(4*k_iso/m)/(2*pi)"), Def("m", "2100 kg"),
                                                   Def("k_iso", "5.2e4 N/m"), Def("zeta", "0.02"),
                                                   Def("c", "2*zeta*sqrt(k_iso*m)")});
  REQUIRE(set.Find("f_susp"));
  CHECK(std::abs(ValueIn(*set.Find("f_susp"), "Hz") - std::sqrt(4 * 5.2e4 / 2100.0) / (2 * kPi)) <=
        1e-14 * 1.58);
  // c = 2 zeta sqrt(k m) in N s/m.
  CHECK(std::abs(ValueIn(*set.Find("c"), "N s/m") - 2 * 0.02 * std::sqrt(5.2e4 * 2100.0)) <= 1e-12 * 420.0);
  CHECK(set.parameters()[0].derived);
  CHECK_FALSE(set.parameters()[1].derived);
  CHECK(set.parameters()[1].unit == "kg");
  CHECK(set.Names() == std::vector<std::string>{"f_susp", "m", "k_iso", "zeta", "c"});
  CHECK(set.Find("nothing") == nullptr);
  CHECK(std::abs(ValueIn(set.EvaluateText("m*2"), "t") - 4.2) <= 1e-15 * 4.2);
}

TEST_CASE("bad parameter sets are refused at the parameter, saying why") {
  std::string where;
  CHECK(Contains(ErrorOf({Def("a", "b + 1"), Def("b", "2*a")}, &where),
                 "parameters refer to each other in a cycle: a -> b -> a"));
  CHECK(where == "parameters.a");
  CHECK(Contains(ErrorOf({Def("a", "a")}), "cycle: a -> a"));
  CHECK(Contains(ErrorOf({Def("x", "1"), Def("a", "b"), Def("b", "c"), Def("c", "a + x")}),
                 "cycle: a -> b -> c -> a"));
  CHECK(Contains(ErrorOf({Def("k_iso", "1 N/m"), Def("f", "kiso*2")}, &where), "unknown name 'kiso' (did you mean 'k_iso'?)"));
  CHECK(where == "parameters.f");
  // The unknown name, wherever it stands among known ones.
  CHECK(Contains(ErrorOf({Def("k", "1 N/m"), Def("f", "sqrt(k/mass)")}), "column 8: unknown name 'mass'"));
  CHECK(Contains(ErrorOf({Def("m", "1 kg"), Def("m", "2 kg")}), "parameter 'm' is defined twice"));
  CHECK(Contains(ErrorOf({Def("pi", "3")}), "'pi' is not a parameter name (it is a function or the constant pi)"));
  CHECK(Contains(ErrorOf({Def("2x", "3")}), "'2x' is not a parameter name"));
  CHECK(Contains(ErrorOf({Def("m", "1 kg"), Def("k", "1 N/m"), Def("bad", "m + k")}, &where),
                 "cannot add kg and kg s-2"));
  CHECK(where == "parameters.bad");
  // A chain longer than kMaxParameterDepth is refused, not a stack overflow.
  std::vector<ParameterDefinition> chain{Def("p0", "1")};
  for (int i = 1; i < 1000; ++i) chain.push_back(Def("p" + std::to_string(i), "p" + std::to_string(i - 1) + "+1"));
  std::reverse(chain.begin(), chain.end());
  CHECK(Contains(ErrorOf(chain), "more than 256 deep"));
  std::vector<ParameterDefinition> many;
  for (std::size_t i = 0; i <= kMaxParameters; ++i) many.push_back(Def("q" + std::to_string(i), "1"));
  CHECK(Contains(ErrorOf(many), "more than 10000 parameters"));
}

}  // namespace
}  // namespace deb

namespace deb {

TEST_CASE("a parameter's unit: a derived stiffness shown in N/m, checked against its value") {
  ParameterDefinition k{"k", "m*(2*pi*f)^2", "", "parameters.k", "N/m"};
  ParameterDefinition c{"c", "2*0.01*sqrt(k*m)", "", "parameters.c", "N s/m"};
  const ParameterSet set = ParameterSet::Evaluate({{"m", "20 kg", "", "parameters.m", ""},
                                                   {"f", "60 Hz", "", "parameters.f", ""}, k, c});
  CHECK(set.parameters()[2].unit == "N/m");
  CHECK(set.parameters()[3].unit == "N s/m");
  CHECK(ValueIn(set.parameters()[2].value, "N/m") == doctest::Approx(20.0 * std::pow(2 * 3.14159265358979323846 * 60.0, 2)).epsilon(1e-15));
  // A literal keeps its own unit unless one is given.
  CHECK(set.parameters()[0].unit == "kg");
  k.unit = "N s/m";
  std::string key;
  const std::string message = [&] {
    try {
      ParameterSet::Evaluate({{"m", "20 kg", "", "parameters.m", ""}, {"f", "60 Hz", "", "parameters.f", ""}, k});
    } catch (const InputError& e) {
      key = e.key_path();
      return std::string(e.what());
    }
    return std::string("no error");
  }();
  CHECK(key == "parameters.k.unit");
  CHECK(test::Contains(message, "'k' is 2.84245e+06 kg s-2, not a quantity in 'N s/m'"));
}

}  // namespace deb
