// deb compare as a user meets it: a budget against itself and against its
// own result directory; the three files, written atomically.
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

TEST_CASE("deb compare of a budget with itself writes zero differences and ratio 1 into the default directory") {
  const fs::path dir = TempDir("compare_cli");
  const std::string budget = ExampleBudget("single_axis_isolator.yaml");
  REQUIRE(RunDebIn(dir, "compare " + budget + " " + budget + " -q").exit_code == 0);
  const fs::path out = dir / "reports" / "compare_single_axis_isolator_vs_single_axis_isolator";
  const auto j = nlohmann::json::parse(ReadAll(out / "compare.json"));
  REQUIRE(j["figures"].size() > 10);
  for (const auto& f : j["figures"]) {
    CHECK(f["difference"].get<double>() == 0.0);
    // A term below 1e-3 of its output's variance has no ratio (0 / 0 at worst).
    if (f["negligible_a"].get<bool>()) CHECK(f["ratio"].is_null());
    else CHECK(f["ratio"].get<double>() == 1.0);
  }
  {
    const std::string md = ReadAll(out / "compare.md");
    const std::size_t row = md.find("| **total** | **whole grid** | **14.0");  // 14.035 um/s
    REQUIRE(row != std::string::npos);
    const std::string line = md.substr(row, md.find('\n', row) - row);
    CHECK(line.find("| **0** | **1.000** |") != std::string::npos);
  }
  CHECK(ReadAll(out / "compare.csv").rfind("output,unit,contributor,band,", 0) == 0);
  CHECK(ReadAll(out / "compare.html").find("<caption>Contributors that changed most</caption>") != std::string::npos);
  // compare.pdf: the headline and per-output tables, then one figure per overlay plot; no SVG left behind.
  CHECK(deb::test::PdfPages(out / "compare.pdf") >= 2);
  if (deb::test::Shell("command -v pdftotext >/dev/null").exit_code == 0) {
    const auto text = deb::test::Shell("pdftotext \"" + (out / "compare.pdf").string() + "\" -");
    CHECK(text.out.find("Headline: total RMS per output") != std::string::npos);
    CHECK(text.out.find("A and B overlaid") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(out / "plots" / ".pdf_figures"));
  // Two budgets: PSD and CPS overlays per output, as PNG with their data and script.
  for (const char* stem : {"z_velocity_psd_overlay", "z_displacement_cps_overlay"}) {
    CAPTURE(stem);
    CHECK(fs::file_size(out / "plots" / (std::string(stem) + ".png")) > 1000);
    CHECK(fs::exists(out / "plots" / (std::string(stem) + ".gp")));
    CHECK(ReadAll(out / "compare.md").find(std::string("(plots/") + stem + ".png)") != std::string::npos);
  }

  // Against a result directory of the same budget: the same figures.
  REQUIRE(RunDebIn(dir, "run " + budget + " --no-plots -q --out run_a").exit_code == 0);
  REQUIRE(RunDebIn(dir, "compare run_a " + budget + " -q --out cmp").exit_code == 0);
  const auto k = nlohmann::json::parse(ReadAll(dir / "cmp" / "compare.json"));
  CHECK(k["a"] == "run_a");
  // Both name the budget by its digest: the directory's from its summary.json, the file's its own.
  {
    const std::string md = ReadAll(dir / "cmp" / "compare.md");
    const std::string digest = nlohmann::json::parse(ReadAll(dir / "run_a" / "summary.json"))["budget_sha256"];
    REQUIRE(digest.size() == 64);
    const std::string sha = "SHA-256 " + digest;
    const std::size_t first = md.find(sha);
    REQUIRE(first != std::string::npos);
    CHECK(md.find(sha, first + 1) != std::string::npos);
  }
  for (const auto& f : k["figures"])
    if (!f["ratio"].is_null()) CHECK(f["ratio"].get<double>() == doctest::Approx(1.0).epsilon(1e-15));
  // Its result store draws the overlays as the budget does: the same data.
  for (const char* stem : {"z_velocity_psd_overlay", "z_displacement_cps_overlay"}) {
    CAPTURE(stem);
    const std::string from_store = ReadAll(dir / "cmp" / "plots" / (std::string(stem) + ".csv"));
    const std::string from_budget = ReadAll(out / "plots" / (std::string(stem) + ".csv"));
    const auto data = [](const std::string& csv) { return csv.substr(csv.find("\n0.") + 1); };
    REQUIRE(from_store.find("\n0.") != std::string::npos);
    CHECK(data(from_store) == data(from_budget));
    CHECK(fs::file_size(dir / "cmp" / "plots" / (std::string(stem) + ".png")) > 1000);
  }

  // A directory without summary.json is invalid input, and nothing is written.
  fs::create_directories(dir / "empty");
  const Command empty = RunDebIn(dir, "compare empty " + budget + " -q --out none");
  CHECK(empty.exit_code == 3);
  CHECK(empty.err.find("summary.json") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "none"));
  fs::remove_all(dir);
}

