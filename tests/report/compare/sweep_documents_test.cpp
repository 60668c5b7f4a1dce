#include "deb/report/compare/sweep_documents.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

namespace deb::report {
namespace {

// One output x in nm with requirement 10: RMS per variant.
BudgetResult Variant(double rms) {
  BudgetResult r;
  OutputResult x;
  x.name = "x";
  x.unit = "nm";
  x.variance = rms * rms;
  x.rms_max = 10.0;
  r.outputs = {x};
  return r;
}

SweepSpec Spec() {
  SweepSpec spec;
  SweepParameter h{"paths[0].h", {0, -100, -200}, {}, {}, {}, {}};
  h.label = "height <h>";
  h.unit = "mm";
  spec.parameters = {h};
  return spec;
}

}  // namespace

TEST_CASE("the sweep tables lead with each output's best variant, then every variant best first with PASS/FAIL") {
  const std::vector<BudgetResult> results = {Variant(12.0), Variant(4.0), Variant(8.0)};
  const std::vector<Table> tables = SweepTables(Spec(), results);
  REQUIRE(tables.size() == 2);
  REQUIRE(tables[0].rows.size() == 1);
  CHECK(tables[0].rows[0][1] == "height <h> = -100 mm");
  CHECK(tables[0].rows[0][2] == Sig(4.0, 4) + " PASS");
  CHECK(tables[0].rows[0][4] == "2 of 3");
  const Table& all = tables[1];
  CHECK(all.header[1] == "height <h> [mm]");
  REQUIRE(all.rows.size() == 3);
  CHECK(all.rows[0] == std::vector<std::string>{"1", "-100", Sig(4.0, 4) + " PASS"});
  CHECK(all.rows[1] == std::vector<std::string>{"2", "-200", Sig(8.0, 4) + " PASS"});
  CHECK(all.rows[2] == std::vector<std::string>{"3", "0", Sig(12.0, 4) + " FAIL"});
  CHECK(all.emphasis[0].back());  // the best of x
  CHECK_FALSE(all.emphasis[1].back());
}

TEST_CASE("a variant the model leaves unexcited, computed as rounding, reads ≈ 0 with a note, not as the best number") {
  // nizamoglu2015_sweep: beta_velocity at K_v = 0, h = 0 computes as 4.2e-11
  // µrad/s against up to 82 µrad/s elsewhere.
  const std::vector<BudgetResult> results = {Variant(82.0), Variant(4.2e-11), Variant(8.0)};
  CHECK(LargestVariance(results, 0) == 82.0 * 82.0);
  const std::vector<Table> tables = SweepTables(Spec(), results);
  REQUIRE(tables.size() == 2);
  CHECK(tables[0].rows[0][2] == "≈ 0 PASS");
  REQUIRE(tables[0].notes.size() == 1);
  CHECK(tables[0].notes[0].find("≈ 0: at most 1e-12 of the output's largest RMS") == 0);
  CHECK(tables[1].rows[0][2] == "≈ 0 PASS");
  CHECK(tables[1].notes.size() == 1);
  // 1e-9 of the largest is data.
  bool rounding = false;
  CHECK(VariantCell(Variant(82e-9).outputs[0], 82.0 * 82.0, &rounding) == Sig(82e-9, 4) + " PASS");
  CHECK_FALSE(rounding);
  CHECK(VariantCell(Variant(82e-13).outputs[0], 82.0 * 82.0, &rounding) == "≈ 0 PASS");
  CHECK(rounding);
}

TEST_CASE("sweep.md, sweep.html and sweep.pdf carry the tables and plots, user text escaped in HTML") {
  const std::vector<BudgetResult> results = {Variant(12.0), Variant(4.0), Variant(8.0)};
  Plot p;
  p.name = "x_sweep";
  p.caption = "x against h";
  const std::vector<Plot> plots = {p};
  const StudyDocument doc = SweepDocument("s", Spec(), results, plots);
  const std::string md = StudyMarkdown(doc);
  CHECK(md.find("# Sweep: s\n") == 0);
  CHECK(md.find("## Best variant per output") < md.find("## Variants, best first"));
  CHECK(md.find("![x against h](plots/x_sweep.png)") != std::string::npos);
  const std::string html = StudyHtml(doc);
  CHECK(html.find("height &lt;h&gt; [mm]") != std::string::npos);
  CHECK(html.find("height <h>") == std::string::npos);
  // The PDF says the same in the same order: the title, the two tables, the figure on a new page.
  const PdfDocumentSpec pdf = StudyPdfSpec(doc, "figures", "2026-01-01T00:00:00Z");
  std::vector<std::string> titles;
  bool page_break = false;
  for (const PdfBlock& b : pdf.blocks) {
    if (b.kind == PdfBlockKind::kTable) titles.push_back(b.text);
    if (b.kind == PdfBlockKind::kPageBreak) page_break = true;
    if (b.kind == PdfBlockKind::kFigure) {
      CHECK(page_break);
      CHECK(b.svg_file == "figures/x_sweep.svg");
      CHECK(b.text == "x against h");
    }
  }
  CHECK(titles == std::vector<std::string>{"Best variant per output", "Variants, best first"});
  CHECK(pdf.title == "Sweep: s");
}

}  // namespace deb::report
