// Groups on the shipped grouped budget (wafer_stage.yaml): summary.json's
// tree, the console's group table, and `deb run --group` reporting one
// sub-tree whose total is that group's variance in the full run.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using deb::test::ExampleBudget;
using deb::test::ReadAll;
using deb::test::RunDeb;

TEST_CASE("summary.json holds every group's sum; deb run --group stage totals that group's variance") {
  const fs::path dir = deb::test::TempDir("groups_cli");
  const auto full = RunDeb("run " + ExampleBudget("wafer_stage.yaml") + " --no-plots --out \"" +
                           (dir / "all").string() + "\"");
  REQUIRE(full.exit_code == 0);
  CHECK(full.out.find("  group                               rms    share\n") != std::string::npos);
  CHECK(full.out.find("\n    drive ") != std::string::npos);  // stage/drive, indented under stage
  const auto j = nlohmann::json::parse(ReadAll(dir / "all" / "summary.json"));
  const auto& out = j["outputs"][0];
  std::vector<std::string> paths;
  for (const auto& g : out["groups"]) paths.push_back(g["path"]);
  CHECK(paths == std::vector<std::string>{"environment", "facility", "stage", "stage/drive", "metrology"});
  double top = 0.0, stage = 0.0, drive_members = 0.0;
  for (const auto& g : out["groups"])
    if (g["depth"] == 0) top += g["variance"].get<double>();
  for (const auto& g : out["groups"])
    if (g["path"] == "stage") stage = g["variance"];
  for (const auto& c : out["contributors"])
    if (c.contains("group") && c["group"] == "stage/drive") drive_members += c["variance"].get<double>();
  for (const auto& g : out["groups"])
    if (g["path"] == "stage/drive") CHECK(std::abs(g["variance"].get<double>() / drive_members - 1.0) < 1e-12);
  CHECK(std::abs(top / out["variance"].get<double>() - 1.0) < 1e-12);  // every contributor is in a group
  // One sub-tree: the stage's five terms, whose total is the stage group's variance.
  const auto sub = RunDeb("run " + ExampleBudget("wafer_stage.yaml") + " --no-plots -q --group stage --out \"" +
                          (dir / "stage").string() + "\"");
  REQUIRE(sub.exit_code == 0);
  const auto js = nlohmann::json::parse(ReadAll(dir / "stage" / "summary.json"));
  CHECK(js["outputs"][0]["contributors"].size() == 5);
  CHECK(std::abs(js["outputs"][0]["variance"].get<double>() / stage - 1.0) < 1e-12);
  const auto none = RunDeb("run " + ExampleBudget("wafer_stage.yaml") + " --no-plots -q --group stag --out \"" +
                           (dir / "none").string() + "\"");
  CHECK(none.exit_code == 3);
  CHECK(none.err.find("did you mean 'stage'?") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "none"));
}
