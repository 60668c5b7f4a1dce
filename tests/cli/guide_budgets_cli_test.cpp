// The budgets docs/guide.md and README.md quote (budgets/guide/) run, and
// print the figures the documents show: a change that alters them fails
// here, so the documents are updated with it.
#include <doctest/doctest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {

const fs::path kGuide = fs::path(DEB_SOURCE_DIR) / "budgets" / "guide";

// Per budget, lines of `deb run`'s console output that the documents quote.
const std::map<std::string, std::vector<std::string>> kQuoted = {
    {"first_budget.yaml",
     {"output table_z [nm]: rms 14.54  (requirement 12: FAIL)", "floor                             10.67   53.91%",
      "sound                             9.869   46.09%"}},
    {"feedback_loop.yaml",
     {"output position [nm]: rms 2.909  (requirement 3: PASS)", "amplifier                         1.672   33.02%",
      "encoder                           1.082   13.84%", "band 10-100 Hz: rms 2.231 (requirement 2.5: PASS)"}},
    {"modal_frame.yaml",
     {"output head_z [nm]: rms 10.58  (requirement 12: PASS)",
      "mode 1, 45 Hz: 65%; mode 2, 120 Hz: 33%; mode 3, 310 Hz: 2%",
      "mode 2, 120 Hz: 100%; mode 1, 45 Hz: -1%; mode 3, 310 Hz: 0%"}},
};

}  // namespace

TEST_CASE("every guide budget passes deb check and deb run") {
  int budgets = 0;
  for (const auto& e : fs::directory_iterator(kGuide)) {
    if (e.path().extension() != ".yaml") continue;
    ++budgets;
    const std::string file = e.path().filename().string();
    CAPTURE(file);
    const Command check = RunDeb("check \"" + e.path().string() + "\"");
    CHECK_MESSAGE(check.exit_code == 0, check.err);
    const fs::path dir = TempDir("guide");
    const Command run = RunDeb("run \"" + e.path().string() + "\" --no-plots -j 1 --out \"" + (dir / "r").string() + "\"");
    CHECK_MESSAGE(run.exit_code == 0, run.err);
    CHECK(fs::is_regular_file(dir / "r" / "summary.json"));
    CHECK(kQuoted.count(file) == 1);  // a new guide budget is quoted: add its lines above
    fs::remove_all(dir);
  }
  CHECK(budgets == static_cast<int>(kQuoted.size()));
}

TEST_CASE("the guide budgets print the figures the guide and the README quote") {
  for (const auto& quoted : kQuoted) {
    // Named, not a structured binding: CAPTURE's lambda may not capture one
    // in C++17 (clang refuses it).
    const auto& file = quoted.first;
    const auto& lines = quoted.second;
    CAPTURE(file);
    const fs::path dir = TempDir("guide_quoted");
    const Command run =
        RunDeb("run \"" + (kGuide / file).string() + "\" --no-plots -j 1 --out \"" + (dir / "r").string() + "\"");
    REQUIRE_MESSAGE(run.exit_code == 0, run.err);
    for (const std::string& line : lines) {
      CAPTURE(line);
      CHECK(run.out.find(line) != std::string::npos);
    }
    fs::remove_all(dir);
  }
}

TEST_CASE("docs/guide.md quotes deb check of the first budget as it prints it") {
  const std::string guide = ReadAll(fs::path(DEB_SOURCE_DIR) / "docs" / "guide.md");
  const std::string command = "deb check budgets/guide/first_budget.yaml\n```\n\n```text\n";
  const std::size_t start = guide.find(command);
  REQUIRE_MESSAGE(start != std::string::npos, "guide.md no longer quotes `deb check` of first_budget.yaml");
  const std::size_t from = start + command.size();
  const std::size_t end = guide.find("```", from);
  REQUIRE(end != std::string::npos);
  const Command check = RunDeb("check \"" + (kGuide / "first_budget.yaml").string() + "\"");
  REQUIRE_MESSAGE(check.exit_code == 0, check.err);
  CHECK(guide.substr(from, end - from) == check.out);
}
