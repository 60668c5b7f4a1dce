// Internal: not part of the public API.
// A typeset A4 document as data, and the one module that draws it (cairo for
// the PDF, pango for text, librsvg for figures given as SVG files). The
// caller lists blocks top to bottom (headings, paragraphs, tables, figures,
// a table of contents); the layout breaks them into pages inside a
// printable margin, numbers the pages in every footer, turns headings into
// the PDF's outline (bookmarks) and link targets, and links the table of
// contents to them. The layout is returned as data (every placed box with
// its page) so that tests can check it without reading the PDF.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace deb::report {

// A4 in points (1/72 in) and the margin every box stays inside: 18 mm, more
// than the 15 mm an office printer leaves.
constexpr double kPageWidthPt = 595.2756, kPageHeightPt = 841.8898;
constexpr double kMarginPt = 18.0 / 25.4 * 72.0;

struct PdfCell {
  PdfCell(std::string text_ = "", bool bold_ = false, bool alert_ = false, std::string link_ = "")
      : text(std::move(text_)), bold(bold_), alert(alert_), link(std::move(link_)) {}
  std::string text;  // may hold line breaks; long text wraps in its column
  bool bold = false;
  bool alert = false;  // drawn in red (a failed requirement)
  bool good = false;   // drawn in green (a met requirement)
  std::string link;    // the text of a heading the cell links to; "" for none
};

struct PdfTable {
  std::vector<std::string> header;  // empty: no header row
  std::vector<bool> numeric;        // per column: aligned on the decimal point
  std::vector<std::vector<PdfCell>> rows;
  std::vector<std::string> footnotes;  // set below the table, one paragraph each
  bool boxed = false;                  // a framed, shaded box (the verdict)
};

enum class PdfBlockKind { kHeading, kParagraph, kTable, kFigure, kContents, kPageBreak };

struct PdfBlock {
  PdfBlockKind kind = PdfBlockKind::kParagraph;
  std::string text;   // heading, paragraph, a table's title, a figure's caption
  int level = 1;      // heading: 0 title (not in the outline), 1 section, 2 subsection
  double size_pt = 9.5;  // paragraph
  bool bold = false, alert = false, good = false;  // paragraph: red, green
  bool bullet = false;               // paragraph: an item of a list, "• " and a hanging indent
  PdfTable table;
  std::string svg_file;  // figure: drawn as vectors across the text width
  // figure: its canvas, when the layout is planned before the SVG is drawn
  // (0: the SVG file's own size).
  int width_px = 0, height_px = 0;
  // figure: where it does not fit below the cursor, the least height (px of
  // its canvas) it may be drawn at, across the text width, to stay on the
  // page rather than leave the rest of it empty (0: never shorter). The
  // layout places it as tall as the room left; the caller then draws it at
  // that height (FittedFigureHeightsPx) and typesets the document again.
  int min_height_px = 0;
  double unless_room_pt = 0.0;  // page break: none when at least this much of the page is left (0: always)
};

// Starts `kind` blocks: Heading(1, "Overview"), Paragraph("..."), ...
PdfBlock Heading(int level, std::string text);
PdfBlock Paragraph(std::string text, double size_pt = 9.5, bool bold = false, bool alert = false, bool good = false);
PdfBlock Bullet(std::string text);
PdfBlock TableBlock(std::string title, PdfTable table);
PdfBlock Figure(std::string svg_file, std::string caption);
PdfBlock Contents();
// A new page; with `unless_room_pt` > 0, only when less than that is left
// below the cursor (a section that may start low on a page rather than
// leave it half empty).
PdfBlock PageBreak(double unless_room_pt = 0.0);

struct PdfDocumentSpec {
  std::string title, subject;  // the PDF's metadata
  std::string footer;          // left of every page's footer; "page n/N" goes right
  std::string create_date;     // ISO 8601 "YYYY-MM-DDThh:mm:ssZ": the same bytes for the same input
  std::string font = "DejaVu Sans";
  std::vector<PdfBlock> blocks;
};

// Where the layout put something: a box in points from the page's top left.
struct PlacedBox {
  int page = 0;  // 1-based
  std::string what;  // "heading", "paragraph", "table row", "figure", "caption", "footer", ...
  std::string text;  // its text (a table row: the cells joined by " | ")
  double x_pt = 0, y_pt = 0, width_pt = 0, height_pt = 0;
  std::string colour;  // "#rrggbb" of the text, for cells and paragraphs
  double point_x_pt = 0;  // a cell of a numeric column: x of its decimal point (or where it would be)
};

struct OutlineEntry {
  int level = 1;
  std::string text;
  int page = 0;
};

struct PdfLayout {
  int pages = 0;
  std::vector<PlacedBox> boxes;
  std::vector<OutlineEntry> outline;  // the headings of level >= 1, in order
};

// Lays out `spec` and writes it as a PDF to `path` (empty: lay out only).
// @throws WriteError if the file or a figure's SVG cannot be read or written.
PdfLayout WritePdfDocument(const PdfDocumentSpec& spec, const std::string& path);

// The layout of `spec` in one pass, without the page numbers the table of
// contents and the footers get (placeholders of the same height): where
// every block lands, which is what planning the figures needs, at half
// WritePdfDocument(spec, "")'s cost.
PdfLayout PlanPdfDocument(const PdfDocumentSpec& spec);

// After a layout of `spec` planned with figure canvases (width_px and
// height_px set): per figure block, in order, the height in px it was
// placed at (its height_px, or less where min_height_px let it stay on a
// page), rounded down to a whole px so that the figure drawn at it fits.
std::vector<int> FittedFigureHeightsPx(const PdfDocumentSpec& spec, const PdfLayout& layout);

// `text` with the space between a number and the word after it (a unit,
// "%", "Hz", "outputs") no-breaking (U+00A0): every text the document sets
// goes through it, so that a line break never parts "1.5" from "nm"; and
// so is the space after a short symbol that follows a number when the word
// after it holds a '/' (a unit of two factors: "50 N s/mm").
std::string NumbersKeptWithUnits(const std::string& text);
// `text` with a number's e-notation set as a power of ten, "3.590e-04" as
// "3.590·10⁻⁴", and a caret's power as superscript, "(µm/s)^2" as "(µm/s)²",
// "10^-6" as "10⁻⁶", as every text the document sets.
std::string TypesetExponents(const std::string& text);

}  // namespace deb::report
