#include "deb/report/budget/report_pdf.h"

#include <doctest/doctest.h>

#include <fstream>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/report_writer.h"
#include "deb/report/budget/requirement_lines.h"
#include "deb/report/budget/report_tables.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

using namespace deb::test;

struct Evaluated {
  Budget budget;
  BudgetResult result;
};

Evaluated Evaluate(const std::string& file) {
  Evaluated e{LoadBudgetFile(ExampleBudget(file)), {}};
  e.result = deb::Evaluate(e.budget);
  return e;
}

std::vector<std::string> Headings(const PdfDocumentSpec& s, int level) {
  std::vector<std::string> h;
  for (const PdfBlock& b : s.blocks)
    if (b.kind == PdfBlockKind::kHeading && b.level == level) h.push_back(b.text);
  return h;
}

}  // namespace

TEST_CASE("a long note shared by several rows is printed once below the table, each row carrying its mark") {
  Table t;
  t.header = {"name", "rms", "remark"};
  t.numeric = {false, true, false};
  const std::string shared = "the source is not white (no exact variance)";
  const std::string alone = "grid holds 99.96 % of the exact variance";
  t.rows = {{"a", "1.5", shared}, {"b", "0.25", alone}, {"c", "0.5", shared}, {"d", "FAIL", "ok"},
            {"e", "0.1", "ok"}};
  const PdfTable p = TypesetTable(t);
  REQUIRE(p.footnotes.size() == 1);
  CHECK(p.footnotes[0] == "¹ " + shared);
  CHECK(p.rows[0][2].text == "¹");
  CHECK(p.rows[2][2].text == "¹");
  CHECK(p.rows[1][2].text == alone);  // once only, outside a note column: stays in its row (wrapped there)
  CHECK(p.rows[3][2].text == "ok");   // short: repeated as it is
  CHECK(p.rows[3][1].alert);
  CHECK(p.rows[3][1].bold);
  CHECK_FALSE(p.rows[0][1].alert);
  CHECK(p.numeric == t.numeric);
}

TEST_CASE("every long note of the column headed note is printed below the table, marked in the order of the rows") {
  Table t;
  t.header = {"contributor", "path", "rms", "note"};
  t.numeric = {false, false, true, false};
  const std::string shared = "the source is not white (no exact variance)";
  const std::string alone = "grid holds 99.96 % of the exact variance";
  const std::string long_path = "measurement_to_position_through_the_frame";  // long, once, not a note column
  t.rows = {{"a", "p", "1.5", shared}, {"b", long_path, "0.25", alone}, {"c", "p", "0.5", shared},
            {"d", "p", "0.1", "short note"}, {"total", "", "2.0", ""}};
  const PdfTable p = TypesetTable(t);
  REQUIRE(p.footnotes.size() == 2);
  CHECK(p.footnotes[0] == "¹ " + shared);
  CHECK(p.footnotes[1] == "² " + alone);
  CHECK(p.rows[0][3].text == "¹");
  CHECK(p.rows[1][3].text == "²");
  CHECK(p.rows[2][3].text == "¹");
  CHECK(p.rows[3][3].text == "short note");  // under 24 characters: stays
  CHECK(p.rows[4][3].text == "");
  CHECK(p.rows[1][1].text == long_path);
}

