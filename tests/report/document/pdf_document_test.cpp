#include "deb/report/document/pdf_document.h"

#include <doctest/doctest.h>

#include <cmath>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "deb/core/error.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

using namespace deb::test;

// A document that starts with `lines` one-line paragraphs: what follows
// them starts anywhere down a page, as the filler's length moves it.
deb::report::PdfDocumentSpec WithFiller(int lines) {
  deb::report::PdfDocumentSpec spec;
  spec.create_date = "2026-01-01T00:00:00Z";
  for (int i = 0; i < lines; ++i) spec.blocks.push_back(deb::report::Paragraph("Filler line " + std::to_string(i) + "."));
  return spec;
}

std::string Bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A 400 x 250 px SVG: a frame and a line.
fs::path SmallSvg(const fs::path& dir) {
  const fs::path f = dir / "figure.svg";
  std::ofstream(f) << "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" "
                      "height=\"250\" viewBox=\"0 0 400 250\"><rect x=\"1\" y=\"1\" width=\"398\" height=\"248\" "
                      "fill=\"none\" stroke=\"black\"/><path d=\"M10 240 L390 10\" stroke=\"red\"/></svg>\n";
  return f;
}

// Title, contents, two sections: a table of 80 rows (one FAIL, one long
// note) and three figures under a subsection.
PdfDocumentSpec Sample(const fs::path& svg) {
  PdfDocumentSpec s;
  s.title = "sample";
  s.footer = "deb · sample";
  s.create_date = "2023-11-14T22:13:20Z";
  s.blocks.push_back(Heading(0, "Sample document"));
  s.blocks.push_back(Paragraph("What this is."));
  s.blocks.push_back(PageBreak());
  s.blocks.push_back(Heading(1, "Contents"));
  s.blocks.push_back(Contents());
  s.blocks.push_back(PageBreak());
  s.blocks.push_back(Heading(1, "Table"));
  PdfTable t;
  t.header = {"name", "value", "note"};
  t.numeric = {false, true, false};
  for (int r = 0; r < 80; ++r)
    t.rows.push_back({{"row " + std::to_string(r)}, {std::to_string(r * r) + ".25"}, {r == 3 ? "FAIL" : "ok"}});
  t.rows[7][1].text = "1.5e-05";
  t.rows[8][1].text = "12 %";
  t.rows[3][2].alert = true;
  t.rows[0][0].link = "Figures";
  t.rows[1][0].link = "no such heading";  // no link
  t.rows[5][2].text = std::string(60, 'x') + " a long note that must wrap inside its column and not be cut off at all";
  t.footnotes = {"¹ a note"};
  s.blocks.push_back(TableBlock("A long table", t));
  PdfTable box;
  box.boxed = true;
  box.header = {"verdict"};
  box.rows = {{{"FAIL", true, true}}};
  s.blocks.push_back(TableBlock("A box", box));
  PdfTable wide;  // 24 numbers that cannot fit at the table font
  for (int c = 0; c < 24; ++c) {
    wide.header.push_back("column " + std::to_string(c));
    wide.numeric.push_back(true);
  }
  wide.rows.push_back(std::vector<PdfCell>(24, PdfCell("123456.789")));
  s.blocks.push_back(TableBlock("A wide table", wide));
  s.blocks.push_back(Heading(1, "Figures"));
  s.blocks.push_back(Heading(2, "Three of them"));
  for (int k = 0; k < 3; ++k) s.blocks.push_back(Figure(svg.string(), "A line, number " + std::to_string(k) + "."));
  return s;
}

}  // namespace

