#include "deb/results/result_xlsx.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "deb/budget/allocation.h"
#include "deb/formats/xlsx_file.h"

namespace deb {
namespace {

using formats::XlsxStyle;
using formats::XlsxWorkbook;

// A sheet filled row by row, which widens each column to its longest text.
class Sheet {
 public:
  Sheet(XlsxWorkbook& book, const std::string& name) : book_(book), index_(book.AddSheet(name)) {}
  ~Sheet() = default;
  Sheet(const Sheet&) = delete;
  Sheet& operator=(const Sheet&) = delete;

  // A header row (bold, kept in view when it is the first).
  void Header(const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) Text(static_cast<int>(c), cells[c], XlsxStyle::kHeader);
    if (row_ == 0) book_.Freeze(index_, 1);
    Next();
  }
  void Text(int column, const std::string& text, XlsxStyle style = XlsxStyle::kPlain) {
    book_.Text(index_, row_, column, text, style);
    Widen(column, text.size());
  }
  void Number(int column, double value) {
    book_.Number(index_, row_, column, value);
    Widen(column, 12);  // as Excel's General format shows it
  }
  void Next() { ++row_; }
  // Sets the column widths (at most 50 characters).
  void Finish() {
    for (std::size_t c = 0; c < width_.size(); ++c)
      book_.ColumnWidth(index_, static_cast<int>(c), static_cast<int>(c),
                        std::min<double>(50.0, static_cast<double>(width_[c]) + 2.0));
  }

 private:
  void Widen(int column, std::size_t characters) {
    const std::size_t c = static_cast<std::size_t>(column);
    if (width_.size() <= c) width_.resize(c + 1, 8);
    width_[c] = std::max(width_[c], characters);
  }
  XlsxWorkbook& book_;
  int index_;
  int row_ = 0;
  std::vector<std::size_t> width_;
};

// Contributors largest first (by variance), ties in budget order.
std::vector<std::size_t> LargestFirst(const OutputResult& o) {
  std::vector<std::size_t> order(o.contributors.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&o](std::size_t a, std::size_t b) {
    return o.contributors[a].variance > o.contributors[b].variance;
  });
  return order;
}

