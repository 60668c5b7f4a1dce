// deb run --digits N: one precision for the console table, the report's
// tables and the plot labels; the console lists contributors largest first.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

TEST_CASE("deb run --digits 3 prints 3 significant digits, largest contributor first, in the console and the documents") {
  const fs::path dir = TempDir("digits");
  const Command r = RunDeb("run " + ExampleBudget("wafer_stage.yaml") + " --no-plots --plot-scripts --digits 3 --out " + (dir / "r").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  // position: 2.173 nm, air_turbulence 1.116 nm (26.6 %) the largest, then floor 1.067 nm.
  CHECK(r.out.find("output position [nm]: rms 2.17  (requirement 1.5: FAIL)") != std::string::npos);
  const std::size_t head = r.out.find("output position");
  const std::size_t air = r.out.find("  air_turbulence", head), floor = r.out.find("  floor", head),
                    dac = r.out.find("  dac", head);
  CHECK(air < floor);
  CHECK(floor < dac);
  std::istringstream row(r.out.substr(air));
  std::string name, rms;
  row >> name >> rms;
  CHECK(rms == "1.12");
  // The report's summary table: the same precision.
  CHECK(ReadAll(dir / "r" / "report.md").find("| position | nm | 2.17 | 1.5 |") != std::string::npos);
  // The plot scripts written without plots carry it into the labels.
  CHECK(ReadAll(dir / "r" / "plots" / "position_cps.gp").find("'position: 2.17 nm RMS, FAIL 1.45× over 1.5 nm'") !=
        std::string::npos);
}

TEST_CASE("deb run --digits outside 1..15 is a usage error") {
  const Command r = RunDeb("run " + ExampleBudget() + " --no-plots --digits 0 --out " + (TempDir("digits0") / "r").string());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--digits") != std::string::npos);
}
