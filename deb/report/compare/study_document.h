// Internal: not part of the public API.
// The documents of a study (deb compare, deb sweep, deb sensitivity): one
// model written three ways, as Markdown, as one self-contained HTML page and
// as a typeset A4 PDF (pdf_document.h, the module of report.pdf), so that
// the three say the same thing in the same order. A document is a title, a
// lead paragraph and sections; a section has a heading, a paragraph, tables,
// figures (drawn as plots/<name>.png beside the page, and as SVG for the
// PDF) and bullets.
#pragma once

#include <string>
#include <vector>

#include "deb/report/budget/report_tables.h"
#include "deb/report/document/pdf_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

inline constexpr double kStudySectionRoomPt = 200.0;

struct StudySection {
  std::string heading;  // "" : none (the part under the title)
  std::string text;     // a paragraph, or ""
  std::vector<Table> tables;
  std::vector<const Plot*> figures;  // each with its caption; the plots outlive the document
  std::vector<std::string> bullets;
  // In the PDF, the section starts a page unless kStudySectionRoomPt are
  // left (its heading then moves on with its first figure if that does not
  // fit): compare.pdf's figures had left 60 % of a page empty.
  bool new_page = false;
};

struct StudyDocument {
  std::string title;   // the page's and the PDF's title
  std::string lead;    // the paragraph under the title
  std::string footer;  // the PDF's page footer, left of "page n/N"
  Table sources;       // under the lead, where rows: what the study was made from (StampSources)
  std::vector<StudySection> sections;
};

// What a study was made from: a budget file or result directory as given
// to the command, under a role ("budget", "A", "B"), with the SHA-256 of its
// budget file (a result directory's as its summary.json records it; "" where
// unknown).
struct StudySource {
  std::string role, path, sha256;
};
// Sets doc's sources: each source with its digest ("–" where unknown), and
// the date the document is written (DocumentTime); the footer gains each
// known digest's first 12 digits (with its role where there are several),
// as a run report's does: the same study, the same name on every page.
void StampSources(StudyDocument* doc, const std::vector<StudySource>& sources);

std::string StudyMarkdown(const StudyDocument& doc);
std::string StudyHtml(const StudyDocument& doc);

// `figure_dir` holds <plot name>.svg for every figure, drawn with
// PdfFigureTerminal; `create_date` as PdfDocumentSpec's.
PdfDocumentSpec StudyPdfSpec(const StudyDocument& doc, const std::string& figure_dir, const std::string& create_date);

// Draws each figure's SVG into plots_dir/.pdf_figures (the plots' .gp and
// .csv already written there), writes the PDF at `pdf_path` and removes the
// SVGs. @throws WriteError as WritePdfDocument and RunGnuplot.
void WriteStudyPdf(const StudyDocument& doc, const std::string& plots_dir, const std::string& pdf_path, int threads);

}  // namespace deb::report
