#include "deb/load/budget_yaml.h"

#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "deb/core/error.h"

namespace deb {
namespace {

std::string ThesisBudgetText() {
  std::ifstream in(std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_h210.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, from);
  return text.replace(at, from.size(), to);
}

std::string ErrorOf(const std::string& text) {
  try {
    LoadBudgetText(text, "avis.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
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
  CHECK(b.models[0].report.find("Static pre-stress") != std::string::npos);
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
  const std::string e = ErrorOf(Replace(ThesisBudgetText(), "gains: 50", "gains: -50"));
  CHECK(e.find("avis.yaml:") == 0);
  CHECK(e.find("paths[0].control") != std::string::npos);
  CHECK(e.find("is not stable; poles with Re >= 0 [rad/s]: 45.4554 + 0j") != std::string::npos);
}

TEST_CASE("a wrong number of skyhook gains is rejected") {
  CHECK(ErrorOf(Replace(ThesisBudgetText(), "gains: 50", "gains: [50, 50]")).find(
            "one number for all six logical axes, or six numbers, got 2") != std::string::npos);
}

TEST_CASE("fewer than three isolators cannot carry the body") {
  std::string text = ThesisBudgetText();
  for (const char* p : {"      - {name: P3, position: [-615, -445, -210], stiffness: [12, 12, 19.7], damping: [0.1, 0.1, 0.1]}\n",
                        "      - {name: P4, position: [-615, 570, -210], stiffness: [12, 12, 15.38], damping: [0.1, 0.1, 0.1]}\n"})
    text = Replace(text, p, "");
  const std::string e = ErrorOf(text);
  CHECK(e.find("avis.yaml:") == 0);
  CHECK(e.find("isolators") != std::string::npos);
}

}  // namespace deb