TEST_CASE("every box of the layout lies inside the printable margin of an A4 page, a table too wide for it too") {
  const fs::path dir = TempDir("pdf_layout");
  const PdfLayout layout = WritePdfDocument(Sample(SmallSvg(dir)), "");
  REQUIRE(layout.pages >= 4);
  CHECK(kMarginPt >= 15.0 / 25.4 * 72.0);
  int footers = 0;
  for (const PlacedBox& b : layout.boxes) {
    CAPTURE(b.what);
    CAPTURE(b.text);
    CHECK(b.page >= 1);
    CHECK(b.page <= layout.pages);
    CHECK(b.x_pt >= kMarginPt - 1e-6);
    CHECK(b.y_pt >= kMarginPt - 1e-6);
    CHECK(b.x_pt + b.width_pt <= kPageWidthPt - kMarginPt + 1e-6);
    CHECK(b.y_pt + b.height_pt <= kPageHeightPt - kMarginPt + 1e-6);
    footers += b.what == "footer";
  }
  CHECK(footers == layout.pages);
  fs::remove_all(dir);
}

TEST_CASE("a long table continues on the next page with its header repeated; long text wraps; FAIL is red") {
  const fs::path dir = TempDir("pdf_table");
  const PdfLayout layout = WritePdfDocument(Sample(SmallSvg(dir)), "");
  std::set<int> table_pages, header_pages;
  double plain_row = 0, long_row = 0;
  for (const PlacedBox& b : layout.boxes) {
    if (b.what == "table row") table_pages.insert(b.page);
    if (b.what == "table header row") header_pages.insert(b.page);
    if (b.what == "table row" && b.text == "row 4 | 16.25 | ok") plain_row = b.height_pt;
    if (b.what == "table row" && b.text.rfind("row 5 |", 0) == 0) long_row = b.height_pt;
    if (b.what == "table cell" && b.text == "FAIL") CHECK(b.colour == "#c00000");
    if (b.what == "table cell" && b.text == "ok") CHECK(b.colour != "#c00000");
  }
  CHECK(table_pages.size() >= 2);
  CHECK(header_pages == table_pages);
  CHECK(long_row > 1.5 * plain_row);  // two lines at least: wrapped, not cut
  fs::remove_all(dir);
}

TEST_CASE("the numbers of a column share the x of their decimal point, inside the column") {
  const fs::path dir = TempDir("pdf_point");
  const PdfLayout layout = WritePdfDocument(Sample(SmallSvg(dir)), "");
  std::set<double> points;
  int cells = 0;
  for (const PlacedBox& b : layout.boxes) {
    if (b.what != "table cell" || b.text.find_first_of("0123456789") != 0) continue;  // the value column
    if (b.text.rfind("row", 0) == 0 || b.text == "123456.789") continue;  // not the long table's
    ++cells;
    points.insert(b.point_x_pt);
    CHECK(b.point_x_pt > b.x_pt);
    CHECK(b.point_x_pt < b.x_pt + b.width_pt);
  }
  CHECK(cells == 80);
  CHECK(points.size() == 1);  // 0.25, 6241.25, 1.5e-05 and "12 %" alike
  fs::remove_all(dir);
}

TEST_CASE("headings form the outline with their pages, and the contents list them with the same pages") {
  const fs::path dir = TempDir("pdf_outline");
  const PdfLayout layout = WritePdfDocument(Sample(SmallSvg(dir)), "");
  REQUIRE(layout.outline.size() == 4);
  CHECK(layout.outline[0].text == "Contents");
  CHECK(layout.outline[0].page == 2);
  CHECK(layout.outline[1].text == "Table");
  CHECK(layout.outline[1].page == 3);
  CHECK(layout.outline[3].level == 2);
  CHECK(layout.outline[3].page > layout.outline[1].page);  // after the long table
  // The contents list the sections (level 1) but their own heading, the outline every heading.
  std::vector<std::string> contents, sections;
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "contents") contents.push_back(b.text);
  for (const OutlineEntry& o : layout.outline)
    if (o.level == 1 && o.text != "Contents") sections.push_back(o.text + " ... " + std::to_string(o.page));
  CHECK(sections.size() == 2);
  CHECK(contents == sections);
  // Figures are numbered in their captions and each stays on the page of its picture.
  int figures = 0;
  for (std::size_t i = 0; i + 1 < layout.boxes.size(); ++i)
    if (layout.boxes[i].what == "figure") {
      ++figures;
      CHECK(layout.boxes[i + 1].what == "caption");
      CHECK(layout.boxes[i + 1].page == layout.boxes[i].page);
      CHECK(layout.boxes[i + 1].text.rfind("Figure " + std::to_string(figures) + ". ", 0) == 0);
    }
  CHECK(figures == 3);
  fs::remove_all(dir);
}

