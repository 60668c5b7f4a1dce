#include "deb/report/compare/study_document.h"

#include <filesystem>
#include <map>
#include <sstream>
#include <vector>

#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/report/budget/report_pdf.h"
#include "deb/report/figure/gnuplot_runner.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;

constexpr const char* kStyle =
    "body{font-family:'DejaVu Sans',sans-serif;max-width:1240px;margin:2rem auto;padding:0 1.5rem}"
    "table{border-collapse:collapse;margin:.6rem 0 1.4rem;font-size:.92rem}th,td{border-bottom:1px solid #ddd;"
    "padding:.2rem .6rem}td.num{text-align:right;font-variant-numeric:tabular-nums}"
    "td.notes{color:#555;font-size:.85rem}img{max-width:100%}";

}  // namespace

void StampSources(StudyDocument* doc, const std::vector<StudySource>& sources) {
  Table& t = doc->sources;
  t = Table();
  t.numeric = {false, false};
  std::vector<std::string> digests;  // each known one's first 12 digits, with its role where there are several
  for (const StudySource& s : sources) {
    const std::string digest = s.sha256.empty() ? "–" : s.sha256;
    if (!s.sha256.empty()) digests.push_back((sources.size() > 1 ? s.role + " " : "") + digest.substr(0, 12));
    t.rows.push_back({s.role, s.path});
    t.rows.push_back({"", "SHA-256 " + digest});
  }
  t.rows.push_back({"date", UtcText(DocumentTime(), "%Y-%m-%d %H:%M:%S UTC")});
  // Every page names what the study was made from: compare's A and B both.
  for (std::size_t i = 0; i < digests.size(); ++i) doc->footer += (i == 0 ? " · SHA-256 " : ", ") + digests[i];
}

std::string StudyMarkdown(const StudyDocument& doc) {
  std::ostringstream md;
  md << "# " << doc.title << "\n\n" << doc.lead << "\n\n";
  if (!doc.sources.rows.empty()) md << ToMarkdown(doc.sources) << "\n";
  for (const StudySection& s : doc.sections) {
    if (!s.heading.empty()) md << "## " << s.heading << "\n\n";
    if (!s.text.empty()) md << s.text << "\n\n";
    for (const Table& t : s.tables) md << "## " << t.title << "\n\n" << ToMarkdown(t) << "\n";
    for (const Plot* p : s.figures)
      md << "![" << p->caption << "](plots/" << p->name << ".png)\n\n" << p->caption << "\n\n";
    for (const std::string& b : s.bullets) md << "- " << b << "\n";
    if (!s.bullets.empty()) md << "\n";
  }
  return md.str();
}

std::string StudyHtml(const StudyDocument& doc) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << HtmlEscape(doc.title)
    << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<h1>" << HtmlEscape(doc.title) << "</h1>\n<p>"
    << HtmlEscape(doc.lead) << "</p>\n";
  if (!doc.sources.rows.empty()) h << ToHtml(doc.sources);
  for (const StudySection& s : doc.sections) {
    if (!s.heading.empty()) h << "<h2>" << HtmlEscape(s.heading) << "</h2>\n";
    if (!s.text.empty()) h << "<p>" << HtmlEscape(s.text) << "</p>\n";
    for (const Table& t : s.tables) h << ToHtml(t);  // its caption titles it
    for (const Plot* p : s.figures)
      h << "<figure><img src=\"plots/" << HtmlEscape(p->name) << ".png\" alt=\"" << HtmlEscape(p->caption)
        << "\"><figcaption>" << HtmlEscape(p->caption) << "</figcaption></figure>\n";
    if (!s.bullets.empty()) {
      h << "<ul>\n";
      for (const std::string& b : s.bullets) h << "<li>" << HtmlEscape(b) << "</li>\n";
      h << "</ul>\n";
    }
  }
  h << "</body>\n</html>\n";
  return h.str();
}

PdfDocumentSpec StudyPdfSpec(const StudyDocument& doc, const std::string& figure_dir, const std::string& create_date) {
  PdfDocumentSpec spec;
  spec.title = doc.title;
  spec.subject = doc.title;
  spec.footer = doc.footer;
  spec.create_date = create_date;
  std::vector<PdfBlock>& b = spec.blocks;
  b.push_back(Heading(0, doc.title));
  b.push_back(Paragraph(doc.lead));
  if (!doc.sources.rows.empty()) b.push_back(TableBlock("", TypesetTable(doc.sources)));
  for (const StudySection& s : doc.sections) {
    if (s.new_page) b.push_back(PageBreak(kStudySectionRoomPt));
    if (!s.heading.empty()) b.push_back(Heading(1, s.heading));
    if (!s.text.empty()) b.push_back(Paragraph(s.text));
    for (const Table& t : s.tables) b.push_back(TableBlock(t.title, TypesetTable(t)));
    for (const Plot* p : s.figures) b.push_back(FigureOfPlot(*p, figure_dir));
    for (const std::string& text : s.bullets) b.push_back(Bullet(text));
  }
  return spec;
}

void WriteStudyPdf(const StudyDocument& given, const std::string& plots_dir, const std::string& pdf_path,
                   int threads) {
  const fs::path figure_dir = fs::path(plots_dir) / kPdfFigureDir;
  const std::string create_date = UtcText(DocumentTime(), "%Y-%m-%dT%H:%M:%SZ");
  // Each figure drawn at the height that keeps it on its page, where a
  // little shorter does (FittedFigureHeights): the document then points at
  // copies of its plots with those heights.
  const std::map<std::string, int> fitted =
      FittedFigureHeights(StudyPdfSpec(given, figure_dir.string(), create_date));
  StudyDocument doc = given;
  std::size_t n = 0;
  for (const StudySection& s : doc.sections) n += s.figures.size();
  std::vector<Plot> copies;
  copies.reserve(n);  // no reallocation: the sections point into it
  for (StudySection& s : doc.sections)
    for (const Plot*& p : s.figures) {
      copies.push_back(*p);
      if (const auto it = fitted.find(p->name); it != fitted.end()) copies.back().pdf_height_px = it->second;
      p = &copies.back();
    }
  std::vector<const Plot*> figures;
  for (const StudySection& s : doc.sections) figures.insert(figures.end(), s.figures.begin(), s.figures.end());
  if (!figures.empty()) {
    std::error_code ec;
    fs::create_directories(figure_dir, ec);
    if (ec) throw WriteError("cannot create directory " + figure_dir.string() + ": " + ec.message());
    const std::string gnuplot = FindGnuplot("");
    ParallelForEach(
        figures.size(),
        [&](std::size_t i) {
          const Plot& p = *figures[i];
          RunGnuplot(gnuplot, plots_dir, PdfFigureCommands(p),
                     "the figure " + p.name + " of " + fs::path(pdf_path).filename().string());
        },
        threads);
  }
  WritePdfDocument(StudyPdfSpec(doc, figure_dir.string(), create_date), pdf_path);
  std::error_code ec;
  fs::remove_all(figure_dir, ec);  // deb wrote it, inside the staged directory
}

}  // namespace deb::report
