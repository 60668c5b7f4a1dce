// deb sweep on the shipped thesis sweep: h = 0...300 mm x K_v = 0...200.
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

TEST_CASE("deb sweep of the thesis case study writes one row per variant; K_v = 0 has no sensor-noise term") {
  const fs::path dir = deb::test::TempDir("sweep_cli");
  REQUIRE(deb::test::RunDeb("sweep " + deb::test::ExampleBudget("nizamoglu2015_sweep.yaml") + " -q --out \"" +
                            (dir / "out").string() + "\"")
              .exit_code == 0);
  std::ifstream in(dir / "out" / "sweep.csv");
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  REQUIRE(lines.size() == 1 + 8 * 4);
  CHECK(lines[0].rfind("paths[0].control.gains,paths[0].isolators[*].position[2],z_velocity.rms,"
                       "z_velocity.floor.rms,z_velocity.sensor_noise.rms,",
                       0) == 0);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::stringstream row(lines[i]);
    std::vector<double> v;
    std::string cell;
    while (std::getline(row, cell, ',')) v.push_back(std::stod(cell));
    REQUIRE(v.size() > 4);
    if (v[0] == 0.0) CHECK(v[4] == 0.0);  // passive: the sensor-noise path is zero
    else CHECK(v[4] > 1.0);               // grows with K_v: about 11 um/s at K_v = 50 (thesis Table 5-4)
    // The thesis' two cases (Table 5-4) among the variants, on the sweep's coarser grid.
    if (v[0] == 50.0 && std::abs(v[1] + 210.0) < 1e-9) CHECK(std::abs(v[4] - 11.1981) < 0.01);
    if (v[0] == 50.0 && v[1] == 0.0) CHECK(std::abs(v[4] - 11.2137) < 0.01);
  }
  CHECK(fs::file_size(dir / "out" / "plots" / "z_velocity_sweep.png") > 1000);  // RMS against K_v
  fs::remove_all(dir);
}

TEST_CASE("deb sweep prints the three best variants by label and unit and writes sweep.md and sweep.html") {
  const fs::path dir = deb::test::TempDir("sweep_cli_docs");
  const deb::test::Command c = deb::test::RunDeb("sweep " + deb::test::ExampleBudget("nizamoglu2015_sweep.yaml") +
                                                 " --no-plots --out \"" + (dir / "out").string() + "\"");
  INFO(c.err);
  REQUIRE(c.exit_code == 0);
  // No requirement in the thesis budget: ranked by RMS relative to each output's worst.
  const std::size_t head = c.out.find("best variants");
  REQUIRE(head != std::string::npos);
  CHECK(c.out.find("  1. skyhook gain K_v = ", head) != std::string::npos);
  CHECK(c.out.find("  3. ", head) != std::string::npos);
  CHECK(c.out.find("  4. ", head) == std::string::npos);
  CHECK(c.out.find(" mm: 0 output(s) fail") != std::string::npos);
  const std::string md = deb::test::ReadAll(dir / "out" / "sweep.md");
  CHECK(md.find("## Best variant per output") != std::string::npos);
  // 32 variants ranked, one row each.
  std::size_t rows = 0;
  for (std::size_t at = md.find("\n| ", md.find("## Variants, best first")); at != std::string::npos;
       at = md.find("\n| ", at + 1))
    ++rows;
  CHECK(rows == 2 + 32);  // header, rule, variants
  CHECK(deb::test::ReadAll(dir / "out" / "sweep.html").find("<caption>Variants, best first</caption>") !=
        std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("deb sweep --shard K/N and deb merge: the parts joined give the unsharded sweep byte for byte") {
  const fs::path dir = deb::test::TempDir("sweep_shards");
  const std::string budget = deb::test::ExampleBudget("nizamoglu2015_sweep.yaml");
  const std::string env = "SOURCE_DATE_EPOCH=1700000000";
  REQUIRE(deb::test::RunDebIn(dir, "sweep " + budget + " -q --out serial", env).exit_code == 0);
  for (int k = 1; k <= 3; ++k)
    REQUIRE(deb::test::RunDebIn(dir, "sweep " + budget + " -q -j 1 --shard " + std::to_string(k) + "/3 --out p" +
                                         std::to_string(k),
                                env)
                .exit_code == 0);
  const deb::test::Command m = deb::test::RunDebIn(dir, "merge p3 p1 p2 --out merged", env);
  REQUIRE(m.exit_code == 0);
  CHECK(m.out.find("sweep of nizamoglu2015_sweep:") != std::string::npos);
  std::size_t files = 0;
  CHECK(deb::test::FilesDiffering(dir / "serial", dir / "merged", &files).empty());
  CHECK(files > 5);
  // A sweep's part and an uncertainty study's do not mix; a shard missing.
  REQUIRE(deb::test::RunDebIn(dir, "uncertainty " + deb::test::ExampleBudget("nizamoglu2015_tolerances.yaml") +
                                       " -n 10 -q --no-plots --shard 2/3 --out u2",
                              env)
              .exit_code == 0);
  const deb::test::Command mixed = deb::test::RunDebIn(dir, "merge p1 u2 p3 --out bad", env);
  CHECK(mixed.exit_code == 3);
  CHECK(mixed.err.find("u2 is a part of an uncertainty study, p1 of a sweep") != std::string::npos);
  const deb::test::Command missing = deb::test::RunDebIn(dir, "merge p1 p3 --out bad", env);
  CHECK(missing.exit_code == 3);
  CHECK(missing.err.find("shard 2 of 3 is missing") != std::string::npos);
  // A part whose variants are not laid out as the others' (an edited file):
  // refused before the report reads it.
  fs::create_directories(dir / "edited");
  std::string text = deb::test::ReadAll(dir / "p2" / "part.json");
  const std::string name = "\"name\":\"z_velocity\"";
  const std::size_t at = text.find(name);
  REQUIRE(at != std::string::npos);
  text.replace(at, name.size(), "\"name\":\"q_velocity\"");
  deb::test::WriteFile(dir / "edited" / "part.json", text);
  const deb::test::Command edited = deb::test::RunDebIn(dir, "merge p1 edited p3 --out bad", env);
  CHECK(edited.exit_code == 3);
  CHECK(edited.err.find("edited: variant") != std::string::npos);
  CHECK(edited.err.find("not what deb wrote") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "bad"));
  fs::remove_all(dir);
}

TEST_CASE("--timeout of sweep, uncertainty and optimise: seconds, finite and >= 0, else a usage error saying so") {
  const std::string tolerances = deb::test::ExampleBudget("nizamoglu2015_tolerances.yaml");
  for (const std::string& study :
       {"sweep " + deb::test::ExampleBudget("nizamoglu2015_sweep.yaml"), "uncertainty " + tolerances,
        "optimise " + tolerances + " --vary Kv"})
    for (const char* bad : {"-1", "inf", "nan", "abc"}) {
      CAPTURE(study);
      CAPTURE(bad);
      const deb::test::Command c = deb::test::RunDeb(study + " -q --timeout " + bad + " --out never_written");
      CHECK(c.exit_code == 2);
      CHECK(c.err.find("--timeout: '" + std::string(bad) + "': give seconds, a finite number >= 0 (0: no limit)") !=
            std::string::npos);
      CHECK_FALSE(fs::exists("never_written"));
    }
}
