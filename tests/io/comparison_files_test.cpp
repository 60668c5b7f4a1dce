#include "deb/io/comparison_files.h"

#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "deb/core/error.h"
#include "deb/io/budget_yaml.h"
#include "deb/io/result_writer.h"

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
  std::ofstream(file) << SummaryJson(budget, result, {"b.yaml", 0.0});
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

TEST_CASE("a JSON file that is not a summary names the missing key") {
  const fs::path file = Temp("other.json");
  std::ofstream(file) << R"({"outputs": [{"name": "z", "unit": "nm"}]})";
  CHECK_THROWS_WITH_AS(ReadSummaryFigures(file.string(), "x"), doctest::Contains("outputs[0].variance: missing"),
                       InputError);
  fs::remove(file);
}

}  // namespace deb
