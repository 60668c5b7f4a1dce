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
  CHECK(line == "parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity,method");
  int checked = 0;
  while (std::getline(in, line)) {
    const std::string numbers = line.substr(0, line.rfind(','));  // the method last
    CHECK(line.substr(line.rfind(',') + 1) == "central_difference");  // a source's level
    const double elasticity = std::stod(numbers.substr(numbers.rfind(',') + 1));
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

TEST_CASE("deb sensitivity states the nominal values, puts the total first and draws a tornado per output") {
  const fs::path dir = deb::test::TempDir("sensitivity_cli_tornado");
  const deb::test::Command c = deb::test::RunDeb("sensitivity " + deb::test::ExampleBudget("single_axis_isolator.yaml") +
                                                 " -p 'sources[1].spectrum.level' -p 'paths[0].num[1]' --out \"" +
                                                 (dir / "out").string() + "\"");
  REQUIRE(c.exit_code == 0);
  CHECK(c.out.find("nominal sources[1].spectrum.level = 0.01\n") != std::string::npos);
  CHECK(c.out.find("nominal paths[0].num[1] = 157.914\n") != std::string::npos);
  // Under each output's header line, the totals come first.
  const std::size_t header = c.out.find("output z_velocity: nominal rms ");
  REQUIRE(header != std::string::npos);
  const std::size_t first = c.out.find('\n', header) + 1, second = c.out.find('\n', first) + 1;
  CHECK(c.out.substr(first, c.out.find('\n', first) - first).find(" total ") != std::string::npos);
  CHECK(c.out.substr(second, c.out.find('\n', second) - second).find(" total ") != std::string::npos);
  const std::string md = deb::test::ReadAll(dir / "out" / "sensitivity.md");
  CHECK(md.find("## Nominal parameters") < md.find("## z_velocity"));
  CHECK(md.find("| sources\\[1\\].spectrum.level | sources\\[1\\].spectrum.level | 0.01 |") != std::string::npos);
  CHECK(md.find("(plots/z_velocity_tornado.png)") != std::string::npos);
  CHECK(fs::file_size(dir / "out" / "plots" / "z_velocity_tornado.png") > 1000);
  fs::remove_all(dir);
}

TEST_CASE("deb sensitivity names a parameter by its --label, and states an expression's nominal value") {
  // nizamoglu2015_h210: gains: Kv, a parameter of 50; the label names it on the console, tables and tornado.
  const fs::path dir = deb::test::TempDir("sensitivity_cli_label");
  const deb::test::Command c = deb::test::RunDeb(
      "sensitivity " + deb::test::ExampleBudget("nizamoglu2015_h210.yaml") +
      " -p 'paths[0].control.gains' --label 'paths[0].control.gains=skyhook gain K_v' --no-plots --out \"" +
      (dir / "out").string() + "\"");
  REQUIRE_MESSAGE(c.exit_code == 0, c.err);
  CHECK(c.out.find("nominal skyhook gain K_v = 50\n") != std::string::npos);  // not nan
  CHECK(c.out.find("  skyhook gain K_v ") != std::string::npos);
  const std::string md = deb::test::ReadAll(dir / "out" / "sensitivity.md");
  CHECK(md.find("| skyhook gain K\\_v | paths\\[0\\].control.gains | 50 |") != std::string::npos);
  // The CSV keeps the key path, for scripts.
  const std::string csv = deb::test::ReadAll(dir / "out" / "sensitivity.csv");
  CHECK(csv.find("\npaths[0].control.gains,") != std::string::npos);
  // A label for no -p parameter: exit 3, the nearest named.
  const deb::test::Command bad = deb::test::RunDeb(
      "sensitivity " + deb::test::ExampleBudget("nizamoglu2015_h210.yaml") +
      " -p 'paths[0].control.gains' --label 'paths[0].control.gain=x' --no-plots --out \"" + (dir / "bad").string() +
      "\"");
  CHECK(bad.exit_code == 3);
  CHECK(bad.err.find("is not one of the -p parameters (did you mean 'paths[0].control.gains'?)") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "bad"));
  // A label's text follows the rule of a sweep's label: one line of at most 60 characters.
  const deb::test::Command long_label = deb::test::RunDeb(
      "sensitivity " + deb::test::ExampleBudget("nizamoglu2015_h210.yaml") + " -p 'paths[0].control.gains' --label "
      "'paths[0].control.gains=" + std::string(61, 'k') + "' --no-plots --out \"" + (dir / "long").string() + "\"");
  CHECK(long_label.exit_code == 3);
  CHECK(long_label.err.find("the label has 61 characters, more than the 60 an axis can show") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "long"));
  const deb::test::Command blank = deb::test::RunDeb(
      "sensitivity " + deb::test::ExampleBudget("nizamoglu2015_h210.yaml") +
      " -p 'paths[0].control.gains' --label 'paths[0].control.gains= ' --no-plots --out \"" + (dir / "blank").string() +
      "\"");
  CHECK(blank.exit_code == 3);
  CHECK(blank.err.find("the label is empty") != std::string::npos);
  fs::remove_all(dir);
}
