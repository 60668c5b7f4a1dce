// deb uncertainty as a user meets it: the shipped example's console, files
// and figures, and the same files byte for byte for 1 and 2 threads.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <tuple>

#include "deb/formats/hdf5_file.h"
#include "tests/support/cli_harness.h"
#include "tests/support/linear_level_budget.h"

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
  // Each output's drivers (four bars, 330 px) and scatter plots (420 px)
  // share a page: 7 pages, 10 when both were drawn at the overview's 600 px.
  CHECK(deb::test::PdfPages(dir / "a" / "uncertainty.pdf") <= 7);
  // result.h5 holds the same figures and every sample.
  const deb::formats::Hdf5Reader h((dir / "a" / "result.h5").string());
  CHECK(h.Integer("uncertainty/samples") == 120);
  CHECK(h.Text("uncertainty/method") == "lhs");
  const std::vector<double> mean = h.Numbers("uncertainty/metrics/mean", deb::formats::AtMost{1000});
  REQUIRE(mean.size() == j["metrics"].size());
  CHECK(mean[0] == j["metrics"][0]["mean"].get<double>());
  const std::vector<double> p = h.Numbers("uncertainty/metrics/p_meet", deb::formats::AtMost{1000}, true);
  CHECK(p[0] == j["metrics"][0]["p_meet"].get<double>());
  fs::remove_all(dir);
}

TEST_CASE("deb uncertainty: the same seed gives the same files for 1 and 2 threads") {
  const fs::path dir = deb::test::TempDir("uncertainty_cli_threads");
  const std::string budget = deb::test::ExampleBudget("nizamoglu2015_tolerances.yaml");
  for (const char* j : {"1", "2"})
    // The documents carry their date: one date for both runs.
    REQUIRE(deb::test::RunDeb("uncertainty " + budget + " -n 60 --method sobol -q --no-plots -j " + j + " --out \"" +
                                  (dir / j).string() + "\"",
                              "SOURCE_DATE_EPOCH=1700000000")
                .exit_code == 0);
  for (const char* f : {"summary.json", "samples.csv", "result.h5", "uncertainty.md", "uncertainty.html"})
    CHECK_MESSAGE(deb::test::ReadAll(dir / "1" / f) == deb::test::ReadAll(dir / "2" / f), f);
  fs::remove_all(dir);
}

TEST_CASE("deb optimise: the optimum, its budget and its report; exit 5 when no design meets the requirements") {
  const fs::path dir = deb::test::TempDir("optimise_cli");
  deb::test::WriteFile(dir / "b.yaml", R"(name: opt
parameters:
  kv: {value: 5, min: 0.5, max: 10}
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - {name: a, unit: N, spectrum: {type: flat, level: 1.0e-6}}
  - {name: b, unit: N, spectrum: {type: flat, level: 16.0e-6}}
paths:
  - {name: pa, type: gain, gain: [[kv], [kv]], outputs: [y, w], input_unit: N, output_unit: um}
  - {name: pb, type: gain, gain: [[1/kv], [0]], outputs: [y, w], input_unit: N, output_unit: um}
contributors:
  - {name: ca, source: a, path: pa}
  - {name: cb, source: b, path: pb}
outputs:
  - {name: z, signal: y, unit: um}
  - {name: w, signal: w, unit: um, rms_max: 0.0149248}
)");
  const deb::test::Command c = deb::test::RunDebIn(dir, "optimise b.yaml --vary kv --objective z --no-plots --out o");
  REQUIRE(c.exit_code == 0);
  CHECK(c.out.find("optimise opt: the RMS of z over 1 parameter(s), slsqp") != std::string::npos);
  CHECK(c.out.find("kv = 1.5") != std::string::npos);
  CHECK(c.out.find("w: RMS 0.014925 of 0.014925 (100 %), active") != std::string::npos);
  for (const char* f : {"summary.json", "history.csv", "optimum.yaml", "report/summary.json"})
    CHECK_MESSAGE(fs::exists(dir / "o" / f), f);
  CHECK(deb::test::ReadAll(dir / "o" / "optimum.yaml").find("extends: '../b.yaml'") != std::string::npos);
  // The optimum's report is optimum.yaml's, not the budget's (another design: the nominal one).
  CHECK(deb::test::ReadAll(dir / "o" / "report" / "summary.json").find("\"budget_file\": \"../optimum.yaml\"") !=
        std::string::npos);
  // The optimum is a budget deb runs.
  CHECK(deb::test::RunDebIn(dir, "run o/optimum.yaml --no-plots -q --out r").exit_code == 0);
  // A requirement no design within the bounds meets.
  const deb::test::Command none = deb::test::RunDebIn(
      dir, "optimise b.yaml --vary kv --objective z --no-plots -q --set outputs[1].rms_max=0.001 --out n");
  CHECK(none.exit_code == 5);
  CHECK(none.err.find("no design within the bounds meets every requirement; the least violating: kv = 0.5") !=
        std::string::npos);
  CHECK(fs::exists(dir / "n" / "optimum.yaml"));
  fs::remove_all(dir);
}

