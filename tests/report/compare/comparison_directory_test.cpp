#include "deb/report/compare/comparison_directory.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "deb/core/error.h"
#include "deb/core/file_name.h"
#include "deb/io/comparison_files.h"
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

TEST_CASE("a budget is evaluated: its figures carry the budget's name, and its result is kept for the plots") {
  const ComparisonInput in = LoadComparisonInput(test::ExampleBudget(), {}, 1, true);
  CHECK(in.figures.label == "single_axis_isolator");
  REQUIRE(in.result);
  CHECK_FALSE(in.result->outputs.empty());
}

TEST_CASE("a directory without summary.json is refused") {
  const fs::path dir = TempDir("empty");
  CHECK_THROWS_WITH_AS(LoadComparisonInput(dir.string(), {}, 1, true), doctest::Contains("must hold summary.json"),
                       InputError);
}

TEST_CASE("the comparison directory holds compare.json, .csv, .md, .html and .pdf; its default name is made safe") {
  const ComparisonInput a = LoadComparisonInput(test::ExampleBudget(), {}, 1, false);
  const Comparison cmp = Compare(a.figures, a.figures);
  const fs::path dir = TempDir("written") / "cmp";
  WriteComparisonDirectory(cmp, {}, dir.string(), {}, 1);
  CHECK(ReadAll(dir / "compare.json") == ComparisonJson(cmp));
  CHECK(ReadAll(dir / "compare.csv") == ComparisonCsv(cmp));
  CHECK(ReadAll(dir / "compare.md") == ComparisonMarkdown(cmp, {}));
  CHECK(ReadAll(dir / "compare.html") == ComparisonHtml(cmp, {}));
  CHECK(fs::is_regular_file(dir / "compare.pdf"));
  CHECK(DefaultComparisonDirectory("a b", "c/d") ==
        "reports/compare_" + FileNameWord("a b") + "_vs_" + FileNameWord("c/d"));
}

}  // namespace deb::report