double Percent(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

bool HasRequirement(const OutputResult& o) { return o.rms_max.has_value() || !o.band_requirements.empty(); }

void SummarySheet(XlsxWorkbook& book, const BudgetResult& result, const std::string& name) {
  Sheet s(book, name);
  s.Header({"Output", "Unit", "RMS [output unit]", "Requirement rms_max [output unit]", "Verdict",
            "Failing band requirements", "Largest contributor", "Largest share [%]"});
  for (const OutputResult& o : result.outputs) {
    s.Text(0, o.name);
    s.Text(1, o.unit);
    s.Number(2, o.rms());
    if (o.rms_max) s.Number(3, *o.rms_max);
    if (HasRequirement(o))
      s.Text(4, o.AllPass() ? "PASS" : "FAIL", o.AllPass() ? XlsxStyle::kPass : XlsxStyle::kFail);
    else
      s.Text(4, "no requirement");
    std::size_t failing = 0;
    for (const BandRequirementResult& b : o.band_requirements) failing += b.pass() ? 0 : 1;
    s.Number(5, static_cast<double>(failing));
    if (!o.contributors.empty()) {
      const ContributorResult& c = o.contributors[LargestFirst(o).front()];
      s.Text(6, c.name);
      s.Number(7, Percent(c.variance, o.variance));
    }
    s.Next();
  }
  s.Finish();
}

void ContributorSheet(XlsxWorkbook& book, const OutputResult& o, const std::string& name) {
  Sheet s(book, name);
  const std::string u = " [" + o.unit + "]", u2 = " [" + o.unit + "^2]";
  std::vector<std::string> header = {"Contributor", "Group", "Source", "Path", "RMS" + u, "Share [%]",
                                     "Variance" + u2, "Exact variance" + u2, "Exact RMS" + u};
  if (o.rms_max) header.push_back("Allocation factor k (on the source PSD)");
  s.Header(header);
  for (const std::size_t i : LargestFirst(o)) {
    const ContributorResult& c = o.contributors[i];
    s.Text(0, c.name);
    s.Text(1, c.group);
    s.Text(2, c.source);
    s.Text(3, c.path);
    s.Number(4, std::sqrt(c.variance));
    s.Number(5, Percent(c.variance, o.variance));
    s.Number(6, c.variance);
    if (c.exact_variance) {
      s.Number(7, *c.exact_variance);
      s.Number(8, std::sqrt(*c.exact_variance));
    }
    if (o.rms_max) {
      // Empty where there is none (summary.json's allocation_note says why).
      if (const Allocation a = AllocationFactor(o, i); a.factor) s.Number(9, *a.factor);
    }
    s.Next();
  }
  s.Text(0, "total", XlsxStyle::kHeader);
  s.Number(4, o.rms());
  s.Number(5, o.variance > 0 ? 100.0 : 0.0);
  s.Number(6, o.variance);
  s.Next();
  s.Finish();
}

void BandSheet(XlsxWorkbook& book, const OutputResult& o, const std::string& name) {
  Sheet s(book, name);
  const std::string u = " [" + o.unit + "]";
  std::vector<std::string> header = {"Band low [Hz]", "Band high [Hz]", "Total RMS" + u};
  for (const ContributorResult& c : o.contributors) header.push_back(c.name + " RMS" + u);
  s.Header(header);
  for (const BandResult& b : o.bands) {
    s.Number(0, b.band.lo_hz);
    s.Number(1, b.band.hi_hz);
    s.Number(2, std::sqrt(b.variance));
    for (std::size_t c = 0; c < o.contributors.size(); ++c)
      s.Number(3 + static_cast<int>(c), std::sqrt(std::max(b.contributor_variance[c], 0.0)));
    s.Next();
  }
  if (!o.band_requirements.empty()) {
    s.Next();
    s.Header({"Requirement low [Hz]", "Requirement high [Hz]", "RMS" + u, "rms_max" + u, "Verdict"});
    for (const BandRequirementResult& b : o.band_requirements) {
      s.Number(0, b.requirement.lo_hz);
      s.Number(1, b.requirement.hi_hz);
      s.Number(2, b.rms());
      s.Number(3, b.requirement.rms_max);
      s.Text(4, b.pass() ? "PASS" : "FAIL", b.pass() ? XlsxStyle::kPass : XlsxStyle::kFail);
      s.Next();
    }
  }
  s.Finish();
}

void TraceSheet(XlsxWorkbook& book, const BudgetResult& result, const OutputResult& o, const std::string& name) {
  Sheet s(book, name);
  const std::string psd = " [" + o.unit + "^2/Hz]", cps = " [" + o.unit + "^2]";
  const int m = static_cast<int>(o.contributors.size());
  std::vector<std::string> header = {"f [Hz]", "Total PSD" + psd};
  for (const ContributorResult& c : o.contributors) header.push_back("PSD " + c.name + psd);
  header.push_back("Total CPS" + cps);
  for (const ContributorResult& c : o.contributors) header.push_back("CPS " + c.name + cps);
  s.Header(header);
  const std::vector<double>& f_hz = result.grid.f_hz();
  for (std::size_t i = 0; i < f_hz.size(); ++i) {
    s.Number(0, f_hz[i]);
    s.Number(1, o.total_psd[i]);
    for (int c = 0; c < m; ++c) s.Number(2 + c, o.contributors[static_cast<std::size_t>(c)].psd[i]);
    s.Number(2 + m, o.total_cps[i]);
    for (int c = 0; c < m; ++c) s.Number(3 + m + c, o.contributors[static_cast<std::size_t>(c)].cps[i]);
    s.Next();
  }
  s.Finish();
}

}  // namespace

void WriteResultXlsx(const BudgetResult& result, const std::string& file) {
  XlsxWorkbook book(file);
  std::vector<std::string> taken;
  SummarySheet(book, result, formats::XlsxSheetName("Summary", "", taken));
  for (const OutputResult& o : result.outputs) {
    // Named before any is filled, so that an output called "Summary" gets "Summary~2".
    const std::string contributors = formats::XlsxSheetName(o.name, "", taken);
    const std::string bands = formats::XlsxSheetName(o.name, " bands", taken);
    const std::string traces = formats::XlsxSheetName(o.name, " traces", taken);
    ContributorSheet(book, o, contributors);
    BandSheet(book, o, bands);
    TraceSheet(book, result, o, traces);
  }
  book.Close();
}

}  // namespace deb
