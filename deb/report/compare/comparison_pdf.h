// Internal: not part of the public API.
// compare.pdf: the comparison of `deb compare` as a typeset document (the
// same module as report.pdf, pdf_document.h): the headline table (per
// output A, B, B / A, better or worse, the largest changes), one table per
// output, and the overlay figures of A and B with their captions.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/report/document/pdf_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// `figure_dir` holds <plot name>.svg for every plot, drawn with
// PdfFigureTerminal; `create_date` as PdfDocumentSpec's.
PdfDocumentSpec ComparisonPdfSpec(const Comparison& cmp, const std::vector<Plot>& plots,
                                  const std::string& figure_dir, const std::string& create_date);

// Draws the plots' SVGs into plots_dir/.pdf_figures (the plots' .gp and .csv
// already written there), writes compare.pdf at `pdf_path` and removes the
// SVGs. @throws WriteError as WritePdfDocument and RunGnuplot.
void WriteComparisonPdf(const Comparison& cmp, const std::vector<Plot>& plots, const std::string& plots_dir,
                        const std::string& pdf_path, int threads);

}  // namespace deb::report
