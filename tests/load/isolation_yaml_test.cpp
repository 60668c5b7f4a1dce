#include "deb/load/budget_yaml.h"

#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "deb/core/error.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

std::string ThesisBudgetText() {
  std::ifstream in(std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_h210.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using test::Replace;

std::string ErrorOf(const std::string& text) {
  return test::InputErrorOf([&] { LoadBudgetText(text, "avis.yaml"); });
}

}  // namespace

TEST_CASE("an isolation_system entry yields the floor, noise and actuator paths, open and closed loop") {
  const Budget b = LoadBudgetText(ThesisBudgetText(), "avis.yaml");
  std::string names;
  for (const auto& p : b.paths) names += p.name + " ";
  CHECK(names == "avis.floor_open avis.actuator_open avis.floor avis.sensor_noise avis.actuator ");
  const Path& noise = b.FindPath("avis.sensor_noise");
  CHECK(noise.system.inputs() == 7);
  CHECK(noise.system.outputs() == 6);
  CHECK(noise.input_names.front() == "x1");
  CHECK(noise.output_names[2] == "z_dot");
  CHECK(noise.output_units[2] == "mm/s");
  CHECK(noise.output_units[3] == "rad/s");
  CHECK(b.FindPath("avis.actuator").input_units[0] == "N");
  REQUIRE(b.models.size() == 1);
  CHECK(b.models[0].report().find("Static pre-stress") != std::string::npos);
}

TEST_CASE("the model's numbers take quantities in any unit, converted to the model's; the literal twin is identical") {
  // The shipped budget writes h, k_h, c_iso and Kv as parameters; its literal twin writes 210 (mm), 12 (N/mm),
  // 0.1 (N s/mm) and 50, and a third writes them in SI and other units.
  const std::string thesis = ThesisBudgetText();
  std::string literal = thesis, si = thesis;
  literal = Replace(literal, "h: {value: 210 mm,", "h: {value: 210,");
  literal = Replace(literal, "k_h: {value: 12 N/mm,", "k_h: {value: 12,");
  literal = Replace(literal, "c_iso: {value: 0.1 N s/mm,", "c_iso: {value: 0.1,");
  si = Replace(si, "h: {value: 210 mm,", "h: {value: 0.21 m,");
  si = Replace(si, "k_h: {value: 12 N/mm,", "k_h: {value: 12 kN/m,");
  si = Replace(si, "c_iso: {value: 0.1 N s/mm,", "c_iso: {value: 100 N s/m,");
  si = Replace(si, "mass: 2.1\n", "mass: 2100 kg\n");
  si = Replace(si, "gravity: 9810\n", "gravity: 9.81 m/s^2\n");
  si = Replace(si, "inertia: [4.8e5, 5.0e5, 6.4e5]", "inertia: [480 kg m^2, 500 kg m^2, 640 kg m^2]");
  const Budget a = LoadBudgetText(thesis, "avis.yaml"), b = LoadBudgetText(literal, "avis.yaml"),
               c = LoadBudgetText(si, "avis.yaml");
  const StateSpace &sa = a.FindPath("avis.floor").system, &sb = b.FindPath("avis.floor").system,
                   &sc = c.FindPath("avis.floor").system;
  CHECK(sa.A() == sb.A());
  CHECK(sa.B() == sb.B());
  CHECK(sa.C() == sb.C());
  CHECK(((sa.A() - sc.A()).norm() <= 1e-12 * sa.A().norm()));
  CHECK(((sa.B() - sc.B()).norm() <= 1e-12 * sa.B().norm()));
  CHECK(ErrorOf(Replace(thesis, "position: [615, 570, -h]", "position: [615, 570, -h*2 N]")).find("isolators[0].position") !=
        std::string::npos);
}

TEST_CASE("a sensor naming an unknown isolator is an error at the sensor") {
  const std::string e = ErrorOf(Replace(ThesisBudgetText(), "{name: y4, isolator: P4, axis: y}", "{name: y4, isolator: P9, axis: y}"));
  CHECK(e.find("avis.yaml:") == 0);
  CHECK(e.find("paths[0]") != std::string::npos);
  CHECK(e.find("'P9'") != std::string::npos);
}

TEST_CASE("an inconsistent unit set is rejected naming the rule") {
  const std::string e = ErrorOf(Replace(ThesisBudgetText(), "units: {length: mm, mass: t, force: N}", "units: {length: mm, mass: kg, force: N}"));
  CHECK(e.find("paths[0].units: units are not one consistent set: 1 kg must equal 1 N s^2/mm") != std::string::npos);
}

TEST_CASE("non-positive mass is rejected at the body") {
  const std::string e = ErrorOf(Replace(ThesisBudgetText(), "mass: 2.1", "mass: 0"));
  CHECK(e.find("paths[0].body:") != std::string::npos);
  CHECK(e.find("mass") != std::string::npos);
}

TEST_CASE("an unstable closed loop is an error listing its poles, not a NaN report") {
  const std::string e = ErrorOf(Replace(ThesisBudgetText(), "gains: Kv", "gains: -Kv"));
  CHECK(e.find("avis.yaml:") == 0);
  CHECK(e.find("paths[0].control") != std::string::npos);
  CHECK(e.find("is not stable; poles with Re >= 0 [rad/s]: 45.4554 + 0j") != std::string::npos);
}

TEST_CASE("a wrong number of skyhook gains is rejected") {
  CHECK(ErrorOf(Replace(ThesisBudgetText(), "gains: Kv", "gains: [Kv, Kv]")).find(
            "one number for all six logical axes, or six numbers, got 2") != std::string::npos);
}

TEST_CASE("fewer than three isolators cannot carry the body") {
  std::string text = ThesisBudgetText();
  for (const char* p : {"      - {name: P3, position: [-615, -445, -h], stiffness: [k_h, k_h, 19.7], damping: [c_iso, c_iso, c_iso]}\n",
                        "      - {name: P4, position: [-615, 570, -h], stiffness: [k_h, k_h, 15.38], damping: [c_iso, c_iso, c_iso]}\n"})
    text = Replace(text, p, "");
  const std::string e = ErrorOf(text);
  CHECK(e.find("avis.yaml:") == 0);
  CHECK(e.find("isolators") != std::string::npos);
}

}  // namespace deb
