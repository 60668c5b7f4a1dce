#include "deb/results/comparison_files.h"

#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/result_writer.h"

namespace deb {
namespace {

namespace fs = std::filesystem;

fs::path Temp(const std::string& name) {
  return fs::temp_directory_path() / ("deb_comparison_files_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace

TEST_CASE("figures read back from summary.json equal those of the evaluation, and compare to ratio 1") {
  const Budget budget = LoadBudgetFile(std::string(DEB_SOURCE_DIR) + "/budgets/single_axis_isolator.yaml");
  const BudgetResult result = Evaluate(budget);
  const fs::path file = Temp("summary.json");
  std::ofstream(file) << SummaryJson(result, {"b.yaml", 0.0});
  const ResultFigures read = ReadSummaryFigures(file.string(), "dir");
  const ResultFigures direct = FiguresOf("eval", result);
  REQUIRE(read.outputs.size() == direct.outputs.size());
  for (std::size_t o = 0; o < read.outputs.size(); ++o) {
    CHECK(read.outputs[o].variance == direct.outputs[o].variance);  // JSON keeps every digit
    REQUIRE(read.outputs[o].bands.size() == direct.outputs[o].bands.size());
  }
  const Comparison cmp = Compare(direct, read);
  for (const ComparedFigure& f : cmp.figures) CHECK(*f.ratio == 1.0);
  const auto j = nlohmann::json::parse(ComparisonJson(cmp));
  CHECK(j["a"] == "eval");
  CHECK(j["figures"].size() == cmp.figures.size());
  const std::string csv = ComparisonCsv(cmp);
  CHECK(csv.rfind("output,unit,contributor,band,rms_a,rms_b,difference,ratio,", 0) == 0);
  fs::remove(file);
}

TEST_CASE("a summary's budget digest is read where it is one: 64 hex digits, else unknown") {
  const BudgetResult result = Evaluate(LoadBudgetFile(std::string(DEB_SOURCE_DIR) + "/budgets/single_axis_isolator.yaml"));
  const fs::path file = Temp("digest.json");
  RunInfo info("b.yaml");
  info.budget_sha256 = std::string(63, 'a') + "F";
  std::ofstream(file) << SummaryJson(result, info);
  CHECK(ReadSummaryFigures(file.string(), "dir").budget_sha256 == info.budget_sha256);
  // A summary deb did not write may hold anything there: a study document prints it.
  for (const std::string& bad : {std::string(63, 'a'), std::string(63, 'a') + "g", std::string("")}) {
    info.budget_sha256 = bad;
    std::ofstream(file) << SummaryJson(result, info);
    CHECK(ReadSummaryFigures(file.string(), "dir").budget_sha256.empty());
  }
  fs::remove(file);
}

TEST_CASE("a JSON file that is not a summary names the missing key") {
  const fs::path file = Temp("other.json");
  std::ofstream(file) << R"({"outputs": [{"name": "z", "unit": "nm"}]})";
  CHECK_THROWS_WITH_AS(ReadSummaryFigures(file.string(), "x"), doctest::Contains("outputs[0].variance: missing"),
                       InputError);
  fs::remove(file);
}

TEST_CASE("a summary with a negative variance, a band that is not one or a requirement <= 0 is refused, located") {
  const fs::path file = Temp("bad.json");
  const auto error_of = [&](const std::string& text) {
    std::ofstream(file) << text;
    try {
      ReadSummaryFigures(file.string(), "x");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string ok_output = R"("name": "z", "unit": "nm", "variance": 4, "contributors": [{"name": "c", "variance": 4}])";
  CHECK(error_of(R"({"outputs": [{"name": "z", "unit": "nm", "variance": -1, "contributors": []}]})")
            .find("outputs[0].variance: -1 is not a variance") != std::string::npos);
  CHECK(error_of(R"({"outputs": [{"name": "z", "unit": "nm", "variance": 1, "contributors": [{"name": "c", "variance": -1}]}]})")
            .find("outputs[0].contributors[0].variance: -1 is not a variance") != std::string::npos);
  CHECK(error_of("{\"outputs\": [{" + ok_output + R"(, "bands": [{"lo_hz": 10, "hi_hz": 1, "variance": 1, "contributors": []}]}]})")
            .find("outputs[0].bands[0]: [10, 1] Hz is not a band") != std::string::npos);
  CHECK(error_of("{\"outputs\": [{" + ok_output + R"(, "bands": [{"lo_hz": 1, "hi_hz": 10, "variance": -5, "contributors": []}]}]})")
            .find("outputs[0].bands[0].variance: -5 is not a variance") != std::string::npos);
  CHECK(error_of("{\"outputs\": [{" + ok_output + R"(, "requirement": {"rms_max": 0}}]})")
            .find("outputs[0].requirement.rms_max: 0 is not a requirement") != std::string::npos);
  CHECK(error_of("{\"outputs\": [{" + ok_output + "}]}") == "(no error)");
  fs::remove(file);
}

}  // namespace deb
