// --set KEY.PATH=VALUE on the commands that load a budget: the changed budget
// is the one evaluated, bad overrides are usage (2) or input (3) errors with
// no report left behind, and compare --set-b compares a budget with its variant.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using deb::test::ExampleBudget;
using deb::test::RunDeb;

namespace {

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("deb run --set evaluates the changed budget; compare --set-b shows the change") {
  const fs::path dir = deb::test::TempDir("set_cli");
  const std::string budget = ExampleBudget();
  const std::string out = "\"" + (dir / "louder").string() + "\"";
  REQUIRE(RunDeb("run " + budget + " --no-plots -q --out " + out + " --set sources[1].spectrum.level=0.03").exit_code == 0);
  const std::string summary = deb::test::ReadAll(dir / "louder" / "summary.json");
  CHECK(Has(summary, "\"geophone_noise\""));
  // B is A with the geophone three times louder: its contributor's RMS is 3x, to the printed digits.
  const auto cmp = RunDeb("compare " + budget + " " + budget + " --no-plots --out \"" + (dir / "cmp").string() +
                          "\" --set-b sources[1].spectrum.level=0.03");
  CHECK(cmp.exit_code == 0);
  // The row of the whole-grid sensor_noise term: its ratio (column 8) is 3 to 1e-12.
  const std::string csv = deb::test::ReadAll(dir / "cmp" / "compare.csv");
  const std::size_t row = csv.find("\nz_velocity,um/s,sensor_noise,,");
  REQUIRE(row != std::string::npos);
  std::string cells = csv.substr(row + 1, csv.find('\n', row + 1) - row - 1);
  for (int comma = 0; comma < 7; ++comma) cells = cells.substr(cells.find(',') + 1);
  CHECK(std::abs(std::stod(cells.substr(0, cells.find(','))) - 3.0) < 1e-12);
  CHECK(RunDeb("check " + budget + " --set sources[1].spectrum.level=0.03").exit_code == 0);
}

TEST_CASE("bad --set: malformed is a usage error, a missing key or refused value an input error, nothing written") {
  const fs::path dir = deb::test::TempDir("set_cli_bad");
  const std::string budget = ExampleBudget();
  const std::string out = " --no-plots -q --out \"" + (dir / "r").string() + "\"";
  const auto no_eq = RunDeb("run " + budget + out + " --set sources[1].spectrum.level");
  CHECK(no_eq.exit_code == 2);
  CHECK(Has(no_eq.err, "no '='"));
  const auto missing = RunDeb("run " + budget + out + " --set sources[1].spectrum.levle=2");
  CHECK(missing.exit_code == 3);
  CHECK(Has(missing.err, "did you mean 'level'"));
  const auto refused = RunDeb("run " + budget + out + " --set sources[1].spectrum.level=-2");
  CHECK(refused.exit_code == 3);
  CHECK(Has(refused.err, "single_axis_isolator.yaml:39:"));
  CHECK(Has(refused.err, "--set sources[1].spectrum.level=-2"));
  CHECK_FALSE(fs::exists(dir / "r"));
  const auto on_results = RunDeb("compare " + budget + " " + budget + " --no-plots --set-b nope=1 --out \"" +
                                 (dir / "c").string() + "\"");
  CHECK(on_results.exit_code == 3);
  CHECK_FALSE(fs::exists(dir / "c"));
}
