// Internal: not part of the public API.
// The first page(s) of report.pdf: what was computed from which file, when
// and by which deb, the conventions, and the tables, set as text by gnuplot
// (the PDF is drawn by gnuplot alone). Text that does not fit on one A4
// landscape page continues on the next, so the page count is known here.
#pragma once

#include <string>
#include <vector>

#include "deb/report/report_tables.h"

namespace deb::report {

struct TitlePages {
  std::string script;  // gnuplot commands; each page ends with one `plot`
  int pages = 0;
};

// `tables` are set in order after the facts and conventions; `warnings`
// follow them. Each page's footer is PageFooter(budget_name, digest, k, N),
// N = the title pages + `following_pages` (the plot pages after them).
TitlePages MakeTitlePages(const std::string& budget_name, const std::string& description, const ReportFacts& facts,
                          const std::vector<Table>& tables, const std::vector<std::string>& warnings,
                          int following_pages = 0, const std::string& digest = "");

// "deb VERSION · BUDGET · SHA-256 0123456789ab · page K/N" (the digest part
// only when given): a loose printout names its budget file and its place.
std::string PageFooter(const std::string& budget_name, const std::string& digest, int page, int total_pages);

// `text` broken at spaces into lines of at most `width` characters.
std::vector<std::string> Wrap(const std::string& text, std::size_t width);

}  // namespace deb::report
