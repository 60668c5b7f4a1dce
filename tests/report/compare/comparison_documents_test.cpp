#include "deb/report/compare/comparison_documents.h"

#include <doctest/doctest.h>

#include <string>

namespace deb::report {
namespace {

// Output z in nm: total 2 -> 3, contributor floor 0 -> 1 (no ratio).
Comparison Example() {
  Comparison c;
  c.label_a = "old<1>";
  c.label_b = "new";
  ComparedFigure total{"z", "nm", "total", "", 2.0, 3.0, 1.0, 1.5, 1.25};
  ComparedFigure floor{"z", "nm", "floor", "", 0.0, 1.0, 1.0, std::nullopt, 0.25, true, false};
  c.figures = {total, floor};
  c.unmatched = {"output y only in B"};
  return c;
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_CASE("the headline comes first: per output A, B, B / A, the verdict and the largest changes") {
  const std::vector<Table> all = ComparisonTables(Example());
  REQUIRE(all.size() == 3);
  const Table& h = all.front();
  CHECK(h.title.find("Headline") == 0);
  REQUIRE(h.rows.size() == 1);
  CHECK(h.rows[0] == std::vector<std::string>{"z [nm]", Sig(2.0, 4), Sig(3.0, 4), Sig(1.5, 4), "worse",
                                              "floor +25 %"});
  // A change below 0.01 % in size reads as such, not in e-notation.
  Comparison tiny = Example();
  tiny.figures[1].variance_change_of_total = -4.6e-6;
  CHECK(ComparisonTables(tiny).front().rows[0].back() == "floor < 0.01 %");
  ComparedFigure better{"z", "nm", "total", "", 3.0, 2.0, -1.0, 2.0 / 3.0, -0.2};
  CHECK(Verdict(better) == "better");
  better.ratio = 1.0001;
  CHECK(Verdict(better) == "unchanged");
}

TEST_CASE("a negligible term reads from about zero, to about zero, or a dash for 0 / 0") {
  ComparedFigure f{"z", "nm", "floor", "", 1e-13, 1.0, 1.0, std::nullopt, 0.25, true, false};
  CHECK(RatioText(f) == "from ≈0");
  f.negligible_a = false;
  f.negligible_b = true;
  CHECK(RatioText(f) == "to ≈0");
  f.negligible_a = true;
  CHECK(RatioText(f) == "–");
}

TEST_CASE("the comparison tables have one per output with the total emphasised, then the largest changes") {
  std::vector<Table> tables = ComparisonTables(Example());
  tables.erase(tables.begin());  // the headline
  REQUIRE(tables.size() == 2);
  CHECK(tables[0].title == "z [nm]");
  CHECK(tables[0].header[2] == "A: old<1>");
  REQUIRE(tables[0].rows.size() == 2);
  CHECK(tables[0].rows[0] ==
        std::vector<std::string>{"total", "whole grid", Sig(2.0, 4), Sig(3.0, 4), Sig(1.0, 4), Sig(1.5, 4)});
  CHECK(tables[0].rows[1][5] == "from ≈0");
  CHECK(tables[0].emphasis[0][0]);
  CHECK_FALSE(tables[0].emphasis[1][0]);
  // A band prints as the run report prints bands, not as its data key.
  Comparison banded = Example();
  ComparedFigure band = banded.figures[0];
  band.band = "100-1e+08 Hz";
  band.band_lo_hz = 100.0;
  band.band_hi_hz = 1e8;
  banded.figures.push_back(band);
  CHECK(ComparisonTables(banded)[1].rows.back()[1] == "100–10⁸ Hz");
  CHECK(tables[1].title == "Contributors that changed most");
  REQUIRE(tables[1].rows.size() == 1);
  CHECK(tables[1].rows[0].back() == Sig(25.0, 3) + " %");
  // A change too small to matter reads as such, not "4.57·10⁻⁴ %" (compare.pdf).
  Comparison tiny = Example();
  tiny.figures[1].variance_change_of_total = 4.57e-6;
  const std::vector<Table> small = ComparisonTables(tiny);
  REQUIRE(small[2].rows.size() == 1);
  CHECK(small[2].rows[0].back() == "< 0.01 %");
}

TEST_CASE("the Markdown and HTML documents carry the title, tables, plots and what was not compared") {
  Plot p;
  p.name = "z_overlay";
  p.caption = "z: A and B";
  const std::vector<Plot> plots = {p};
  const StudyDocument doc = ComparisonDocument(Example(), plots);
  const std::string md = StudyMarkdown(doc);
  CHECK(md.find("# Comparison: old<1> (A) vs new (B)\n\n") == 0);
  CHECK(md.find("## z [nm]") != std::string::npos);
  CHECK(md.find("![z: A and B](plots/z_overlay.png)") != std::string::npos);
  CHECK(md.find("## Not compared\n\n- output y only in B\n") != std::string::npos);
  const std::string html = StudyHtml(doc);
  CHECK(html.find("<!DOCTYPE html>") == 0);
  CHECK(html.find("<title>Comparison: old&lt;1&gt; (A) vs new (B)</title>") != std::string::npos);
  CHECK(Count(html, "old<1>") == 0);  // user text is escaped
  CHECK(html.find("<img src=\"plots/z_overlay.png\" alt=\"z: A and B\">") != std::string::npos);
  CHECK(html.find("<li>output y only in B</li>") != std::string::npos);
  CHECK(html.find("</body>\n</html>\n") != std::string::npos);
}

}  // namespace
}  // namespace deb::report
