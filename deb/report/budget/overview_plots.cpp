#include "deb/report/budget/overview_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/core/number_text.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr const char* kBarEdge = "#303030";
constexpr std::size_t kPanelsPerPage = 8;

}  // namespace

std::vector<Plot> OverviewFigures(const BudgetResult& result, int digits) {
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
    p.caption = "RMS of every contributor (largest first) and the total per output, against the requirement where "
                "there is one" +
                std::string(pages == 1 ? "." : " (outputs " + std::to_string(first + 1) + "–" + std::to_string(last) + ").");

    // Columns: 1 panel, 2 position, 3 rms, 4 label, descriptive text, 11 row (the bar's own id).
    std::ostringstream csv;
    csv << "# deb " << DEB_VERSION << ", budget " << result.outline.name
        << ": RMS per output and contributor (position: bar position in the panel; row: the bar)\n";
    csv << "panel,position,rms,rms_label,output,unit,contributor,share_percent,rms_max,pass,row\n";
    std::size_t row = 0;
    // Names beside horizontal bars need a panel's width: one output across
    // the figure, two panels to a row, three from five outputs up.
    const std::size_t cols = panels == 1 ? 1 : panels <= 4 ? 2 : 3;
    // In a PDF, as tall as its rows of bars need (a title; per row two title
    // lines and an axis, 110 px, and 17 px a bar, at least 70 px of plot),
    // within the overview's 600 px: one output with six contributors got
    // bars 50 px thick.
    std::size_t most_bars = 0;
    for (std::size_t o = first; o < last; ++o) most_bars = std::max(most_bars, result.outputs[o].contributors.size() + 1);
    const double rows = std::ceil(static_cast<double>(panels) / static_cast<double>(cols));
    p.pdf_height_px = static_cast<int>(
        std::min(30.0 + rows * (110.0 + std::max(70.0, 17.0 * (static_cast<double>(most_bars) + 0.5))), 600.0));
    p.figure.title = "RMS per output and contributor" +
                     std::string(pages > 1 ? " (" + std::to_string(page + 1) + "/" + std::to_string(pages) + ")" : "");
    p.figure.columns = cols;
    const std::string data = p.name + ".csv";
    for (std::size_t o = first; o < last; ++o) {
      const OutputResult& out = result.outputs[o];
      const std::size_t n = out.contributors.size(), panel_index = o - first + 1;
      const std::string unit = DisplayUnit(out.unit);
      const std::vector<std::size_t> order = ShareOrder(out);
      FigurePanel panel;
      std::string status = "RMS " + SigLabel(out.rms(), digits) + " " + UnitLabel(unit);
      // Three panels or more to a row: the verdict on a line of its own (in
      // report.pdf a panel is 220 px wide: one line ran into the next title).
      if (out.rms_max)
        status += std::string(cols >= 3 ? "\n" : ": ") + (out.pass() ? "PASS" : "FAIL") + " (requirement " +
                  Short(*out.rms_max) + ")";
      panel.title = Enhanced(out.name) + "\n" + status;
      panel.title_colour = out.rms_max && !out.pass() ? kRequirementColour : "#202020";
      panel.key.placement = KeyPlacement::kNone;
      // Horizontal bars, largest at the top and the total at the foot: the
      // names read across on the y axis and each value beside its bar's end
      // (upright labels over 12 vertical bars were 4 pt in report.pdf).
      panel.y.min = 0.4;
      panel.y.max = static_cast<double>(n) + 1.9;
      panel.y.grid = panel.y.minor_grid = false;
      const double top = std::max(out.rms(), out.rms_max.value_or(0.0));
      panel.x.min = 0.0;
      panel.x.max = top > 0 ? top * 1.4 : 1.0;  // room for the values beside the bars
      panel.x.minor_grid = false;
      panel.x.label = "RMS [" + UnitLabel(unit) + "]";
      panel.x.format = "%g";
      // At most 4 steps (3 panels to a row: gnuplot's own ran together).
      if (top > 0) {
        const double step = NiceStep(*panel.x.max / (cols >= 3 ? 3.0 : 5.0));
        for (int k = 0; k * step <= *panel.x.max * (1 + 1e-12); ++k)
          panel.x.tics.push_back({k * step, SignificantText(k * step)});
      }
      panel.y2.shown = false;
      for (std::size_t i = 0; i <= n; ++i) {
        const bool total = i == n;
        const std::size_t c = total ? n : order[i];
        // Top to bottom: the largest contributor at n + 1.3, the total at 1.
        const double position = total ? 1.0 : static_cast<double>(n - i) + 1.3;
        // An uncoupled contributor computed as rounding reads 0, as in the tables.
        const double var = total ? out.variance : WithoutRounding(out.contributors[c].variance, out.variance);
        ++row;
        csv << panel_index << ',' << CsvNumber(position) << ',' << CsvNumber(std::sqrt(var)) << ','
            << Sig(std::sqrt(var), digits) << ',' << CsvField(out.name) << ',' << CsvField(unit) << ','
            << (total ? "total" : CsvField(out.contributors[c].name)) << ','
            << CsvNumber(out.variance > 0 ? 100.0 * var / out.variance : 0.0) << ','
            << (out.rms_max ? CsvNumber(*out.rms_max) : "") << ','
            << (out.rms_max ? (out.pass() ? "pass" : "FAIL") : "") << ',' << row << '\n';
        panel.y.tics.push_back({position, total ? "total" : Enhanced(out.contributors[c].name)});
        FigureSeries bar;
        bar.name = total ? "total" : out.contributors[c].name;
        bar.kind = SeriesKind::kHorizontalBars;
        bar.data = data;
        bar.x_column = 3;
        bar.y_columns = {2};
        bar.bar_height = 0.7;
        bar.where_column = 11;
        bar.where_value = static_cast<double>(row);
        bar.edge_colour = kBarEdge;
        if (total) {
          bar.colour = kTotalColour;
        } else {
          const SeriesStyle st = ContributorStyle(c);
          bar.colour = st.colour;
          bar.fill_pattern = st.fill_pattern;
          bar.hatch_colour = st.hatch_colour;
        }
        panel.series.push_back(bar);
      }
      if (out.rms_max) {
        FigureAnnotation limit;
        limit.kind = AnnotationKind::kVerticalLine;
        limit.x0 = *out.rms_max;
        limit.colour = kRequirementColour;
        limit.dash = kRequirementDash;
        // Under the bars and their value labels: drawn over them, the dashes
        // struck through the bars and the values that reach the limit.
        limit.behind = true;
        panel.annotations.push_back(limit);
      }
      FigureSeries values;  // last: over the bars
      values.name = "values";
      values.kind = SeriesKind::kLabels;
      values.data = data;
      values.x_column = 3;
      values.y_columns = {2};
      values.where_column = 1;
      values.where_value = static_cast<double>(panel_index);
      values.label_column = 4;
      values.colour = "#202020";
      values.labels_beside_end = true;
      panel.series.push_back(values);
      p.figure.panels.push_back(std::move(panel));
    }
    p.csv = csv.str();
    p.script = EmitFigure(p.figure);
    plots.push_back(std::move(p));
  }
  return plots;
}

}  // namespace deb::report
