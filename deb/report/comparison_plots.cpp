#include "deb/report/comparison_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/report/plot_style.h"
#include "deb/report/spectrum_plots.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr const char* kBarEdge = "#303030";
constexpr std::size_t kPanelsPerPage = 8;

std::string Col(std::size_t column) { return "column(" + std::to_string(column) + ")"; }

}  // namespace

std::string BandText(double lo_hz, double hi_hz) { return Short(lo_hz) + "–" + Short(hi_hz) + " Hz"; }

Plot BandPlot(const BudgetResult& result, std::size_t o) {
  const OutputResult& out = result.outputs[o];
  const std::size_t n = out.contributors.size(), bands = out.bands.size();
  const std::string unit = DisplayUnit(out.unit);
  Plot p;
  p.name = FileStem(out.name) + "_bands";
  p.kind = PlotKind::kBands;
  p.output = static_cast<int>(o);
  p.caption = "RMS of " + out.name + " per frequency band: the band's total, then each contributor by share.";

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.budget_name << ", output " << out.name << ": RMS in "
      << unit << " per band, in total and per contributor\n";
  csv << "band,lo_hz,hi_hz,total";
  for (const auto& c : out.contributors) csv << ',' << CsvField(c.name);
  csv << '\n';
  double top = 0.0, bottom = HUGE_VAL, smallest_total = HUGE_VAL;
  for (std::size_t b = 0; b < bands; ++b) {
    const BandResult& br = out.bands[b];
    csv << b + 1 << ',' << CsvNumber(br.band.lo_hz) << ',' << CsvNumber(br.band.hi_hz) << ','
        << CsvNumber(std::sqrt(br.variance));
    top = std::max(top, std::sqrt(br.variance));
    if (br.variance > 0.0) smallest_total = std::min(smallest_total, std::sqrt(br.variance));
    for (std::size_t c = 0; c < n; ++c) {
      const double rms = std::sqrt(br.contributor_variance[c]);
      csv << ',' << CsvNumber(rms);
      if (rms > 0.0) bottom = std::min(bottom, rms);
    }
    csv << '\n';
  }
  p.csv = csv.str();

  const double slot = 0.84 / static_cast<double>(n + 1);  // total + contributors share 84 % of a band
  std::ostringstream s;
  s << "reset\n" << StylePreamble();
  s << "set title " << Quote(Enhanced(out.name) + ": RMS per frequency band") << "\n";
  s << "set xrange [0.5:" << bands + 0.5 << "]\nset xtics scale 0 (";
  for (std::size_t b = 0; b < bands; ++b)
    s << (b ? ", " : "") << Quote(HzLabel(out.bands[b].band.lo_hz) + "–" + HzLabel(out.bands[b].band.hi_hz) + " Hz")
      << " " << b + 1;
  s << ")\nset xlabel 'frequency band'\nset grid noxtics nomxtics ytics\n";
  s << "set ylabel " << Quote("RMS in band [" + UnitLabel(unit) + "]") << "\n";
  s << "set logscale y 10\nset format y '10^{%L}'\n";
  if (top > 0.0) {
    // Five decades below the largest bar, deeper if a band's total needs it.
    const double lo = std::min(std::max(bottom, top * 1e-5), smallest_total);
    s << "set yrange [" << CsvNumber(std::pow(10.0, std::floor(std::log10(lo)))) << ":"
      << CsvNumber(std::pow(10.0, std::ceil(std::log10(top * 1.5)))) << "]\n";
  } else {
    s << "set yrange [0.1:10]\nset label 1 'every contributor is zero on this output' at graph 0.5,0.5 center\n";
  }
  s << "set boxwidth " << CsvNumber(slot * 0.9) << " absolute\n";
  s << "set style fill solid 1.0 border linecolor rgb " << Quote(kBarEdge) << "\n";
  s << "set key outside right top Left reverse\n";
  const std::string data = Quote(p.name + ".csv");
  const auto x = [&](std::size_t slot_index) {
    const double offset = (static_cast<double>(slot_index) - 0.5 * static_cast<double>(n)) * slot;
    return "(column(1) + " + CsvNumber(offset) + ")";
  };
  const auto positive = [](std::size_t col) { return "(" + Col(col) + " > 0 ? " + Col(col) + " : NaN)"; };
  std::vector<std::string> clauses;
  clauses.push_back(data + " using " + x(0) + ":" + positive(4) + " with boxes fillcolor rgb " +
                    Quote(kTotalColour) + " title 'total'");
  const std::vector<std::size_t> order = ShareOrder(out);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t c = order[i];
    for (std::string& clause : FillClauses(ContributorStyle(c), data + " using " + x(i + 1) + ":" + positive(5 + c),
                                           "boxes", "title " + Quote(Enhanced(out.contributors[c].name)),
                                           kBarEdge))
      clauses.push_back(std::move(clause));
  }
  s << PlotList(clauses);
  p.script = s.str();
  return p;
}

