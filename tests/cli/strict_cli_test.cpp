// deb run --strict: a failed requirement becomes exit code 5 (for CI), the
// report is still written and names the allocation factor of every contributor.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {

// The single-axis example with its velocity requirement replaced.
fs::path BudgetWithVelocityLimit(const fs::path& dir, const std::string& limit) {
  std::string text = ReadAll(ExampleBudget("single_axis_isolator.yaml"));
  const std::string key = "rms_max: 20";
  REQUIRE(text.find(key) != std::string::npos);
  text.replace(text.find(key), key.size(), "rms_max: " + limit);
  const fs::path p = dir / "budget.yaml";
  std::ofstream(p) << text;
  return p;
}

}  // namespace

TEST_CASE("run --strict exits with code 5 when a requirement fails, and still writes the report") {
  const fs::path dir = TempDir("fail");
  const fs::path budget = BudgetWithVelocityLimit(dir, "0.001");
  const Command lenient = RunDeb("run " + budget.string() + " --no-plots -q --out " + (dir / "a").string());
  CHECK(lenient.exit_code == 0);
  const Command strict =
      RunDeb("run " + budget.string() + " --strict --no-plots -q --out " + (dir / "b").string());
  CHECK(strict.exit_code == 5);
  CHECK(strict.err.find("fail their requirement") != std::string::npos);
  const auto j = nlohmann::json::parse(ReadAll(dir / "b" / "summary.json"));
  CHECK(j["pass"] == false);
  const auto& velocity = j["outputs"][0];
  CHECK(velocity["requirement"]["pass"] == false);
  CHECK(velocity["requirement"]["margin"].get<double>() < 0.0);
  // 0.001 um/s is below what either contributor gives alone: no factor, a reason instead.
  for (const auto& c : velocity["contributors"]) {
    CHECK(c["allocation_factor"].is_null());
    CHECK(c["allocation_note"].get<std::string>().find("other contributors") != std::string::npos);
  }
  CHECK(ReadAll(dir / "b" / "report.md").find("allocation k") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("run --strict exits with 0 when every requirement is met, and reports allocation factors above 1") {
  const fs::path dir = TempDir("pass");
  const fs::path budget = BudgetWithVelocityLimit(dir, "1000");
  const Command r = RunDeb("run " + budget.string() + " --strict --no-plots -q --out " + (dir / "r").string());
  CHECK(r.exit_code == 0);
  const auto j = nlohmann::json::parse(ReadAll(dir / "r" / "summary.json"));
  const auto& velocity = j["outputs"][0];
  REQUIRE(velocity["requirement"]["pass"] == true);
  const double limit2 = 1000.0 * 1000.0, total = velocity["variance"].get<double>();
  for (const auto& c : velocity["contributors"]) {
    const double own = c["variance"].get<double>();
    REQUIRE(c["allocation_factor"].is_number());
    CHECK(c["allocation_factor"].get<double>() > 1.0);
    CHECK(c["allocation_factor"].get<double>() == doctest::Approx((limit2 - (total - own)) / own).epsilon(1e-12));
    CHECK(c["allocation_note"].is_null());
  }
  fs::remove_all(dir);
}

TEST_CASE("run --strict also fails on a band requirement, which summary.json and report.md list") {
  const fs::path dir = TempDir("band");
  std::string text = ReadAll(std::string(DEB_SOURCE_DIR) + "/budgets/single_axis_isolator.yaml");
  const std::string key = "rms_max: 20";
  REQUIRE(text.find(key) != std::string::npos);
  text.replace(text.find(key), key.size(),
               "rms_max: 1000\n    band_requirements: [{lo_hz: 1, hi_hz: 10, rms_max: 0.5}]");
  const fs::path budget = dir / "budget.yaml";
  std::ofstream(budget) << text;
  const Command r = RunDeb("run " + budget.string() + " --strict --no-plots -q --out " + (dir / "r").string());
  CHECK(r.exit_code == 5);
  const auto j = nlohmann::json::parse(ReadAll(dir / "r" / "summary.json"));
  const auto& velocity = j["outputs"][0];
  CHECK(velocity["requirement"]["pass"] == true);
  REQUIRE(velocity["band_requirements"].size() == 1);
  CHECK(velocity["band_requirements"][0]["pass"] == false);
  CHECK(velocity["band_requirements"][0]["rms"].get<double>() > 0.5);
  CHECK(j["pass"] == false);
  CHECK(ReadAll(dir / "r" / "report.md").find("z\\_velocity, 1–10 Hz") != std::string::npos);
  // The console names the failing band, both in the run's table and in the --strict verdict.
  CHECK(r.err.find("fail their requirement (--strict): z_velocity (band 1-10 Hz)") != std::string::npos);
  const Command plain = RunDeb("run " + budget.string() + " --no-plots --out " + (dir / "r2").string());
  REQUIRE(plain.exit_code == 0);
  const std::string out = plain.out + plain.err;
  CHECK(out.find("band 1-10 Hz: rms") != std::string::npos);
  CHECK(out.find("(requirement 0.5: FAIL)") != std::string::npos);
  fs::remove_all(dir);
}
