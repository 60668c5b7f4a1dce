#include "deb/report/compare/study_document.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/report/budget/file_digest.h"

namespace deb::report {

TEST_CASE("a study's sources: each file with its SHA-256, a result directory's from its summary, and the date") {
  // The digests as the commands give them: a budget file's own
  // (FileSha256), a result directory's from its summary.json
  // (ResultFigures::budget_sha256), none for a directory without one.
  const std::string budget = "b.yaml", results = "reports_b", bare = "bare";
  const std::string digest(64, 'a');
  StudyDocument doc;
  doc.footer = "deb · compare";
  StampSources(&doc, {{"A", budget, Sha256("name: b\n")}, {"B", results, digest}, {"C", bare, ""}});
  const Table& t = doc.sources;
  REQUIRE(t.rows.size() == 7);  // a path and its digest per source, then the date
  CHECK(t.rows[0] == std::vector<std::string>{"A", budget});
  CHECK(t.rows[1][1] == "SHA-256 " + Sha256("name: b\n"));
  CHECK(t.rows[3][1] == "SHA-256 " + digest);
  CHECK(t.rows[5][1] == "SHA-256 –");  // a directory deb did not write: unknown
  CHECK(t.rows[6][0] == "date");
  CHECK(t.rows[6][1].size() == std::string("2026-12-07 06:09:02 UTC").size());
  // The footer names every known digest, as a run report's pages name theirs.
  CHECK(doc.footer == "deb · compare · SHA-256 A " + Sha256("name: b\n").substr(0, 12) + ", B " + digest.substr(0, 12));
  StudyDocument one;
  one.footer = "deb · sweep";
  StampSources(&one, {{"budget", budget, Sha256("name: b\n")}});
  CHECK(one.footer == "deb · sweep · SHA-256 " + Sha256("name: b\n").substr(0, 12));
  // Every format shows them.
  CHECK(StudyMarkdown(doc).find(Sha256("name: b\n")) != std::string::npos);
  CHECK(StudyHtml(doc).find(digest) != std::string::npos);
}

}  // namespace deb::report