TEST_CASE("a loop's required margins: deb check and deb run say PASS or FAIL, summary.json and result.h5 keep them") {
  const fs::path dir = deb::test::TempDir("margins_cli");
  const std::string budget = R"(name: pm
parameters:
  k: {value: 0.5, min: 0.1, max: 10}
grid: {type: log, min_hz: 0.001, max_hz: 100, points: 400}
sources:
  - {name: d, unit: N, spectrum: {type: flat, level: 1}}
paths:
  - {name: G, type: transfer_function, num: [1], den: [1, 1, 0], input_unit: N, output_unit: m}
  - {name: K, type: gain, gain: [[k]], input_unit: m, output_unit: N}
  - {name: PS, type: feedback, plant: G, controller: K, margins: {phase_deg: 45, modulus: 0.5}}
contributors:
  - {name: c, source: d, path: PS}
outputs:
  - {name: x, signal: y, unit: m}
)";
  deb::test::WriteFile(dir / "b.yaml", budget);
  const deb::test::Command check = deb::test::RunDebIn(dir, "check b.yaml");
  REQUIRE(check.exit_code == 0);
  CHECK(check.out.find("required: phase margin 65.53 deg >= 45 deg: PASS; modulus margin 0.7862 >= 0.5: PASS") !=
        std::string::npos);
  // k = 4: the phase margin 90 - atan(w_c) deg falls below 45 (w_c = 1.87 rad/s: 28 deg).
  const deb::test::Command run =
      deb::test::RunDebIn(dir, "run b.yaml --set k=4 --no-plots --out a", "SOURCE_DATE_EPOCH=1");
  REQUIRE(run.exit_code == 0);
  CHECK(run.out.find("loop G closed by K: phase margin 28.") != std::string::npos);
  CHECK(run.out.find(" >= 45 deg: FAIL") != std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(deb::test::ReadAll(dir / "a" / "summary.json"));
  REQUIRE(j["loops"][0]["requirements"].size() == 2);
  CHECK(j["loops"][0]["requirements"][0]["margin"] == "phase margin");
  CHECK(j["loops"][0]["requirements"][0]["pass"] == false);
  // Redrawn from result.h5: the same summary.json.
  REQUIRE(deb::test::RunDebIn(dir, "report a --no-plots --out b", "SOURCE_DATE_EPOCH=1").exit_code == 0);
  CHECK(deb::test::ReadAll(dir / "a" / "summary.json") == deb::test::ReadAll(dir / "b" / "summary.json"));
  fs::remove_all(dir);
}

