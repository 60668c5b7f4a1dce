// `deb report RESULT_DIR`: the report redrawn from result.h5 alone is the
// report `deb run` wrote, byte for byte (every text file, plot, PDF and
// export, with SOURCE_DATE_EPOCH); the budget file is not read again (it may
// be gone); the options of run apply; a missing or malformed store is a
// clear error that leaves nothing behind.
#include <doctest/doctest.h>

#include <filesystem>
#include <map>
#include <string>

#include "tests/support/cli_harness.h"
#include "tests/support/contains.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {

const std::string kReproducible = "SOURCE_DATE_EPOCH=1700000000";

// Every regular file under `dir`, by relative path, with its bytes.
std::map<std::string, std::string> Tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = ReadAll(e.path());
  return files;
}

// The names of the files that differ between two trees (or are in one only).
std::string Differences(const std::map<std::string, std::string>& a, const std::map<std::string, std::string>& b) {
  std::string d;
  for (const auto& [name, bytes] : a) {
    const auto other = b.find(name);
    if (other == b.end())
      d += name + " (only in the first) ";
    else if (other->second != bytes)
      d += name + " ";
  }
  for (const auto& f : b)
    if (a.count(f.first) == 0) d += f.first + " (only in the second) ";
  return d;
}

}  // namespace

TEST_CASE("deb report redraws from result.h5 the report deb run wrote, byte for byte, without the budget file") {
  const fs::path dir = TempDir("report_redraw");
  // The budget in a directory of its own, removed after the run: the
  // redraw cannot read it.
  const fs::path budget = dir / "budget" / "thesis.yaml";
  fs::create_directories(budget.parent_path());
  fs::copy_file(ExampleBudget("nizamoglu2015_h210.yaml"), budget);
  const fs::path run = dir / "run", redrawn = dir / "redrawn";
  const Command r = RunDeb("run -q \"" + budget.string() + "\" --export mat --out \"" + run.string() + "\"", kReproducible);
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  REQUIRE(fs::is_regular_file(run / "result.h5"));
  CHECK(Contains(ReadAll(run / "index.html"), "href=\"result.h5\""));
  fs::remove_all(budget.parent_path());

  const Command c = RunDeb("report \"" + run.string() + "\" --export mat --out \"" + redrawn.string() + "\"", kReproducible);
  REQUIRE_MESSAGE(c.exit_code == 0, c.err);
  CHECK(Contains(c.out, "redrawn from"));
  const auto original = Tree(run), again = Tree(redrawn);
  CHECK(original.size() > 20);  // data, documents, report.pdf, plots with their CSV and script
  CHECK(original.count("report.pdf") == 1);
  CHECK(original.count("result.mat") == 1);
  CHECK_MESSAGE(Differences(original, again).empty(), Differences(original, again));

  {  // In place, the directory is the same, with the exports it had.
    const Command inplace = RunDeb("report -q \"" + run.string() + "\"", kReproducible);
    REQUIRE_MESSAGE(inplace.exit_code == 0, inplace.err);
    CHECK_MESSAGE(Differences(original, Tree(run)).empty(), Differences(original, Tree(run)));
  }
  {  // The options of run apply: ASDs and 3 digits, as run draws them.
    fs::create_directories(budget.parent_path());
    fs::copy_file(ExampleBudget("nizamoglu2015_h210.yaml"), budget);
    const fs::path direct = dir / "direct", asd = dir / "asd";
    REQUIRE(RunDeb("run -q \"" + budget.string() + "\" --no-plots --plot-scripts --asd --digits 3 --out \"" +
                       direct.string() + "\"",
                   kReproducible)
                .exit_code == 0);
    const Command a = RunDeb("report -q \"" + (run / "result.h5").string() +
                                 "\" --no-plots --plot-scripts --asd --digits 3 --out \"" + asd.string() + "\"",
                             kReproducible);
    REQUIRE_MESSAGE(a.exit_code == 0, a.err);
    CHECK_MESSAGE(Differences(Tree(direct), Tree(asd)).empty(), Differences(Tree(direct), Tree(asd)));
    CHECK(Tree(asd) != Tree(redrawn));
  }
  fs::remove_all(dir);
}

TEST_CASE("deb report of a directory without a store, or with a malformed one, fails and writes nothing") {
  const fs::path dir = TempDir("report_errors");
  const fs::path empty = dir / "empty", out = dir / "out";
  fs::create_directories(empty);
  const Command none = RunDeb("report \"" + empty.string() + "\" --out \"" + out.string() + "\"");
  CHECK(none.exit_code == 3);
  CHECK(Contains(none.err, "holds no result store (result.h5)"));

  WriteFile(empty / "result.h5", "not HDF5 at all\n");
  const Command bad = RunDeb("report \"" + empty.string() + "\" --out \"" + out.string() + "\"");
  CHECK(bad.exit_code == 3);
  CHECK(Contains(bad.err, (empty / "result.h5").string()));
  CHECK_FALSE(fs::exists(out));
  // Nothing beside the two directories: no temporary report left behind.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.exists();
  CHECK(entries == 1);

  // A directory deb did not write is not replaced.
  const fs::path run = dir / "run", mine = dir / "mine";
  REQUIRE(RunDeb("run -q --no-plots " + ExampleBudget() + " --out \"" + run.string() + "\"").exit_code == 0);
  fs::create_directories(mine);
  WriteFile(mine / "notes.txt", "mine\n");
  const Command refused = RunDeb("report --no-plots \"" + run.string() + "\" --out \"" + mine.string() + "\"");
  CHECK(refused.exit_code == 4);
  CHECK(ReadAll(mine / "notes.txt") == "mine\n");
  fs::remove_all(dir);
}
