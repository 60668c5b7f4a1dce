#include "deb/report/compare/comparison_directory.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/file_name.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/comparison_files.h"
#include "deb/results/result_writer.h"
#include "deb/report/compare/comparison_documents.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;
using test::ReadAll;
using test::TempDir;

}  // namespace

TEST_CASE("a comparison input is a budget file unless it is a directory or a summary.json") {
  const fs::path dir = TempDir("kinds");
  CHECK(IsComparisonBudgetFile(test::ExampleBudget()));
  CHECK_FALSE(IsComparisonBudgetFile(dir.string()));
  CHECK_FALSE(IsComparisonBudgetFile((dir / "summary.json").string()));
}

TEST_CASE("a result directory is read as its summary's figures, labelled with the directory's name") {
  const BudgetResult result = Evaluate(LoadBudgetFile(test::ExampleBudget()));
  const fs::path dir = TempDir("read") / "run_a";
  fs::create_directories(dir);
  WriteResultFiles(result, {}, dir.string());
  const ComparisonInput in = ReadComparisonResult(dir.string(), true);
  CHECK(in.figures.label == "run_a");
  CHECK_FALSE(in.result);  // no result store in it
  const ComparisonInput json = ReadComparisonResult((dir / "summary.json").string(), false);
  CHECK(json.figures.label == "run_a");
  const Comparison same = Compare(in.figures, FiguresOf("x", result));
  REQUIRE_FALSE(same.figures.empty());
  CHECK(same.Moved(1e-9).empty());
}

TEST_CASE("a directory without summary.json is refused") {
  const fs::path dir = TempDir("empty");
  CHECK_THROWS_WITH_AS(ReadComparisonResult(dir.string(), true), doctest::Contains("must hold summary.json"),
                       InputError);
}

TEST_CASE("the comparison directory holds compare.json, .csv, .md, .html and .pdf; its default name is made safe") {
  const ResultFigures a = FiguresOf("a", Evaluate(LoadBudgetFile(test::ExampleBudget())));
  const Comparison cmp = Compare(a, a);
  const fs::path dir = TempDir("written") / "cmp";
  WriteComparisonDirectory(cmp, {}, dir.string(), {}, 1);
  CHECK(ReadAll(dir / "compare.json") == ComparisonJson(cmp));
  CHECK(ReadAll(dir / "compare.csv") == ComparisonCsv(cmp));
  CHECK(ReadAll(dir / "compare.md") == StudyMarkdown(ComparisonDocument(cmp, {})));
  CHECK(ReadAll(dir / "compare.html") == StudyHtml(ComparisonDocument(cmp, {})));
  CHECK(fs::is_regular_file(dir / "compare.pdf"));
  CHECK(DefaultComparisonDirectory("a b", "c/d") ==
        "reports/compare_" + FileNameWord("a b") + "_vs_" + FileNameWord("c/d"));
}

}  // namespace deb::report
