// The deb command line as a user meets it: exit codes, messages, and the
// report directory (complete, or not there at all).
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

TEST_CASE("deb run writes summary.json with the documented shape, and with --export csv one CSV per output") {
  const fs::path dir = TempDir("run");
  const Command r =
      RunDeb("run " + ExampleBudget("single_axis_isolator.yaml") + " --export csv --out " + (dir / "rep").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const auto j = nlohmann::json::parse(ReadAll(dir / "rep" / "summary.json"));
  CHECK(j["budget"] == "single_axis_isolator");
  CHECK(j["conventions"].is_object());
  CHECK(j["grid"]["points"].get<int>() > 100);
  CHECK(j["grid"]["min_hz"] == 0.1);
  REQUIRE(j["outputs"].size() == 2);
  for (const auto& o : j["outputs"]) {
    CHECK(o["unit"].is_string());
    CHECK(o["rms"].get<double>() == doctest::Approx(std::sqrt(o["variance"].get<double>())).epsilon(1e-12));
    CHECK(o["requirement"]["rms_max"].is_number());
    CHECK(o["requirement"]["pass"].is_boolean());
    double share = 0.0;
    for (const auto& c : o["contributors"]) {
      share += c["share"].get<double>();
      CHECK(c.contains("exact_rms"));
    }
    CHECK(share == doctest::Approx(1.0).epsilon(1e-12));
    REQUIRE(o["bands"].size() == 4);
    CHECK(o["bands"][0]["lo_hz"] == 0.1);
    CHECK(o["bands"][0]["contributors"].size() == 2);
    CHECK(fs::exists(dir / "rep" / (o["name"].get<std::string>() + ".csv")));
  }
  // Sensor noise on the velocity output is white through a strictly proper path: exact RMS present.
  CHECK(j["outputs"][0]["contributors"][1]["exact_rms"].is_number());
  CHECK(r.out.find("output z_velocity [um/s]") != std::string::npos);
  // Nothing else was left beside the report.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.exists();
  CHECK(entries == 1);
  fs::remove_all(dir);
}

TEST_CASE("the CSV has a header row and one row per grid frequency") {
  const fs::path dir = TempDir("csv");
  REQUIRE(RunDeb("run -q " + ExampleBudget("single_axis_isolator.yaml") + " --export csv --out " + (dir / "rep").string())
              .exit_code == 0);
  const auto j = nlohmann::json::parse(ReadAll(dir / "rep" / "summary.json"));
  std::ifstream in(dir / "rep" / "z_velocity.csv");
  std::string line;
  int comments = 0, rows = 0;
  std::string header;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) ++comments;
    else if (header.empty()) header = line;
    else ++rows;
  }
  CHECK(comments >= 1);
  CHECK(header == "frequency_hz,psd_floor,psd_sensor_noise,psd_total,cps_floor,cps_sensor_noise,cps_total,reverse_cps_total");
  CHECK(rows == j["grid"]["points"].get<int>());
  fs::remove_all(dir);
}

TEST_CASE("a bad budget exits 3 with file:line:col and leaves no report behind") {
  const fs::path dir = TempDir("bad");
  std::string text = ReadAll(ExampleBudget("single_axis_isolator.yaml"));
  text.replace(text.find("level: 0.01"), 11, "level: -0.01");
  const fs::path bad = WriteFile(dir / "bad.yaml", text);
  const Command r = RunDeb("run " + bad.string() + " --out " + (dir / "rep").string());
  CHECK(r.exit_code == 3);
  CHECK(r.err.find(bad.string() + ":") != std::string::npos);
  CHECK(r.err.find("sources[1].spectrum.level: value -0.01 must be >= 0") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "rep"));
  fs::remove_all(dir);
}

TEST_CASE("a failing run keeps the previous report intact") {
  const fs::path dir = TempDir("keep");
  REQUIRE(RunDeb("run -q " + ExampleBudget("single_axis_isolator.yaml") + " --export csv --out " + (dir / "rep").string())
              .exit_code == 0);
  const std::string before = ReadAll(dir / "rep" / "summary.json");
  // Unstable path: caught during evaluation, after loading succeeded.
  std::string text = ReadAll(ExampleBudget("single_axis_isolator.yaml"));
  text.replace(text.find("den: [1, 13.82301, 157.9137]"), 28, "den: [1, -13.82301, 157.9137]");
  const fs::path bad = WriteFile(dir / "unstable.yaml", text);
  const Command r = RunDeb("run " + bad.string() + " --out " + (dir / "rep").string());
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("is unstable") != std::string::npos);
  // Found during evaluation, located all the same: the contributor whose path it is.
  CHECK(r.err.find(bad.string() + ":") != std::string::npos);
  CHECK(r.err.find(": contributors[0].path: path '") != std::string::npos);
  CHECK(ReadAll(dir / "rep" / "summary.json") == before);
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.exists();
  CHECK(entries == 2);  // rep/ and unstable.yaml
  fs::remove_all(dir);
}

TEST_CASE("usage errors exit 2 and --help exits 0") {
  CHECK(RunDeb("").exit_code == 2);
  CHECK(RunDeb("run").exit_code == 2);
  CHECK(RunDeb("run /nonexistent/budget.yaml").exit_code == 2);
  const Command help = RunDeb("run --help");
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("--out") != std::string::npos);
  CHECK(RunDeb("--help").out.find("Exit codes") != std::string::npos);
}

