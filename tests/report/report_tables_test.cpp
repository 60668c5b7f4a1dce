#include "deb/report/report_tables.h"

#include <doctest/doctest.h>

#include "deb/io/budget_yaml.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

Table Small() {
  Table t;
  t.title = "t";
  t.header = {"name", "value", "note"};
  t.numeric = {false, true, false};
  t.rows = {{"a|b", "1.5", "x"}, {"µm", "12.25", "a very long note that goes on"}};
  t.emphasis = {{false, true, false}};
  return t;
}

}  // namespace

TEST_CASE("text tables align columns by characters, numbers to the right, and shorten long cells") {
  const std::vector<std::string> lines = ToText(Small(), 30, 24);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "name  value  note");
  CHECK(lines[2] == "a|b     1.5  x");
  CHECK(lines[3] == "µm    12.25  a very long…");  // the last column gets what is left of 24
}

TEST_CASE("Markdown and HTML tables escape their cells and mark emphasis") {
  const std::string md = ToMarkdown(Small());
  CHECK(md.find("| name | value | note |\n| --- | ---: | --- |\n") == 0);
  CHECK(md.find("a\\|b | **1.5** | x") != std::string::npos);
  const std::string html = ToHtml(Small());
  CHECK(html.find("<td class=\"num\"><strong>1.5</strong></td>") != std::string::npos);
  CHECK(HtmlEscape("<a & \"b\">") == "&lt;a &amp; &quot;b&quot;&gt;");
}

TEST_CASE("the band table lists contributors by share, emphasises the largest per band and ends with the total") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const Table t = BandTable(result.outputs[0]);
  CHECK(t.header.front() == "contributor");
  CHECK(t.header.back() == "whole grid");
  REQUIRE(t.rows.size() == 3);
  CHECK(t.rows[0][0] == "floor");
  CHECK(t.rows[2][0] == "total");
  // Floor dominates the 1-10 Hz band; sensor noise the 100-1000 Hz band (the VC spectrum stops near 89 Hz).
  CHECK(t.emphasis[0][2]);
  CHECK(t.emphasis[1][4]);
  CHECK_FALSE(t.emphasis[0][4]);
}

TEST_CASE("the summary table gives status and the largest contributor of every output") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const Table t = SummaryTable(result);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0][0] == "z_velocity");
  CHECK(t.rows[0][1] == "µm/s");
  CHECK(t.rows[0][3] == "20");
  CHECK(t.rows[0][5] == "pass");
  CHECK(t.rows[0][6].rfind("floor (", 0) == 0);
  const ReportFacts f = MakeFacts(budget, result, "b.yaml", "abc", "today", 0.5);
  CHECK(f.items[0] == std::make_pair(std::string("budget"), std::string("single_axis_isolator")));
  CHECK(f.items.back().second == "all 2 met");
}

}  // namespace deb::report
