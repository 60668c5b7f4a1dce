#include "deb/report/compare/comparison_pdf.h"

#include <cstdlib>
#include <ctime>
#include <filesystem>

#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/report/budget/report_pdf.h"
#include "deb/report/compare/comparison_documents.h"
#include "deb/report/figure/gnuplot_runner.h"
#include "deb/version.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;

}  // namespace

PdfDocumentSpec ComparisonPdfSpec(const Comparison& cmp, const std::vector<Plot>& plots,
                                  const std::string& figure_dir, const std::string& create_date) {
  PdfDocumentSpec s;
  s.title = cmp.label_a + " vs " + cmp.label_b;
  s.subject = "deb compare: " + s.title;
  s.footer = std::string("deb ") + DEB_VERSION + " · compare " + cmp.label_a + " (A) with " + cmp.label_b + " (B)";
  s.create_date = create_date;
  std::vector<PdfBlock>& b = s.blocks;
  b.push_back(Heading(0, s.title));
  b.push_back(Paragraph("A is " + cmp.label_a + ", B is " + cmp.label_b +
                        ". RMS per output, contributor and band; B − A, B / A, and the change of variance as a "
                        "fraction of the output's larger total. A figure below 10⁻⁶ of its total's variance is "
                        "negligible: it gets no ratio (\"from ≈0\", \"to ≈0\", \"–\")."));
  const std::vector<Table> tables = ComparisonTables(cmp);
  for (std::size_t i = 0; i < tables.size(); ++i) {
    if (i == 1) b.push_back(Heading(1, "Outputs"));
    b.push_back(TableBlock(tables[i].title, TypesetTable(tables[i])));
  }
  if (!cmp.unmatched.empty()) {
    b.push_back(Heading(1, "Not compared"));
    for (const std::string& u : cmp.unmatched) b.push_back(Bullet(u));
  }
  if (!plots.empty()) {
    b.push_back(PageBreak());
    b.push_back(Heading(1, "A and B overlaid"));
    for (const Plot& p : plots) b.push_back(Figure((fs::path(figure_dir) / (p.name + ".svg")).string(), p.caption));
  }
  return s;
}

void WriteComparisonPdf(const Comparison& cmp, const std::vector<Plot>& plots, const std::string& plots_dir,
                        const std::string& pdf_path, int threads) {
  const std::string figures = ".pdf_figures";
  const fs::path figure_dir = fs::path(plots_dir) / figures;
  if (!plots.empty()) {
    std::error_code ec;
    fs::create_directories(figure_dir, ec);
    if (ec) throw WriteError("cannot create directory " + figure_dir.string() + ": " + ec.message());
    const std::string gnuplot = FindGnuplot("");
    ParallelForEach(
        plots.size(),
        [&](std::size_t i) {
          const Plot& p = plots[i];
          RunGnuplot(gnuplot, plots_dir,
                     PdfFigureTerminal(p.kind) + "set output " + QuoteFile(figures + "/" + p.name + ".svg") + "\nload " +
                         QuoteFile(p.name + ".gp") + "\nunset output\n",
                     "the figure of compare.pdf " + p.name);
        },
        threads);
  }
  WritePdfDocument(ComparisonPdfSpec(cmp, plots, figure_dir.string(), UtcText(DocumentTime(), "%Y-%m-%dT%H:%M:%SZ")), pdf_path);
  std::error_code ec;
  fs::remove_all(figure_dir, ec);  // deb wrote it, inside the staged directory
}

}  // namespace deb::report
