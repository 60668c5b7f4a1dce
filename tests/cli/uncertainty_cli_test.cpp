// deb uncertainty as a user meets it: the shipped example's console, files
// and figures, and the same files byte for byte for 1 and 2 threads.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;

TEST_CASE("deb uncertainty on the thesis with tolerances: console, summary.json, samples.csv, documents, plots") {
  const fs::path dir = deb::test::TempDir("uncertainty_cli");
  const std::string budget = deb::test::ExampleBudget("nizamoglu2015_tolerances.yaml");
  const deb::test::Command c =
      deb::test::RunDeb("uncertainty " + budget + " -n 120 --method lhs --seed 3 --out \"" + (dir / "a").string() + "\"");
  REQUIRE(c.exit_code == 0);
  CHECK(c.out.find("uncertainty of nizamoglu2015_tolerances: 120 samples (lhs, seed 3)") != std::string::npos);
  CHECK(c.out.find("z_velocity [um/s]: nominal 12.05") != std::string::npos);
  CHECK(c.out.find("P(RMS <= 13) = ") != std::string::npos);
  CHECK(c.out.find("worst corners: all 16 vertices of the tolerance box") != std::string::npos);
  for (const char* f : {"summary.json", "samples.csv", "uncertainty.md", "uncertainty.html", "uncertainty.pdf",
                        "plots/z_velocity_uncertainty.png", "plots/z_velocity_drivers.png",
                        "plots/z_velocity_scatter.png", "plots/x_velocity_uncertainty.csv"})
    CHECK_MESSAGE(fs::exists(dir / "a" / f), f);
  const nlohmann::json j = nlohmann::json::parse(deb::test::ReadAll(dir / "a" / "summary.json"));
  CHECK(j["study"] == "uncertainty");
  CHECK(j["samples"] == 120);
  CHECK(j["evaluations"] == 120 + 1 + 2 * 4 + 16);
  CHECK(j["parameters"].size() == 4);
  CHECK(j["metrics"][0]["name"] == "z_velocity");
  CHECK(j["metrics"][0]["rms_max"] == 13.0);
  CHECK(deb::test::PdfPages(dir / "a" / "uncertainty.pdf") >= 4);
  fs::remove_all(dir);
}

TEST_CASE("deb uncertainty: the same seed gives the same files for 1 and 2 threads") {
  const fs::path dir = deb::test::TempDir("uncertainty_cli_threads");
  const std::string budget = deb::test::ExampleBudget("nizamoglu2015_tolerances.yaml");
  for (const char* j : {"1", "2"})
    REQUIRE(deb::test::RunDeb("uncertainty " + budget + " -n 60 --method sobol -q --no-plots -j " + j + " --out \"" +
                              (dir / j).string() + "\"")
                .exit_code == 0);
  for (const char* f : {"summary.json", "samples.csv", "uncertainty.md", "uncertainty.html"})
    CHECK_MESSAGE(deb::test::ReadAll(dir / "1" / f) == deb::test::ReadAll(dir / "2" / f), f);
  fs::remove_all(dir);
}
