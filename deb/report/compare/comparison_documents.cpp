#include "deb/report/compare/comparison_documents.h"

#include <cmath>
#include <sstream>

#include "deb/report/budget/band_text.h"
#include "deb/version.h"

namespace deb::report {
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
  t.header = {"output", "A", "B", "B / A", "B is (unchanged: within 1 %)", "largest changes (variance change / total)"};
  t.numeric = {false, true, true, true, false, false};
  const std::vector<ComparedFigure> largest = cmp.LargestChanges();
  for (const ComparedFigure& f : cmp.figures) {
    if (f.contributor != "total" || !f.band.empty()) continue;
    std::string changes;
    for (const ComparedFigure& c : largest) {
      if (c.output != f.output || c.variance_change_of_total == 0.0) continue;
      const double pct = 100.0 * c.variance_change_of_total;
      // Below 0.01 % in size: "< 0.01 %" (compare.pdf had "+4.6·10⁻⁴ %").
      changes += (changes.empty() ? "" : ", ") + c.contributor + " " +
                 (std::abs(pct) < 0.01 ? std::string("< 0.01 %") : (pct > 0 ? "+" : "−") + Sig(std::abs(pct), 2) + " %");
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
    t.rows.push_back({f.contributor, f.band.empty() ? "whole grid" : BandText(f.band_lo_hz, f.band_hi_hz), Sig(f.rms_a, 4),
                      Sig(f.rms_b, 4), Sig(f.difference, 4), RatioText(f)});
    t.emphasis.push_back(std::vector<bool>(6, f.contributor == "total" && f.band.empty()));
  }
  Table largest;
  largest.title = "Contributors that changed most";
  largest.header = {"output", "contributor", "A", "B", "B / A", "variance change / total"};
  largest.numeric = {false, false, true, true, true, true};
  for (const ComparedFigure& f : cmp.LargestChanges())
    largest.rows.push_back({f.output, f.contributor, Sig(f.rms_a, 4), Sig(f.rms_b, 4), RatioText(f),
                            Share(f.variance_change_of_total, 1.0)});  // "< 0.01 %", not "4.57e-04 %"
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
      moved.rows.push_back({f.output, f.contributor, f.band.empty() ? "whole grid" : BandText(f.band_lo_hz, f.band_hi_hz), Sig(f.rms_a, 4),
                            Sig(f.rms_b, 4), RatioText(f)});
    if (moved.rows.empty()) moved.rows.push_back({"none", "", "", "", "", ""});
    tables.push_back(moved);
  }
  return tables;
}


StudyDocument ComparisonDocument(const Comparison& cmp, const std::vector<Plot>& plots) {
  StudyDocument d;
  d.title = "Comparison: " + cmp.label_a + " (A) vs " + cmp.label_b + " (B)";
  d.lead = "A is " + cmp.label_a + ", B is " + cmp.label_b +
           ". RMS per output, contributor and band; B − A in the output's unit, B / A, and the change of variance as "
           "a fraction of the output's larger total. A figure below 10⁻⁶ of its total's variance is negligible: it "
           "gets no ratio (\"from ≈0\", \"to ≈0\", \"–\").";
  d.footer = std::string("deb ") + DEB_VERSION + " · compare " + cmp.label_a + " (A) with " + cmp.label_b + " (B)";
  const std::vector<Table> tables = ComparisonTables(cmp);
  d.sections.push_back({"", "", {tables.front()}, {}, {}, false});
  d.sections.push_back({"Outputs", "", std::vector<Table>(tables.begin() + 1, tables.end()), {}, {}, false});
  if (!cmp.unmatched.empty()) d.sections.push_back({"Not compared", "", {}, {}, cmp.unmatched, false});
  if (!plots.empty()) {
    StudySection figures{"A and B overlaid, and B / A", "", {}, {}, {}, true};
    for (const Plot& p : plots) figures.figures.push_back(&p);
    d.sections.push_back(std::move(figures));
  }
  return d;
}

}  // namespace deb::report
