// Internal: not part of the public API.
// The two readable documents of a report directory: index.html, one
// self-contained page (inline CSS, its figures drawn by inline scripts from
// inline data, nothing fetched from the network; interactive_figures.h) for
// a browser, and report.md with the same sections and tables (images by
// relative path) for terminals and repositories.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

struct DocumentInputs {
  const BudgetResult* result = nullptr;
  ReportFacts facts;
  std::vector<Plot> plots;            // in report order
  std::string image_extension;        // "png", "svg", or "" for no images
  bool pdf = false;                   // report.pdf exists
  bool asd = false;                   // index.html's spectra open as ASD
  std::vector<std::string> data_files;  // summary.json, output CSVs: relative paths that exist
  int digits = 4;                       // significant digits of the tables (ReportOptions::digits)
};

std::string IndexHtml(const DocumentInputs& in);
std::string ReportMarkdown(const DocumentInputs& in);

// The anchor of an output's section, e.g. "output-z_velocity".
std::string OutputAnchor(const std::string& output_name);

}  // namespace deb::report