TEST_CASE("the PDF has the pages of its layout, an outline, its text, and the same bytes when written again") {
  const fs::path dir = TempDir("pdf_file");
  const PdfDocumentSpec spec = Sample(SmallSvg(dir));
  const PdfLayout layout = WritePdfDocument(spec, (dir / "a.pdf").string());
  WritePdfDocument(spec, (dir / "b.pdf").string());
  CHECK(PdfPages(dir / "a.pdf") == layout.pages);
  const std::string a = Bytes(dir / "a.pdf");
  CHECK(a == Bytes(dir / "b.pdf"));
  // Bookmarks: one per heading of level >= 1; links: one per line of the contents (a section each but the
  // contents' own), one per linked cell.
  CHECK(a.find("/Outlines") != std::string::npos);
  for (const char* title : {"/Title (Contents)", "/Title (Table)", "/Title (Figures)", "/Title (Three of them)"})
    CHECK_MESSAGE(a.find(title) != std::string::npos, title);
  std::size_t links = 0;
  for (std::size_t at = a.find("/Subtype /Link"); at != std::string::npos; at = a.find("/Subtype /Link", at + 1))
    ++links;
  CHECK(links == 2 + 1);
  CHECK(a.find("20231114221320Z") != std::string::npos);
  const Command text = Shell("pdftotext -layout \"" + (dir / "a.pdf").string() + "\" -");
  if (text.exit_code == 0) {  // poppler-utils present
    CHECK(text.out.find("Sample document") != std::string::npos);
    CHECK(text.out.find("page 1/" + std::to_string(layout.pages)) != std::string::npos);
    CHECK(text.out.find("Figure 3. A line, number 2.") != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("in a table too wide, short columns stay on one line and the long text wraps") {
  PdfTable t;
  t.header = {"requirement", "value", "what would meet it"};
  t.numeric = {false, false, false};
  std::string guidance;
  for (int k = 0; k < 40; ++k) guidance += "reduce the floor vibration ";
  t.rows = {{{"0.1–10 Hz: RMS ≤ 0.8 nm"}, {"1.333 nm"}, {guidance}}, {{"RMS ≤ 1.5 nm"}, {"2.114 nm"}, {"–"}}};
  PdfDocumentSpec spec;
  spec.blocks.push_back(TableBlock("", t));
  const PdfLayout layout = WritePdfDocument(spec, "");
  double one_line = 0.0, wrapped = 0.0;
  for (const PlacedBox& b : layout.boxes) {
    if (b.what == "table header row") one_line = b.height_pt;
    if (b.what == "table row" && b.text.rfind("0.1–10 Hz", 0) == 0) wrapped = b.height_pt;
    if (b.what == "table row" && b.text.rfind("RMS ≤ 1.5", 0) == 0) CHECK(b.height_pt == doctest::Approx(one_line));
  }
  CHECK(one_line > 0.0);
  CHECK(wrapped > 3.0 * one_line);  // the guidance, several lines
}

TEST_CASE("a figure that is not an SVG file is an error naming it") {
  const fs::path dir = TempDir("pdf_bad");
  PdfDocumentSpec spec;
  spec.blocks.push_back(Figure((dir / "missing.svg").string(), "gone"));
  CHECK_THROWS_WITH_AS(WritePdfDocument(spec, (dir / "x.pdf").string()), doctest::Contains("missing.svg"), WriteError);
  fs::remove_all(dir);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a figure that fits at 85 % of the text width or more is set smaller rather than moved to the next page") {
  const fs::path dir = TempDir("pdf_fit");
  const fs::path svg = dir / "tall.svg";  // 400 x 290 px: 358 pt high across the text width
  std::ofstream(svg) << "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" "
                        "height=\"290\" viewBox=\"0 0 400 290\"><rect x=\"1\" y=\"1\" width=\"398\" height=\"288\" "
                        "fill=\"none\" stroke=\"black\"/></svg>\n";
  PdfDocumentSpec spec;
  for (int k = 0; k < 3; ++k) spec.blocks.push_back(Figure(svg.string(), "Figure " + std::to_string(k) + "."));
  const PdfLayout layout = WritePdfDocument(spec, "");
  std::vector<PlacedBox> figures;
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "figure") figures.push_back(b);
  REQUIRE(figures.size() == 3);
  const double text_width = kPageWidthPt - 2.0 * kMarginPt;
  // The first at the text width; the second below it on the same page, at 85-100 % of it, centred.
  CHECK(figures[0].width_pt == doctest::Approx(text_width));
  CHECK(figures[1].page == 1);
  CHECK(figures[1].width_pt < text_width);
  CHECK(figures[1].width_pt >= 0.85 * text_width);
  CHECK(figures[1].height_pt == doctest::Approx(figures[1].width_pt * 0.725));
  CHECK(figures[1].x_pt + 0.5 * figures[1].width_pt == doctest::Approx(0.5 * kPageWidthPt));
  // Its caption stays above the footer.
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "caption" && b.page == 1) CHECK(b.y_pt + b.height_pt <= kPageHeightPt - kMarginPt - 9.0);
  // The third would need far less than 85 %: the next page, at the text width.
  CHECK(figures[2].page == 2);
  CHECK(figures[2].width_pt == doctest::Approx(text_width));
  fs::remove_all(dir);
}

// A figure block planned on a canvas of 662 x height px (no SVG drawn yet),
// free to be drawn down to `least` px high.
PdfBlock Planned(int height_px, int least_px, const std::string& caption) {
  PdfBlock b = Figure("planned.svg", caption);
  b.width_px = 662;
  b.height_px = height_px;
  b.min_height_px = least_px;
  return b;
}

std::vector<PlacedBox> Figures(const PdfLayout& layout) {
  std::vector<PlacedBox> figures;
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "figure") figures.push_back(b);
  return figures;
}