std::vector<Plot> OverviewPlots(const BudgetResult& result) {
  std::vector<Plot> plots;
  const std::size_t outputs = result.outputs.size();
  // Outputs spread evenly over the pages (7 outputs: 4 + 3, not 6 + 1).
  const std::size_t pages = (outputs + kPanelsPerPage - 1) / kPanelsPerPage;
  const std::size_t per_page = pages ? (outputs + pages - 1) / pages : 0;
  for (std::size_t page = 0; page < pages; ++page) {
    const std::size_t first = page * per_page, last = std::min(outputs, first + per_page);
    const std::size_t panels = last - first;
    Plot p;
    p.name = pages == 1 ? "overview" : "overview_" + std::to_string(page + 1);
    p.kind = PlotKind::kOverview;
    p.caption = "RMS of every contributor and the total per output, against the requirement where there is one" +
                std::string(pages == 1 ? "." : " (outputs " + std::to_string(first + 1) + "–" +
                                                   std::to_string(last) + ").");

    // Columns: 1 panel, 2 position, 3 rms, 4 label, then descriptive text.
    std::ostringstream csv;
    csv << "# deb " << DEB_VERSION << ", budget " << result.budget_name
        << ": RMS per output and contributor (position: bar position in the panel)\n";
    csv << "panel,position,rms,rms_label,output,unit,contributor,share_percent,rms_max,pass\n";
    for (std::size_t o = first; o < last; ++o) {
      const OutputResult& out = result.outputs[o];
      const std::size_t n = out.contributors.size();
      const std::string req = out.rms_max ? CsvNumber(*out.rms_max) : "";
      const std::string pass = out.rms_max ? (out.pass() ? "pass" : "FAIL") : "";
      for (std::size_t c = 0; c <= n; ++c) {
        const bool total = c == n;
        const double var = total ? out.variance : out.contributors[c].variance;
        csv << o - first + 1 << ',' << (total ? CsvNumber(n + 1.3) : std::to_string(c + 1)) << ','
            << CsvNumber(std::sqrt(var)) << ',' << Sig(std::sqrt(var)) << ',' << CsvField(out.name) << ','
            << CsvField(DisplayUnit(out.unit)) << ',' << (total ? "total" : CsvField(out.contributors[c].name))
            << ',' << CsvNumber(out.variance > 0 ? 100.0 * var / out.variance : 0.0) << ',' << req << ','
            << pass << '\n';
      }
    }
    p.csv = csv.str();

    const std::size_t cols = panels <= 2 ? panels : panels <= 4 ? 2 : panels <= 6 ? 3 : 4;
    const std::size_t rows = (panels + cols - 1) / cols;
    const std::string data = Quote(p.name + ".csv");
    std::ostringstream s;
    s << "reset\n" << StylePreamble();
    s << "set multiplot layout " << rows << "," << cols << " title "
      << Quote("RMS per output and contributor" + std::string(pages > 1 ? " (" + std::to_string(page + 1) + "/" +
                                                                            std::to_string(pages) + ")"
                                                                      : ""))
      << " font '," << 15 << "'\n";
    s << "unset key\nset grid noxtics nomxtics ytics\nset boxwidth 0.7 absolute\n"
         "set style textbox opaque noborder margins 0.5,0.5\n";  // value labels stay readable over lines
    s << "set style fill solid 1.0 border linecolor rgb " << Quote(kBarEdge) << "\n";
    for (std::size_t o = first; o < last; ++o) {
      const OutputResult& out = result.outputs[o];
      const std::size_t n = out.contributors.size(), panel = o - first + 1;
      const std::string unit = DisplayUnit(out.unit);
      // Two lines: the output, then its figure against the requirement.
      std::string status = "RMS " + SigLabel(out.rms()) + " " + UnitLabel(unit);
      if (out.rms_max)
        status += std::string(out.pass() ? ": PASS" : ": FAIL") + " (requirement " + Short(*out.rms_max) + ")";
      const std::string title = QuoteLines({Enhanced(out.name), status});
      const double top = std::max(out.rms(), out.rms_max ? *out.rms_max : 0.0);
      s << "set title " << title << " font '," << (panels > 2 ? 12 : 13) << "' textcolor rgb "
        << Quote(out.rms_max && !out.pass() ? kRequirementColour : "#202020") << "\n";
      s << "set xrange [0.4:" << CsvNumber(n + 1.9) << "]\n";
      // Many bars: names at a steeper angle, values upright above the bars.
      const bool crowded = 1200.0 / static_cast<double>(cols) / static_cast<double>(n + 2) < 60.0;  // px per bar
      s << "set yrange [0:" << CsvNumber(top > 0 ? top * (crowded ? 1.3 : 1.2) : 1.0) << "]\n";
      s << "set ylabel " << Quote("RMS [" + UnitLabel(unit) + "]") << "\n";
      s << "set xtics scale 0 " << (crowded ? "rotate by 50 right " : n > 3 || panels > 2 ? "rotate by 30 right " : "norotate ")
        << "(";
      for (std::size_t c = 0; c < n; ++c) s << Quote(Enhanced(out.contributors[c].name)) << " " << c + 1 << ", ";
      s << "'total' " << CsvNumber(n + 1.3) << ")\n";
      const std::string here = "(column(1) == " + std::to_string(panel) + " ? column(3) : NaN)";
      std::vector<std::string> clauses;
      for (std::size_t c = 0; c <= n; ++c) {
        SeriesStyle st;
        st.colour = kTotalColour;
        if (c < n) st = ContributorStyle(c);
        for (std::string& clause : FillClauses(st, data + " using 2:(column(1) == " + std::to_string(panel) +
                                                       " && column(2) == " +
                                                       (c == n ? CsvNumber(n + 1.3) : std::to_string(c + 1)) +
                                                       " ? column(3) : NaN)",
                                               "boxes", "notitle", kBarEdge))
          clauses.push_back(std::move(clause));
      }
      if (out.rms_max)
        clauses.push_back(CsvNumber(*out.rms_max) + " with lines linecolor rgb " + Quote(kRequirementColour) +
                          " dashtype " + kRequirementDash + " linewidth 2");
      clauses.push_back(data + " using 2:" + here + ":4 with labels " +
                        (crowded ? "rotate by 90 left offset 0,0.5" : "offset 0,0.8") +
                        " boxed font ',9' textcolor rgb '#202020'");  // last: over the requirement line
      s << PlotList(clauses);
    }
    s << "unset multiplot\n";
    p.script = s.str();
    plots.push_back(std::move(p));
  }
  return plots;
}

}  // namespace deb::report