TEST_CASE("the verdict has a row per requirement line: PASS in green, FAIL in red, what would meet it once") {
  const Evaluated e = Evaluate("wafer_stage.yaml");
  const PdfTable v = VerdictTable(e.result);
  CHECK(v.boxed);
  std::size_t row = 0;
  int failing_outputs = 0, failing_lines = 0, passing_lines = 0;
  for (const OutputResult& o : e.result.outputs) {
    CAPTURE(o.name);
    const std::vector<RequirementLine> lines = RequirementLines(o);
    REQUIRE(!lines.empty());  // every output of the example has a requirement
    CHECK(lines.size() == (o.rms_max ? 1u : 0u) + o.band_requirements.size());
    const bool fails = !o.AllPass();
    failing_outputs += fails;
    for (std::size_t i = 0; i < lines.size(); ++i, ++row) {
      REQUIRE(row < v.rows.size());
      const std::vector<PdfCell>& r = v.rows[row];
      // The output named (and linked to its section) on its first line only.
      CHECK(r[0].text == (i == 0 ? o.name : ""));
      CHECK(r[0].link == (i == 0 ? "Output " + o.name : ""));
      CHECK(r[1].text.find("RMS ≤ " + Short(lines[i].rms_max)) != std::string::npos);
      CHECK(r[2].text == Sig(lines[i].rms, 4) + " " + UnitText(o.unit));
      CHECK(r[3].text == (lines[i].pass ? "PASS" : "FAIL"));
      CHECK(r[3].alert == !lines[i].pass);
      CHECK(r[3].good == lines[i].pass);
      failing_lines += !lines[i].pass;
      passing_lines += lines[i].pass;
      CHECK(r[4].text == (i == 0 && fails ? GuidanceText(o, e.result.grid) : "–"));
    }
  }
  CHECK(row == v.rows.size());
  CHECK(failing_outputs == 2);  // position and image_shift
  // position fails overall and in 0.1–10 Hz; image_shift overall: a passing line among them is green.
  CHECK(failing_lines == 3);
  CHECK(passing_lines >= 1);
}

TEST_CASE("a verdict without a failing output has no column for what would meet it") {
  const Evaluated e = Evaluate("nizamoglu2015_h210.yaml");
  const PdfTable v = VerdictTable(e.result);
  CHECK(v.header == std::vector<std::string>{"output", "requirement", "value", "verdict"});
  REQUIRE(v.rows.size() == e.result.outputs.size());
  for (const auto& row : v.rows) {
    CHECK(row.size() == 4);
    CHECK(row[1].text == "none");
    CHECK(row[3].text == "–");
  }
}

TEST_CASE("the document: title page, contents, overview, a section per output with its own plots in order, notes") {
  const Evaluated e = Evaluate("wafer_stage.yaml");
  std::vector<Plot> plots;
  // Shuffled kinds and outputs: the layout groups them.
  const auto plot = [&](const std::string& name, PlotKind kind, int output) {
    Plot p;
    p.name = name;
    p.kind = kind;
    p.output = output;
    p.caption = name;
    plots.push_back(p);
  };
  plot("path_1_a", PlotKind::kPath, 1);
  plot("overview", PlotKind::kOverview, -1);
  plot("bands_0", PlotKind::kBands, 0);
  plot("cps_0", PlotKind::kCps, 0);
  plot("path_0_a", PlotKind::kPath, 0);
  plot("psd_0", PlotKind::kSpectrum, 0);
  plot("cps_1", PlotKind::kCps, 1);
  ReportPdfInputs in;
  in.result = &e.result;
  in.plots = &plots;
  in.figure_dir = "/figs";
  in.sha256 = "0123456789abcdef";
  const PdfDocumentSpec s = ReportPdfSpec(in);
  CHECK(s.footer.find("wafer_stage · SHA-256 0123456789ab") != std::string::npos);
  CHECK(Headings(s, 0) == std::vector<std::string>{"wafer_stage"});
  std::vector<std::string> sections = {"Contents", "Overview"};
  for (const auto& o : e.result.outputs) sections.push_back("Output " + o.name);
  sections.push_back("Paths");  // the path figures, listed
  sections.push_back("Warnings and notes");
  sections.push_back("Conventions");
  CHECK(Headings(s, 1) == sections);
  // Figures in order, each under its output's section.
  std::vector<std::string> figures;
  std::string section;
  for (const PdfBlock& b : s.blocks) {
    if (b.kind == PdfBlockKind::kHeading && b.level == 1) section = b.text;
    if (b.kind == PdfBlockKind::kFigure) figures.push_back(section + ": " + b.svg_file);
  }
  const std::string out0 = "Output " + e.result.outputs[0].name + ": /figs/",
                    out1 = "Output " + e.result.outputs[1].name + ": /figs/";
  // The path figures are not drawn: the section Paths lists them (drawn in index.html).
  CHECK(figures == std::vector<std::string>{"Overview: /figs/overview.svg", out0 + "cps_0.svg", out0 + "psd_0.svg",
                                            out0 + "bands_0.svg", out1 + "cps_1.svg"});
  std::vector<std::string> listed;
  for (const PdfBlock& b : s.blocks)
    if (b.kind == PdfBlockKind::kTable && b.text.rfind("Bode figures of the paths", 0) == 0)
      for (const auto& row : b.table.rows) listed.push_back(row.at(1).text);
  CHECK(listed == std::vector<std::string>{"path_0_a", "path_1_a"});
  // The verdict box is on page 1 (before the first page break).
  bool verdict_before_break = false;
  for (const PdfBlock& b : s.blocks) {
    if (b.kind == PdfBlockKind::kPageBreak) break;
    verdict_before_break = verdict_before_break || (b.kind == PdfBlockKind::kTable && b.table.boxed);
  }
  CHECK(verdict_before_break);
}

