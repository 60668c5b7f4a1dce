// deb run --export mat --export xlsx (or --export mat,xlsx): result.mat and
// result.xlsx in the report directory, listed by index.html and report.md,
// their figures those of summary.json (the .mat's exactly; it stores the
// doubles); an unknown format is a usage error listing the allowed ones.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "deb/formats/mat_file.h"
#include "tests/support/cli_harness.h"
#include "tests/support/contains.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {
const std::string kBudget = ExampleBudget("single_axis_isolator.yaml");
}  // namespace

TEST_CASE("run --export mat --export xlsx writes result.mat and result.xlsx beside summary.json") {
  const fs::path dir = TempDir("export");
  const fs::path out = dir / "r";
  const Command c = RunDeb("run \"" + kBudget + "\" -q --no-plots --export mat --export xlsx --out \"" + out.string() + "\"");
  REQUIRE_MESSAGE(c.exit_code == 0, c.err);
  REQUIRE(fs::is_regular_file(out / "result.mat"));
  REQUIRE(fs::is_regular_file(out / "result.xlsx"));
  CHECK(Contains(ReadAll(out / "index.html"), "href=\"result.mat\""));
  CHECK(Contains(ReadAll(out / "index.html"), "href=\"result.xlsx\""));
  CHECK(Contains(ReadAll(out / "report.md"), "(result.xlsx)"));

  const nlohmann::json summary = nlohmann::json::parse(ReadAll(out / "summary.json"));
  deb::formats::MatFile mat((out / "result.mat").string());
  const std::vector<std::string> fields = mat.Names("output_fields");
  REQUIRE(fields.size() == summary["outputs"].size());
  for (std::size_t o = 0; o < fields.size(); ++o) {
    const nlohmann::json& js = summary["outputs"][o];
    const std::string s = "outputs." + fields[o] + ".";
    CHECK(mat.Names(s + "name").front() == js["name"].get<std::string>());
    CHECK(mat.Vector(s + "rms").front() == js["rms"].get<double>());
    CHECK(mat.Vector(s + "variance").front() == js["variance"].get<double>());
    const std::vector<std::string> names = mat.Names(s + "contributors");
    const std::vector<double> variance = mat.Vector(s + "contributor_variance");
    REQUIRE(names.size() == js["contributors"].size());
    for (std::size_t k = 0; k < names.size(); ++k) {
      CHECK(names[k] == js["contributors"][k]["name"].get<std::string>());
      CHECK(variance[k] == js["contributors"][k]["variance"].get<double>());
    }
  }
  CHECK(mat.Vector("f_hz").size() == summary["grid"]["points"].get<std::size_t>());

  const Command sheets = Shell("unzip -p '" + (out / "result.xlsx").string() + "' xl/workbook.xml");
  REQUIRE(sheets.exit_code == 0);
  CHECK(Contains(sheets.out, "<sheet name=\"Summary\""));
}

TEST_CASE("run --export mat,xlsx is the same as two options; an unknown format lists the allowed ones") {
  const fs::path dir = TempDir("export_list");
  REQUIRE(RunDeb("run \"" + kBudget + "\" -q --no-plots --export mat,xlsx --out \"" + (dir / "r").string() + "\"")
              .exit_code == 0);
  CHECK(fs::is_regular_file(dir / "r" / "result.mat"));
  CHECK(fs::is_regular_file(dir / "r" / "result.xlsx"));
  const Command bad = RunDeb("run \"" + kBudget + "\" -q --no-plots --export pdf --out \"" + (dir / "s").string() + "\"");
  CHECK(bad.exit_code == 2);
  CHECK(Contains(bad.err, "unknown export format 'pdf'; allowed: csv, mat, xlsx"));
  CHECK_FALSE(fs::exists(dir / "s"));
  // Without --export: neither file.
  REQUIRE(RunDeb("run \"" + kBudget + "\" -q --no-plots --out \"" + (dir / "t").string() + "\"").exit_code == 0);
  CHECK_FALSE(fs::exists(dir / "t" / "result.mat"));
  CHECK_FALSE(fs::exists(dir / "t" / "result.xlsx"));
}
