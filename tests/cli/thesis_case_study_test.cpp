// The thesis' published sensor-noise figures (Nizamoglu 2015, Tables 5-4 and
// 5-5), reproduced through the CLI from the shipped budgets: the summary's
// sensor_noise RMS (integrated over the grid) and its exact (Lyapunov) RMS must
// both round to the printed four decimals, |x - printed| < 5e-5.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;

namespace {

nlohmann::json RunBudget(const std::string& budget) {
  const fs::path dir = deb::test::TempDir("thesis_" + budget), out = dir / "out";
  REQUIRE(deb::test::RunDeb("run -q \"" + deb::test::ExampleBudget(budget + ".yaml") + "\" --out \"" + out.string() +
                            "\"")
              .exit_code == 0);
  std::ifstream in(out / "summary.json");
  nlohmann::json j = nlohmann::json::parse(in);
  fs::remove_all(dir);
  return j;
}

const nlohmann::json& Contributor(const nlohmann::json& summary, const std::string& output, const std::string& name) {
  for (const auto& o : summary["outputs"])
    if (o["name"] == output)
      for (const auto& c : o["contributors"])
        if (c["name"] == name) return c;
  FAIL("no contributor " << name << " on output " << output);
  static nlohmann::json none;
  return none;
}

void CheckPublished(const nlohmann::json& summary, const std::string& output, double printed) {
  const auto& c = Contributor(summary, output, "sensor_noise");
  const double rms = c["rms"].get<double>();
  const double exact = c["exact_rms"].get<double>();
  CAPTURE(output);
  CAPTURE(rms);
  CAPTURE(exact);
  CHECK(std::abs(rms - printed) < 5e-5);
  CHECK(std::abs(exact - printed) < 5e-5);
}

}  // namespace

TEST_CASE("the h = 210 mm budget reproduces 11.1981 um/s and 1.9047 um from sensor noise") {
  const nlohmann::json s = RunBudget("nizamoglu2015_h210");
  CheckPublished(s, "z_velocity", 11.1981);
  CheckPublished(s, "z_position", 1.9047);
}

TEST_CASE("the h = 0 budget reproduces 11.2137 um/s and 1.8972 um from sensor noise") {
  const nlohmann::json s = RunBudget("nizamoglu2015_h0");
  CheckPublished(s, "z_velocity", 11.2137);
  CheckPublished(s, "z_position", 1.8972);
}

TEST_CASE("the thesis budgets report all six CoG velocities and the floor contributor") {
  const nlohmann::json s = RunBudget("nizamoglu2015_h210");
  std::string names;
  for (const auto& o : s["outputs"]) names += o["name"].get<std::string>() + " ";
  CHECK(names == "z_velocity z_position x_velocity y_velocity alpha_velocity beta_velocity gamma_velocity ");
  // The floor source is not white: no exact variance, and the reason is given.
  const auto& floor = Contributor(s, "z_velocity", "floor");
  CHECK(floor["exact_rms"].is_null());
  CHECK(floor["exact_note"].get<std::string>().find("not white") != std::string::npos);
  CHECK(floor["rms"].get<double>() > 0.0);
}