TEST_CASE("report.pdf of a failing budget: verdict and guidance on page 1, a section per output, every page numbered") {
  const Evaluated e = Evaluate("wafer_stage.yaml");
  const fs::path dir = TempDir("report_pdf") / "report";
  const ReportManifest m =
      WriteReportDirectory(e.result, {ExampleBudget("wafer_stage.yaml"), 0.1}, {}, dir.string());
  REQUIRE(m.pdf_pages > 5);
  CHECK(PdfPages(dir / "report.pdf") == m.pdf_pages);
  const Command page1 = Shell("pdftotext -f 1 -l 1 \"" + (dir / "report.pdf").string() + "\" -");
  if (page1.exit_code == 0) {  // poppler-utils present
    CHECK(page1.out.find("Verdict") != std::string::npos);
    CHECK(page1.out.find("FAIL") != std::string::npos);
    CHECK(page1.out.find("PASS") != std::string::npos);
    CHECK(page1.out.find("page 1/" + std::to_string(m.pdf_pages)) != std::string::npos);
    CHECK(page1.out.find("position fails by") != std::string::npos);
    const Command all = Shell("pdftotext \"" + (dir / "report.pdf").string() + "\" -");
    for (const auto& o : e.result.outputs) CHECK(all.out.find("Output " + o.name) != std::string::npos);
    CHECK(all.out.find("page " + std::to_string(m.pdf_pages) + "/" + std::to_string(m.pdf_pages)) !=
          std::string::npos);
  }
  fs::remove_all(dir.parent_path());
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("page 1 says how many warnings the evaluation raised; the last section lists them") {
  Evaluated e{LoadBudgetFile(ExampleBudget("measured_stage.yaml")), {}};
  e.result = deb::Evaluate(e.budget);
  REQUIRE(e.result.warnings.size() == 1);
  ReportPdfInputs in;
  in.result = &e.result;
  const PdfDocumentSpec s = ReportPdfSpec(in);
  bool on_page_1 = false, listed = false, first_page = true;
  for (const PdfBlock& b : s.blocks) {
    if (b.kind == PdfBlockKind::kPageBreak) first_page = false;
    if (b.kind != PdfBlockKind::kParagraph) continue;
    on_page_1 = on_page_1 || (first_page && b.text == "The evaluation raised 1 warning: see Warnings and notes.");
    listed = listed || (b.bullet && b.text == e.result.warnings[0]);
  }
  CHECK(on_page_1);
  CHECK(listed);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the failing example's document keeps every box inside the margin; its verdict and FAIL cells are red") {
  Evaluated e{LoadBudgetFile(ExampleBudget("wafer_stage.yaml")), {}};
  e.result = deb::Evaluate(e.budget);
  const fs::path dir = TempDir("report_pdf_layout");
  std::vector<Plot> plots;
  for (int o = -1; o < static_cast<int>(e.result.outputs.size()); ++o)
    for (PlotKind kind : {PlotKind::kCps, PlotKind::kSpectrum, PlotKind::kBands, PlotKind::kPath}) {
      Plot p;
      p.name = "plot_" + std::to_string(plots.size());
      p.kind = o < 0 ? PlotKind::kOverview : kind;
      p.output = o;
      p.caption = "A plot.";
      std::ofstream(dir / (p.name + ".svg"))
          << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"662\" height=\"420\"><rect width=\"662\" "
             "height=\"420\" fill=\"none\" stroke=\"black\"/></svg>\n";
      plots.push_back(p);
      if (o < 0) break;
    }
  ReportPdfInputs in;
  in.result = &e.result;
  in.plots = &plots;
  in.figure_dir = dir.string();
  const PdfLayout layout = WritePdfDocument(ReportPdfSpec(in), "");
  int fail_cells = 0, figures = 0;
  for (const PlacedBox& b : layout.boxes) {
    CAPTURE(b.what);
    CAPTURE(b.text);
    CHECK(b.x_pt >= kMarginPt - 1e-6);
    CHECK(b.y_pt >= kMarginPt - 1e-6);
    CHECK(b.x_pt + b.width_pt <= kPageWidthPt - kMarginPt + 1e-6);
    CHECK(b.y_pt + b.height_pt <= kPageHeightPt - kMarginPt + 1e-6);
    if (b.what == "table cell" && b.text == "FAIL") {
      ++fail_cells;
      CHECK(b.colour == "#c00000");
    }
    figures += b.what == "figure";
  }
  CHECK(fail_cells == 3 + 3);  // the verdict and the summary alike: position, its 0.1–10 Hz band, image_shift
  int path_plots = 0;
  for (const Plot& p : plots) path_plots += p.kind == PlotKind::kPath && p.output >= 0;
  CHECK(figures == static_cast<int>(plots.size()) - path_plots);  // path figures listed, not drawn
  // The verdict box on page 1; each output's section starts on a page of its own, or below the previous one
  // where at least 200 pt of the page are left (its heading, verdict and first rows: no half-empty page).
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "box") CHECK(b.page == 1);
  int sections = 0, sharing = 0;
  for (const OutlineEntry& o : layout.outline)
    if (o.text.rfind("Output ", 0) == 0) {
      ++sections;
      int first_on_page = 0;
      double y_pt = 0.0;
      for (const PlacedBox& b : layout.boxes) {
        if (b.page == o.page && first_on_page == 0) first_on_page = 1 + (b.text == o.text ? 1 : 0);
        if (b.page == o.page && b.what == "heading" && b.text == o.text) y_pt = b.y_pt;
      }
      if (first_on_page != 2) {
        ++sharing;
        CHECK_MESSAGE(y_pt < kPageHeightPt - kMarginPt - 200.0, o.text);
      }
    }
  CHECK(sections == static_cast<int>(e.result.outputs.size()));
  CHECK(sharing >= 1);  // the example's image_shift follows position's section on its last page
  fs::remove_all(dir);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("report.pdf has the covariance table of index.html and report.md below the summary, none without one") {
  const Evaluated e = Evaluate("nizamoglu2015_h210.yaml");
  REQUIRE(e.result.covariance.has_value());
  ReportPdfInputs in;
  in.result = &e.result;
  in.digits = 4;
  const Table expected = CovarianceTable(*e.result.covariance, 4);
  const PdfDocumentSpec s = ReportPdfSpec(in);
  std::vector<std::string> tables_in_overview;
  const PdfBlock* found = nullptr;
  std::string section;
  for (const PdfBlock& b : s.blocks) {
    if (b.kind == PdfBlockKind::kHeading && b.level == 1) section = b.text;
    if (b.kind != PdfBlockKind::kTable || section != "Overview") continue;
    tables_in_overview.push_back(b.text);
    if (b.text == expected.title) found = &b;
  }
  CHECK(tables_in_overview == std::vector<std::string>{"Summary", expected.title});
  REQUIRE(found);
  CHECK(found->table.header == expected.header);
  REQUIRE(found->table.rows.size() == 6);  // 4 outputs: 6 pairs
  for (std::size_t r = 0; r < expected.rows.size(); ++r)
    for (std::size_t c = 0; c < 4; ++c) CHECK(found->table.rows[r][c].text == expected.rows[r][c]);

  const Evaluated plain = Evaluate("wafer_stage.yaml");
  REQUIRE_FALSE(plain.result.covariance.has_value());
  in.result = &plain.result;
  for (const PdfBlock& b : ReportPdfSpec(in).blocks) CHECK(b.text.find("Covariance") == std::string::npos);
}

}  // namespace deb::report