TEST_CASE("deb compare A B C with an invalid C exits 3 and writes no comparison, not even A vs B") {
  const fs::path dir = TempDir("compare_cli_all");
  const std::string budget = ExampleBudget("single_axis_isolator.yaml");
  std::ofstream(dir / "broken.yaml") << "name: broken\nbogus_key: 1\n";
  const Command broken = RunDebIn(dir, "compare " + budget + " " + budget + " broken.yaml -q --no-plots");
  CHECK(broken.exit_code == 3);
  CHECK(broken.err.find("broken.yaml:2:1: bogus_key: unknown key") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "reports"));
  // The valid inputs alone still compare.
  REQUIRE(RunDebIn(dir, "compare " + budget + " " + budget + " -q --no-plots").exit_code == 0);
  CHECK(fs::exists(dir / "reports" / "compare_single_axis_isolator_vs_single_axis_isolator" / "compare.json"));
  fs::remove_all(dir);
}

TEST_CASE("deb compare --tolerance is a regression gate: exit 6 and the figures that moved, reports written") {
  const fs::path dir = TempDir("compare_cli_tolerance");
  const std::string budget = ExampleBudget("single_axis_isolator.yaml");
  // A noisier geophone (1.4 % of the velocity variance), then +3 % more: the
  // sensor_noise RMS moves by exactly 3 %, the totals by less.
  const std::string text = ReadAll(budget), level = "level: 0.01\n";
  REQUIRE(text.find(level) != std::string::npos);
  for (const auto& [file, to] : {std::pair<std::string, std::string>{"noisy.yaml", "level: 1.0\n"},
                                 std::pair<std::string, std::string>{"noisier.yaml", "level: 1.03\n"}}) {
    std::string t = text;
    t.replace(t.find(level), level.size(), to);
    std::ofstream(dir / file) << t;
  }
  const std::string args = "compare noisy.yaml noisier.yaml --no-plots -q --out cmp --force";
  CHECK(RunDebIn(dir, args + " --tolerance 0.031").exit_code == 0);
  const Command gate = RunDebIn(dir, args + " --tolerance 0.029");
  CHECK(gate.exit_code == 6);
  CHECK(gate.err.find("moved by more than 0.029 relative (--tolerance)") != std::string::npos);
  CHECK(gate.err.find("z_velocity, sensor_noise: ") != std::string::npos);
  CHECK(gate.err.find(", floor") == std::string::npos);  // the floor did not move
  // compare.json records the gate: the tolerance and the figures that moved.
  const auto j = nlohmann::json::parse(ReadAll(dir / "cmp" / "compare.json"));
  CHECK(j["tolerance"].get<double>() == 0.029);
  REQUIRE(j["moved"].size() >= 1);
  for (const auto& f : j["moved"]) CHECK(f["contributor"] != "floor");
  CHECK(ReadAll(dir / "cmp" / "compare.md").find("## Moved by more than 2.90 % (--tolerance)") != std::string::npos);
  // The headline table leads compare.md, naming the contributor that changed.
  const std::string md = ReadAll(dir / "cmp" / "compare.md");
  const std::size_t headline = md.find("## Headline"), first_output = md.find("## z_velocity [");
  REQUIRE(headline != std::string::npos);
  CHECK(headline < first_output);
  CHECK(md.find("| sensor\\_noise +", headline) < first_output);
  CHECK(RunDebIn(dir, args + " --tolerance -1").exit_code == 2);
  fs::remove_all(dir);
}
