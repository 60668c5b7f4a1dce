// deb run --no-plots writes the tables, data and documents and no plots/
// directory; --plot-scripts adds each plot's CSV and gnuplot script back,
// still without drawing.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {

int CountWithExtension(const fs::path& dir, const std::string& ext) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ext) ++n;
  return n;
}

const std::string kBudget = ExampleBudget("single_axis_isolator.yaml");

}  // namespace

TEST_CASE("run --no-plots leaves no plots/ directory; the documents link no plot") {
  const fs::path dir = TempDir("plain");
  REQUIRE(RunDeb("run \"" + kBudget + "\" -q --no-plots --out \"" + (dir / "r").string() + "\"").exit_code == 0);
  CHECK(fs::is_regular_file(dir / "r" / "summary.json"));
  CHECK(fs::is_regular_file(dir / "r" / "index.html"));
  CHECK(fs::is_regular_file(dir / "r" / "report.md"));
  CHECK(fs::is_regular_file(dir / "r" / "result.h5"));  // the data
  CHECK(CountWithExtension(dir / "r", ".csv") == 0);    // each output's CSV: --export csv
  CHECK_FALSE(fs::exists(dir / "r" / "plots"));
  CHECK_FALSE(fs::exists(dir / "r" / "report.pdf"));
  CHECK(ReadAll(dir / "r" / "index.html").find("plots/") == std::string::npos);
  CHECK(ReadAll(dir / "r" / "report.md").find("plots/") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("run --no-plots --plot-scripts writes every plot's CSV and script, and draws none") {
  const fs::path dir = TempDir("scripts");
  REQUIRE(RunDeb("run \"" + kBudget + "\" -q --no-plots --plot-scripts --out \"" + (dir / "r").string() + "\"")
              .exit_code == 0);
  const fs::path plots = dir / "r" / "plots";
  REQUIRE(fs::is_directory(plots));
  const int scripts = CountWithExtension(plots, ".gp");
  CHECK(scripts >= 3);
  CHECK(CountWithExtension(plots, ".csv") == scripts + 1);  // and colours.csv
  CHECK(CountWithExtension(plots, ".png") == 0);
  CHECK(ReadAll(dir / "r" / "index.html").find("plots/") != std::string::npos);
  fs::remove_all(dir);
}