TEST_CASE("deb uncertainty --shard K/N and deb merge: the parts joined give the unsharded directory byte for byte") {
  const fs::path dir = deb::test::TempDir("uncertainty_shards");
  const std::string budget = deb::test::ExampleBudget("nizamoglu2015_tolerances.yaml");
  const std::string env = "SOURCE_DATE_EPOCH=1700000000";
  const std::string study = "uncertainty " + budget + " -n 90 --method sobol --seed 5 -q";
  REQUIRE(deb::test::RunDebIn(dir, study + " -j 2 --out serial", env).exit_code == 0);
  for (int k = 1; k <= 4; ++k) {
    // Shard 3 from a Slurm array job's variables (indices 0..3), the others from --shard.
    const deb::test::Command c =
        k == 3 ? deb::test::RunDebIn(dir, study + " -j 1 --out p3",
                                     env + " SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=4 SLURM_ARRAY_TASK_MIN=0")
               : deb::test::RunDebIn(dir, study + " -j 1 --shard " + std::to_string(k) + "/4 --out p" + std::to_string(k), env);
    REQUIRE(c.exit_code == 0);
    CHECK(fs::exists(dir / ("p" + std::to_string(k)) / "part.json"));
  }
  const deb::test::Command m = deb::test::RunDebIn(dir, "merge p4 p2 p1 p3 --out merged", env);
  REQUIRE(m.exit_code == 0);
  CHECK(m.out.find("uncertainty of nizamoglu2015_tolerances: 180 samples (sobol, seed 5)") != std::string::npos);
  std::size_t files = 0;
  CHECK(deb::test::FilesDiffering(dir / "serial", dir / "merged", &files).empty());
  CHECK(files > 20);  // the documents, the data and every figure

  // A missing, a duplicated and a foreign part; a directory that is no part.
  const auto merge_error = [&](const std::string& parts) {
    const deb::test::Command c = deb::test::RunDebIn(dir, "merge " + parts + " --out bad --no-plots", env);
    CHECK(c.exit_code == 3);
    CHECK_FALSE(fs::exists(dir / "bad"));
    return c.err;
  };
  CHECK(merge_error("p1 p2 p4").find("shard 3 of 4 is missing") != std::string::npos);
  CHECK(merge_error("p1 p2 p2 p3 p4").find("p2 and p2 are both shard 2/4") != std::string::npos);
  REQUIRE(deb::test::RunDebIn(dir, "uncertainty " + budget + " -n 90 --method sobol --seed 6 -q --shard 2/4 --out other", env)
              .exit_code == 0);
  CHECK(merge_error("p1 other p3 p4").find("other is a part of another study than p1") != std::string::npos);
  CHECK(merge_error("p1 serial p3 p4").find("serial: no part.json: not a part of a sharded study") != std::string::npos);
  // Edited parts: samples beyond the limit, a method deb does not know.
  const std::string part1 = deb::test::ReadAll(dir / "p1" / "part.json");
  for (const auto& [from, to, why] :
       {std::make_tuple("\"samples\":90", "\"samples\":9000000", "samples 9000000 outside 1 to 1000000"),
        std::make_tuple("\"method\":\"sobol\"", "\"method\":\"xx\"", "method: unknown sampling method 'xx'"),
        // a kind that is not text (found by fuzz_study_part: it escaped as a JSON type error)
        std::make_tuple("\"kind\":\"deb uncertainty part\"", "\"kind\":1", "not the part of a sharded study"),
        // a count as a float far out of range (undefined converted to an integer: fuzz_study_part's find)
        std::make_tuple("\"begin\":0", "\"begin\":3.3e99", "begin must be a whole number >= 0, not 3.3e+99"),
        std::make_tuple("\"seed\":5", "\"seed\":-5", "seed must be a whole number >= 0, not -5")}) {
    std::string text = part1;
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, std::string(from).size(), to);
    fs::create_directories(dir / "edited");
    deb::test::WriteFile(dir / "edited" / "part.json", text);
    CHECK(merge_error("edited p2 p3 p4").find(why) != std::string::npos);
  }
  // Bad shards are usage errors.
  for (const char* bad : {"0/4", "5/4", "a/b", "3"}) {
    CAPTURE(bad);
    const deb::test::Command c = deb::test::RunDebIn(dir, study + " --shard " + bad + " --out x");
    CHECK(c.exit_code == 2);
    CHECK(c.err.find("--shard") != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("deb merge refuses parts of a budget that changed since they were made") {
  const fs::path dir = deb::test::TempDir("uncertainty_stale");
  const std::string& budget = deb::test::kLinearLevelBudget;
  deb::test::WriteFile(dir / "b.yaml", budget);
  for (const char* k : {"1", "2"})
    REQUIRE(deb::test::RunDebIn(dir, std::string("uncertainty b.yaml -n 50 -q --shard ") + k + "/2 --out p" + k).exit_code == 0);
  REQUIRE(deb::test::RunDebIn(dir, "merge p1 p2 --no-plots -q --out ok").exit_code == 0);
  deb::test::WriteFile(dir / "b.yaml", budget + "# a comment is a change of the document\n");
  const deb::test::Command c = deb::test::RunDebIn(dir, "merge p1 p2 --no-plots --out stale");
  CHECK(c.exit_code == 3);
  CHECK(c.err.find("is not the budget the parts were made from") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "stale"));
  fs::remove_all(dir);
}
