#include "deb/report/compare/study_document.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "deb/report/budget/file_digest.h"
#include "tests/support/cli_harness.h"

namespace deb::report {

TEST_CASE("a study's sources: each file with its SHA-256, a result directory's from its summary, and the date") {
  namespace fs = std::filesystem;
  const fs::path dir = test::TempDir("study_sources");
  const fs::path budget = dir / "b.yaml";
  std::ofstream(budget) << "name: b\n";
  const fs::path results = dir / "reports_b";
  fs::create_directories(results);
  const std::string digest(64, 'a');
  std::ofstream(results / "summary.json") << "{\"budget\": \"b\", \"budget_sha256\": \"" << digest << "\"}\n";
  const fs::path bare = dir / "bare";
  fs::create_directories(bare);

  StudyDocument doc;
  doc.footer = "deb · compare";
  StampSources(&doc, {{"A", budget.string()}, {"B", results.string()}, {"C", bare.string()}});
  const Table& t = doc.sources;
  REQUIRE(t.rows.size() == 7);  // a path and its digest per source, then the date
  CHECK(t.rows[0] == std::vector<std::string>{"A", budget.string()});
  CHECK(t.rows[1][1] == "SHA-256 " + Sha256("name: b\n"));
  CHECK(t.rows[3][1] == "SHA-256 " + digest);
  CHECK(t.rows[5][1] == "SHA-256 –");  // a directory deb did not write: unknown
  CHECK(t.rows[6][0] == "date");
  CHECK(t.rows[6][1].size() == std::string("2026-12-07 06:09:02 UTC").size());
  // The footer names every known digest, as a run report's pages name theirs.
  CHECK(doc.footer == "deb · compare · SHA-256 A " + Sha256("name: b\n").substr(0, 12) + ", B " + digest.substr(0, 12));
  StudyDocument one;
  one.footer = "deb · sweep";
  StampSources(&one, {{"budget", budget.string()}});
  CHECK(one.footer == "deb · sweep · SHA-256 " + Sha256("name: b\n").substr(0, 12));
  // Every format shows them.
  CHECK(StudyMarkdown(doc).find(Sha256("name: b\n")) != std::string::npos);
  CHECK(StudyHtml(doc).find(digest) != std::string::npos);
}

}  // namespace deb::report