TEST_CASE("a figure free to be shorter stays on its page across the text width, at the height of the room left") {
  const double text_width = kPageWidthPt - 2.0 * kMarginPt;
  // 600 px (437 pt) then 420 px (306 pt): about 240 pt are left for the
  // second, 79 % of it: too little for the 85 % rule, enough at 2/3.
  PdfDocumentSpec spec;
  spec.blocks = {Planned(600, 0, "A."), Planned(420, 0, "B.")};
  const std::vector<PlacedBox> fixed = Figures(WritePdfDocument(spec, ""));
  REQUIRE(fixed.size() == 2);
  CHECK(fixed[1].page == 2);
  spec.blocks[1].min_height_px = 280;
  const PdfLayout layout = WritePdfDocument(spec, "");
  const std::vector<PlacedBox> shorter = Figures(layout);
  REQUIRE(shorter.size() == 2);
  CHECK(shorter[1].page == 1);
  CHECK(shorter[1].width_pt == doctest::Approx(text_width));
  CHECK(shorter[1].height_pt < 0.85 * 420.0 / 662.0 * text_width);
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "caption" && b.page == 1) CHECK(b.y_pt + b.height_pt <= kPageHeightPt - kMarginPt - 9.0);
  // The heights to draw: whole px, the placed height rounded down.
  const std::vector<int> px = FittedFigureHeightsPx(spec, layout);
  REQUIRE(px.size() == 2);
  CHECK(px[0] == 600);
  CHECK(px[1] >= 280);
  CHECK(px[1] < 420);
  CHECK(px[1] == static_cast<int>(std::floor(shorter[1].height_pt * 662.0 / text_width + 1e-6)));
}

