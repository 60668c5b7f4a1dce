#include "deb/report/compare/comparison_documents.h"

#include <cmath>
#include <sstream>

namespace deb::report {
namespace {

std::string Lead() {
  return "RMS per output, contributor and band; difference B − A in the output's unit; ratio B / A.";
}

}  // namespace

std::string RatioText(const ComparedFigure& f) {
  if (f.ratio) return Sig(*f.ratio, 4);
  if (f.negligible_a && !f.negligible_b) return "from ≈0";
  if (f.negligible_b && !f.negligible_a) return "to ≈0";
  return "–";
}

std::string Verdict(const ComparedFigure& total) {
  if (!total.ratio) return total.negligible_a && !total.negligible_b ? "worse" : "–";
  if (std::abs(*total.ratio - 1.0) < kUnchangedRel) return "unchanged";
  return *total.ratio < 1.0 ? "better" : "worse";
}

Table HeadlineTable(const Comparison& cmp) {
  Table t;
  t.title = "Headline: total RMS per output, A: " + cmp.label_a + ", B: " + cmp.label_b;
  t.header = {"output", "A", "B", "B / A", "B is", "largest changes (variance change / total)"};
  t.numeric = {false, true, true, true, false, false};
  const std::vector<ComparedFigure> largest = cmp.LargestChanges();
  for (const ComparedFigure& f : cmp.figures) {
    if (f.contributor != "total" || !f.band.empty()) continue;
    std::string changes;
    for (const ComparedFigure& c : largest) {
      if (c.output != f.output || c.variance_change_of_total == 0.0) continue;
      const double pct = 100.0 * c.variance_change_of_total;
      changes += (changes.empty() ? "" : ", ") + c.contributor + " " + (pct > 0 ? "+" : "−") + Sig(std::abs(pct), 2) +
                 " %";
    }
    t.rows.push_back({f.output + " [" + UnitText(f.unit) + "]", Sig(f.rms_a, 4), Sig(f.rms_b, 4), RatioText(f),
                      Verdict(f), changes.empty() ? "none" : changes});
  }
  return t;
}

// The tables of a comparison: the headline, one per output, then the largest changes.
std::vector<Table> ComparisonTables(const Comparison& cmp) {
  std::vector<Table> tables = {HeadlineTable(cmp)};
  std::string current;
  for (const ComparedFigure& f : cmp.figures) {
    if (tables.size() == 1 || f.output != current) {
      current = f.output;
      Table t;
      t.title = f.output + " [" + UnitText(f.unit) + "]";
      t.header = {"contributor", "band", "A: " + cmp.label_a, "B: " + cmp.label_b, "B − A", "B / A"};
      t.numeric = {false, false, true, true, true, true};
      tables.push_back(t);
    }
    Table& t = tables.back();
    t.rows.push_back({f.contributor, f.band.empty() ? "whole grid" : f.band, Sig(f.rms_a, 4),
                      Sig(f.rms_b, 4), Sig(f.difference, 4), RatioText(f)});
    t.emphasis.push_back(std::vector<bool>(6, f.contributor == "total" && f.band.empty()));
  }
  Table largest;
  largest.title = "Contributors that changed most";
  largest.header = {"output", "contributor", "A", "B", "B / A", "variance change / total"};
  largest.numeric = {false, false, true, true, true, true};
  for (const ComparedFigure& f : cmp.LargestChanges())
    largest.rows.push_back({f.output, f.contributor, Sig(f.rms_a, 4), Sig(f.rms_b, 4), RatioText(f),
                            Sig(100.0 * f.variance_change_of_total, 3) + " %"});
  tables.push_back(largest);
  if (!cmp.parameters.empty()) {
    Table changed;
    changed.title = "Parameters that differ";
    changed.header = {"parameter", "A: " + cmp.label_a, "B: " + cmp.label_b};
    changed.numeric = {false, false, false};
    for (const ParameterChange& p : cmp.parameters)
      changed.rows.push_back({p.name, p.a.empty() ? "–" : p.a, p.b.empty() ? "–" : p.b});
    tables.push_back(changed);
  }
  if (cmp.tolerance) {
    Table moved;
    moved.title = "Moved by more than " + Sig(100.0 * *cmp.tolerance, 3) + " % (--tolerance)";
    moved.header = {"output", "contributor", "band", "A", "B", "B / A"};
    moved.numeric = {false, false, false, true, true, true};
    for (const ComparedFigure& f : cmp.Moved(*cmp.tolerance))
      moved.rows.push_back({f.output, f.contributor, f.band.empty() ? "whole grid" : f.band, Sig(f.rms_a, 4),
                            Sig(f.rms_b, 4), RatioText(f)});
    if (moved.rows.empty()) moved.rows.push_back({"none", "", "", "", "", ""});
    tables.push_back(moved);
  }
  return tables;
}


std::string ComparisonMarkdown(const Comparison& cmp, const std::vector<Plot>& plots) {
  std::ostringstream md;
  md << "# Comparison: " << cmp.label_a << " (A) vs " << cmp.label_b << " (B)\n\n" << Lead() << "\n\n";
  for (const Table& t : ComparisonTables(cmp)) md << "## " << t.title << "\n\n" << ToMarkdown(t) << "\n";
  for (const Plot& p : plots)
    md << "![" << p.caption << "](plots/" << p.name << ".png)\n\n" << p.caption << "\n\n";
  if (!cmp.unmatched.empty()) {
    md << "## Not compared\n\n";
    for (const std::string& s : cmp.unmatched) md << "- " << s << "\n";
  }
  return md.str();
}

// One self-contained page (the plots are files beside it).
std::string ComparisonHtml(const Comparison& cmp, const std::vector<Plot>& plots) {
  std::ostringstream h;
  const std::string title = "Comparison: " + cmp.label_a + " (A) vs " + cmp.label_b + " (B)";
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << HtmlEscape(title)
    << "</title>\n<style>body{font-family:'DejaVu Sans',sans-serif;max-width:1240px;margin:2rem auto;padding:0 1.5rem}"
       "table{border-collapse:collapse;margin:.6rem 0 1.4rem;font-size:.92rem}th,td{border-bottom:1px solid #ddd;"
       "padding:.2rem .6rem}td.num{text-align:right;font-variant-numeric:tabular-nums}img{max-width:100%}</style>\n"
       "</head>\n<body>\n<h1>"
    << HtmlEscape(title) << "</h1>\n<p>" << HtmlEscape(Lead()) << "</p>\n";
  for (const Table& t : ComparisonTables(cmp)) h << ToHtml(t);  // the caption titles it
  for (const Plot& p : plots)
    h << "<figure><img src=\"plots/" << HtmlEscape(p.name) << ".png\" alt=\"" << HtmlEscape(p.caption)
      << "\"><figcaption>" << HtmlEscape(p.caption) << "</figcaption></figure>\n";
  if (!cmp.unmatched.empty()) {
    h << "<h2>Not compared</h2>\n<ul>\n";
    for (const std::string& s : cmp.unmatched) h << "<li>" << HtmlEscape(s) << "</li>\n";
    h << "</ul>\n";
  }
  h << "</body>\n</html>\n";
  return h.str();
}

}  // namespace deb::report
