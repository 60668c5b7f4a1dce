// deb sensitivity as a user meets it: the CSV and its ranked Markdown.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;

TEST_CASE("deb sensitivity ranks the derivatives: an ASD level has elasticity 2 on its own contributor, 0 elsewhere") {
  const fs::path dir = deb::test::TempDir("sensitivity_cli");
  REQUIRE(deb::test::RunDeb("sensitivity " + deb::test::ExampleBudget("single_axis_isolator.yaml") +
                            " -p 'sources[1].spectrum.level' -q --out \"" + (dir / "out").string() + "\"")
              .exit_code == 0);
  std::ifstream in(dir / "out" / "sensitivity.csv");
  std::string line;
  std::getline(in, line);
  CHECK(line == "parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity");
  int checked = 0;
  while (std::getline(in, line)) {
    const double elasticity = std::stod(line.substr(line.rfind(',') + 1));
    if (line.find(",sensor_noise,") != std::string::npos) {
      CHECK(std::abs(elasticity - 2.0) < 3e-6);  // PSD = level^2; O(h^2) = 1e-6 difference error
      ++checked;
    }
    if (line.find(",floor,") != std::string::npos) {
      CHECK(elasticity == 0.0);
      ++checked;
    }
  }
  CHECK(checked == 4);  // two outputs x two contributors
  std::ifstream md(dir / "out" / "sensitivity.md");
  CHECK(md.good());
  fs::remove_all(dir);
}