TEST_CASE("two figures free to be shorter share one scale where the second would leave the page otherwise") {
  // 300 px, then 420 and 420: the third fits neither whole nor at 2/3 after
  // the second; both at about 70 % fill the page instead.
  PdfDocumentSpec spec;
  spec.blocks = {Planned(300, 0, "A."), Planned(420, 280, "B."), Planned(420, 280, "C.")};
  const PdfLayout layout = WritePdfDocument(spec, "");
  const std::vector<PlacedBox> f = Figures(layout);
  REQUIRE(f.size() == 3);
  CHECK(f[2].page == 1);
  const double full = 420.0 / 662.0 * (kPageWidthPt - 2.0 * kMarginPt);
  CHECK(f[1].height_pt == doctest::Approx(f[2].height_pt).epsilon(0.01));
  CHECK(f[1].height_pt >= 2.0 / 3.0 * full);
  CHECK(f[1].height_pt < full);
  for (const PlacedBox& b : layout.boxes) CHECK(b.y_pt + b.height_pt <= kPageHeightPt - kMarginPt);
  // Not at 3/4 at least: the third goes to the next page, the second whole.
  for (int k : {1, 2}) spec.blocks[static_cast<std::size_t>(k)].min_height_px = 315;
  const std::vector<PlacedBox> g = Figures(WritePdfDocument(spec, ""));
  CHECK(g[1].height_pt == doctest::Approx(full));
  CHECK(g[2].page == 2);
}

TEST_CASE("a page break with room to spare starts a new page only when less than that is left") {
  PdfDocumentSpec spec;
  spec.blocks.push_back(Paragraph("one"));
  spec.blocks.push_back(PageBreak(300.0));  // most of the page is left: no break
  spec.blocks.push_back(Paragraph("two"));
  spec.blocks.push_back(PageBreak(kPageHeightPt));  // never that much: a break
  spec.blocks.push_back(Paragraph("three"));
  spec.blocks.push_back(PageBreak());
  spec.blocks.push_back(Paragraph("four"));
  const PdfLayout layout = WritePdfDocument(spec, "");
  std::map<std::string, int> page;
  for (const PlacedBox& b : layout.boxes)
    if (b.what == "paragraph") page[b.text] = b.page;
  CHECK(page["one"] == 1);
  CHECK(page["two"] == 1);
  CHECK(page["three"] == 2);
  CHECK(page["four"] == 3);
}