TEST_CASE("--version names the BLAS kernels, which are AVX2 or later wherever the processor runs AVX2") {
  // deb starts itself again with OPENBLAS_CORETYPE where OpenBLAS picked
  // older kernels (deb::BetterBlasKernel): the started deb reports them.
  const Command v = RunDeb("--version");
  CHECK(v.exit_code == 0);
  CHECK(v.out.rfind("deb ", 0) == 0);
  const std::size_t at = v.out.find("BLAS: OpenBLAS, ");
  if (at == std::string::npos) return;  // another BLAS: nothing to choose
  const std::string kernel = v.out.substr(at + 16, v.out.find(" kernels", at) - at - 16);
  MESSAGE("deb --version: " << kernel << " kernels");
#if defined(__x86_64__)
  __builtin_cpu_init();
  if (std::getenv("OPENBLAS_CORETYPE") == nullptr && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    CHECK((kernel == "Haswell" || kernel == "Zen" || kernel == "SkylakeX" || kernel == "Cooperlake" ||
           kernel == "SapphireRapids"));
#endif
}

TEST_CASE("an unknown command exits 2, names the commands and offers the nearest") {
  const Command typo = RunDeb("runn budget.yaml");
  CHECK(typo.exit_code == 2);
  CHECK(typo.err.find("deb: unknown command 'runn' (did you mean 'run'?); the commands are run, check,") == 0);
  const Command far = RunDeb("plot budget.yaml");
  CHECK(far.exit_code == 2);
  CHECK(far.err.find("unknown command 'plot'; the commands are") != std::string::npos);
  CHECK(far.err.find("did you mean") == std::string::npos);
}

TEST_CASE("deb check validates and describes without writing anything") {
  const Command r = RunDeb("check " + ExampleBudget("single_axis_isolator.yaml"));
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("budget single_axis_isolator: valid") != std::string::npos);
  CHECK(r.out.find("transmissibility") != std::string::npos);
  CHECK(r.out.find("covariance") == std::string::npos);  // none asked for
}

TEST_CASE("deb check lists the outputs of a covariance request") {
  const Command r = RunDeb("check " + ExampleBudget("nizamoglu2015_h210.yaml"));
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("\ncovariance of 4 outputs: x_velocity, beta_velocity, y_velocity, alpha_velocity (") !=
        std::string::npos);
}

TEST_CASE("deb check and summary.json state the margins of every feedback loop") {
  // budgets/measured_stage.yaml: PM 53.01 deg at 30.06 Hz (tests/load/frf_path_test.cpp checks the figures).
  const Command r = RunDeb("check " + ExampleBudget("measured_stage.yaml"));
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("feedback loops:\n  stage closed by controller (negative feedback), in closed_loop\n"
                   "    phase margin 53.0") != std::string::npos);
  const fs::path dir = TempDir("loops_summary");
  const Command run = RunDeb("run " + ExampleBudget("measured_stage.yaml") + " --no-plots --out " + (dir / "r").string());
  REQUIRE(run.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(ReadAll(dir / "r" / "summary.json"));
  REQUIRE(j["loops"].size() == 1);
  CHECK(j["loops"][0]["plant"] == "stage");
  CHECK(std::abs(j["loops"][0]["phase_margin"]["deg"].get<double>() - 53.01) < 0.05);
  CHECK(j["loops"][0]["gain_margin"]["factor"].get<double>() == doctest::Approx(24.33).epsilon(5e-3));
  CHECK(j["loops"][0]["lower_gain_margin"].is_null());
  // A budget without feedback paths has no "loops" key.
  const Command plain = RunDeb("run " + ExampleBudget("single_axis_isolator.yaml") + " --no-plots --out " +
                               (dir / "p").string());
  REQUIRE(plain.exit_code == 0);
  CHECK_FALSE(nlohmann::json::parse(ReadAll(dir / "p" / "summary.json")).contains("loops"));
}

TEST_CASE("deb check validates a sweep section and every variant it makes") {
  const Command ok = RunDeb("check " + ExampleBudget("nizamoglu2015_sweep.yaml"));
  CHECK(ok.exit_code == 0);
  CHECK(ok.out.find("sweep: grid of 2 parameter(s), 32 variants, each valid") != std::string::npos);
  CHECK(ok.out.find("paths[0].control.gains") != std::string::npos);

  const fs::path dir = TempDir("check_sweep");
  std::string text = ReadAll(ExampleBudget("nizamoglu2015_sweep.yaml"));
  const std::string good = "path: \"paths[0].control.gains\"";
  REQUIRE(text.find(good) != std::string::npos);
  const fs::path bad = WriteFile(dir / "bad_sweep.yaml",
                                 text.replace(text.find(good), good.size(), "path: \"paths[0].control.gainz\""));
  const Command r = RunDeb("check " + bad.string());
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("sweep.parameters[0].path: key path 'paths[0].control.gainz' does not reach a number") !=
        std::string::npos);
  CHECK(r.out.empty());
  fs::remove_all(dir);
}