TEST_CASE("in a table too wide, the columns that must wrap share the width by what each lacks") {
  PdfTable t;
  t.header = {"name", "note", "a", "b"};
  t.numeric = {false, false, true, true};
  std::string names, notes;
  for (int k = 0; k < 20; ++k) names += "word ";
  for (int k = 0; k < 60; ++k) notes += "word ";
  t.rows = {{{names}, {notes}, {"123456.789012"}, {"123456.789012"}}};
  PdfDocumentSpec spec;
  spec.blocks.push_back(TableBlock("", t));
  const PdfLayout layout = WritePdfDocument(spec, "");
  double name_w = 0.0, note_w = 0.0;
  for (const PlacedBox& b : layout.boxes) {
    if (b.what != "table cell") continue;
    if (b.text == names) name_w = b.width_pt;
    if (b.text == notes) note_w = b.width_pt;
  }
  REQUIRE(name_w > 0.0);
  // Both lack more than an even share; the note lacks three times what the name does and gets about three times
  // the width (an even share gave both the same).
  CHECK(note_w > 2.0 * name_w);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a figure's text keeps the space after a superscript, as gnuplot writes it to SVG") {
  // gnuplot's enhanced "10^{-3} of" in SVG: the text after the superscript is a tspan starting with its space,
  // which librsvg would drop under SVG's default white-space handling ("10-3of").
  const fs::path dir = TempDir("pdf_tspan");
  const fs::path svg = dir / "text.svg";
  std::ofstream(svg) << "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" "
                        "height=\"100\" viewBox=\"0 0 400 100\"><g transform=\"translate(20,50)\" font-family=\"DejaVu "
                        "Sans\" font-size=\"11\"><text><tspan>all but 10</tspan><tspan font-size=\"7\" dy=\"-4px\">-3"
                        "</tspan><tspan dy=\"4px\"> of every contributor</tspan></text></g></svg>\n";
  PdfDocumentSpec s;
  s.title = "t";
  s.footer = "t";
  s.create_date = "2023-11-14T22:13:20Z";
  s.blocks.push_back(Figure(svg.string(), "A figure."));
  WritePdfDocument(s, (dir / "t.pdf").string());
  const Command text = Shell("pdftotext \"" + (dir / "t.pdf").string() + "\" -");
  if (text.exit_code == 0) {  // poppler-utils present
    CHECK(text.out.find("-3 of every contributor") != std::string::npos);
    CHECK(text.out.find("-3of") == std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("no table row is alone on a page, and a short table is not split") {
  // Tables of 30 to 90 rows after a paragraph: wherever the page breaks,
  // every page that holds rows of the table holds at least two.
  for (std::size_t n = 30; n <= 90; ++n) {
    CAPTURE(n);
    PdfDocumentSpec spec;
    spec.create_date = "2026-01-01T00:00:00Z";
    spec.blocks.push_back(Paragraph("A paragraph before the table."));
    PdfTable t;
    t.header = {"row", "value"};
    t.numeric = {false, true};
    for (std::size_t r = 0; r < n; ++r) t.rows.push_back({PdfCell("row " + std::to_string(r)), PdfCell("1.5")});
    spec.blocks.push_back(TableBlock("rows", t));
    const PdfLayout layout = WritePdfDocument(spec, "");
    std::map<int, int> rows_on;
    for (const PlacedBox& b : layout.boxes)
      if (b.what == "table row") ++rows_on[b.page];
    for (const auto& page : rows_on) CHECK_MESSAGE(page.second >= 2, "page " << page.first);
  }
  // Five rows that would start at the foot of a page start on the next, whole.
  PdfDocumentSpec spec;
  spec.create_date = "2026-01-01T00:00:00Z";
  for (int i = 0; i < 48; ++i) spec.blocks.push_back(Paragraph("Filler line " + std::to_string(i) + "."));
  PdfTable t;
  t.header = {"row"};
  t.numeric = {false};
  for (int r = 0; r < 5; ++r) t.rows.push_back({PdfCell("row " + std::to_string(r))});
  spec.blocks.push_back(TableBlock("five", t));
  std::set<int> pages;
  for (const PlacedBox& b : WritePdfDocument(spec, "").boxes)
    if (b.what == "table row") pages.insert(b.page);
  CHECK(pages.size() == 1);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a heading and a one-line paragraph are never all of a page's bottom: they go with the table after them") {
  // sensitivity.pdf left "x_velocity" and "Nominal RMS 11.28 µm/s." alone at
  // a page's foot, their table of 15 rows on the next. Wherever the filler
  // ends, the heading's page holds the table's first row.
  for (int filler = 30; filler <= 56; ++filler) {
    CAPTURE(filler);
    PdfDocumentSpec spec = WithFiller(filler);
    spec.blocks.push_back(Heading(2, "x_velocity"));
    spec.blocks.push_back(Paragraph("Nominal RMS 11.28 um/s."));
    PdfTable t;
    t.header = {"parameter", "value"};
    t.numeric = {false, true};
    for (int r = 0; r < 15; ++r) t.rows.push_back({PdfCell("p" + std::to_string(r)), PdfCell("1.5")});
    spec.blocks.push_back(TableBlock("x_velocity: the total first", t));
    int heading_page = -1, first_row_page = -1;
    for (const PlacedBox& b : WritePdfDocument(spec, "").boxes) {
      if (b.what == "heading" && b.text == "x_velocity") heading_page = b.page;
      if (b.what == "table row" && first_row_page < 0) first_row_page = b.page;
    }
    CHECK(heading_page == first_row_page);
  }
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a short list stays whole with its heading; a long one's last item never stands alone at a page's top") {
  // The tolerances report's last page held only the last Conventions
  // bullet, then, with that rule alone, its last two. Wherever the filler
  // ends, a heading and its 6 items share one page.
  const std::string item = ": a convention said in one line or two.";
  for (int filler = 30; filler <= 110; ++filler) {
    CAPTURE(filler);
    PdfDocumentSpec spec = WithFiller(filler);
    spec.blocks.push_back(Heading(1, "Conventions"));
    for (int i = 0; i < 6; ++i) spec.blocks.push_back(Bullet("Item " + std::to_string(i) + item));
    std::set<int> pages;
    for (const PlacedBox& b : WritePdfDocument(spec, "").boxes)
      if ((b.what == "paragraph" && b.text.rfind("•", 0) == 0) || (b.what == "heading" && b.text == "Conventions"))
        pages.insert(b.page);
    CHECK(pages.size() == 1);
  }
  // A list of 40 items (taller than a third of a page) breaks across pages,
  // but its last item goes with the one before it.
  int moved = 0;
  for (int filler = 0; filler <= 48; ++filler) {
    CAPTURE(filler);
    PdfDocumentSpec spec = WithFiller(filler);
    for (int i = 0; i < 40; ++i) spec.blocks.push_back(Bullet("Item " + std::to_string(i) + item));
    std::map<std::string, int> page;
    for (const PlacedBox& b : WritePdfDocument(spec, "").boxes)
      if (b.what == "paragraph") page[b.text] = b.page;
    REQUIRE(page.size() == static_cast<std::size_t>(filler) + 40);
    const int last = page["•\tItem 39" + item], before = page["•\tItem 38" + item];
    CHECK(last == before);
    if (page["•\tItem 37" + item] == before - 1) ++moved;
  }
  CHECK(moved >= 1);  // the case the rule exists for arose
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a number keeps its unit on its line: the space between them does not break") {
  const std::string nbsp = "\u00a0";
  CHECK(NumbersKeptWithUnits("RMS reaches 1.5 nm at 20.31 Hz") == "RMS reaches 1.5" + nbsp + "nm at 20.31" + nbsp + "Hz");
  CHECK(NumbersKeptWithUnits("12.07 µm/s, 81.1 %, 3 (two-sided)") ==
        "12.07" + nbsp + "µm/s, 81.1" + nbsp + "%, 3" + nbsp + "(two-sided)");
  // Words and numbers that follow words break as before; so does a number before a number or a sign.
  CHECK(NumbersKeptWithUnits("in 2 of 3 - 4 5") == "in 2" + nbsp + "of 3 - 4 5");
  CHECK(NumbersKeptWithUnits("no digits here") == "no digits here");
  CHECK(NumbersKeptWithUnits("ends with 7 ") == "ends with 7 ");
  // A unit of two factors stays whole (uncertainty.pdf's "N s/mm" broke after "N").
  CHECK(NumbersKeptWithUnits("c = 50 N s/mm and 2 µm s/K, 3 N m") ==
        "c = 50" + nbsp + "N" + nbsp + "s/mm and 2" + nbsp + "µm" + nbsp + "s/K, 3" + nbsp + "N m");
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("numbers in e-notation are set as powers of ten on the page") {
  CHECK(TypesetExponents("3.590e-04") == "3.590·10⁻⁴");  // wafer_stage's band table
  CHECK(TypesetExponents("k = 2.84245e+06 N/m") == "k = 2.84245·10⁶ N/m");
  CHECK(TypesetExponents("1e-12 and 6.144e-13 %") == "1·10⁻¹² and 6.144·10⁻¹³ %");
  CHECK(TypesetExponents("2e10") == "2·10¹⁰");
  // Powers after a caret (sensitivity.pdf's "variance [(µm/s)^2]", compare.pdf's "below 10^-6").
  CHECK(TypesetExponents("variance [(µm/s)^2], below 10^-6, |sinc(pi f T)|^2") ==
        "variance [(µm/s)²], below 10⁻⁶, |sinc(pi f T)|²");
  CHECK(TypesetExponents("a ^2, x^y, 2^3a") == "a ^2, x^y, 2^3a");
  CHECK(TypesetExponents("1.0e+00") == "1.0·10⁰");
  // Not numbers: identifiers, words, a bare 'e'.
  CHECK(TypesetExponents("path_1e3x, line e-4, 3e, 2e+, 5e-3b, mode_1e3, x2e-5") ==
        "path_1e3x, line e-4, 3e, 2e+, 5e-3b, mode_1e3, x2e-5");
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("contents of up to 30 lines stay whole on one page") {
  // wafer_stage's last two contents lines stood alone at the top of page 2.
  for (int filler = 20; filler <= 60; ++filler) {
    CAPTURE(filler);
    PdfDocumentSpec spec = WithFiller(filler);
    spec.blocks.push_back(Heading(1, "Contents"));
    spec.blocks.push_back(Contents());
    for (int s = 0; s < 10; ++s) {
      spec.blocks.push_back(Heading(1, "Section " + std::to_string(s)));
      spec.blocks.push_back(Paragraph("Text."));
    }
    std::set<int> pages;
    int heading_page = 0;
    for (const PlacedBox& b : WritePdfDocument(spec, "").boxes) {
      if (b.what == "contents") pages.insert(b.page);
      if (b.what == "heading" && b.text == "Contents") heading_page = b.page;
    }
    CHECK(pages.size() == 1);
    // Its heading goes along (wafer_stage's stood alone at the foot of page 1).
    CHECK(heading_page == *pages.begin());
  }
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a name too wide for its column breaks after an underscore, never hyphenated inside a word") {
  // sweep.pdf's variants table: a rank, two parameters and seven outputs
  // whose names are wider than their columns ("gamma_veloci-ty" before).
  PdfTable t;
  t.header = {"rank", "skyhook gain K_v [N/(mm/s)]", "isolator z position (-h) [mm]"};
  for (const char* name : {"x_velocity", "y_velocity", "z_velocity", "alpha_velocity", "beta_velocity",
                           "gamma_velocity", "measurement_to_position"})
    t.header.push_back(std::string(name) + " [µm/s]");
  t.numeric.assign(t.header.size(), true);
  for (int r = 0; r < 3; ++r) t.rows.push_back(std::vector<PdfCell>(t.header.size(), PdfCell("12.34")));
  PdfDocumentSpec spec;
  spec.create_date = "2026-01-01T00:00:00Z";
  spec.blocks.push_back(TableBlock("Variants", t));
  const fs::path dir = TempDir("pdf_names");
  WritePdfDocument(spec, (dir / "t.pdf").string());
  const Command text = Shell("pdftotext \"" + (dir / "t.pdf").string() + "\" -");
  if (text.exit_code == 0) {  // poppler-utils present
    // Each name's parts whole: broken, if at all, after an underscore.
    for (const char* part : {"gamma_", "velocity", "measurement_", "position"})
      CHECK_MESSAGE(text.out.find(part) != std::string::npos, part);
    CHECK(text.out.find("veloci-") == std::string::npos);
    CHECK(text.out.find("posi-") == std::string::npos);
    // A bracket without a space is not broken at its '/' or '-' ("[N/(mm/" "s)]" before).
    CHECK(text.out.find("[N/(mm/s)]") != std::string::npos);
    CHECK(text.out.find("(-h)") != std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace deb::report
