#include "deb/report/budget/overview_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

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

    // Columns: 1 panel, 2 position, 3 rms, 4 label, descriptive text, 11 row (the bar's own id), 12 where the
    // label goes.
    std::ostringstream csv;
    csv << "# deb " << DEB_VERSION << ", budget " << result.outline.name
        << ": RMS per output and contributor (position: bar position in the panel; row: the bar; label_at: where "
           "its value is written)\n";
    csv << "panel,position,rms,rms_label,output,unit,contributor,share_percent,rms_max,pass,row,label_at\n";
    std::size_t row = 0;
    // Names beside horizontal bars need a panel's width: one output across
    // the figure, two panels to a row, three from five outputs up.
    const std::size_t cols = panels == 1 ? 1 : panels <= 4 ? 2 : 3;
    // In a PDF, as tall as its rows of bars need (a title; per row its title
    // lines, 20 px each, and an axis, 90 px; 17 px a bar, at least 80 px of
    // plot), within the overview's 600 px: one output with six contributors
    // got bars 50 px thick.
    std::size_t most_bars = 0;
    bool verdict_line = false;  // a third title line: the verdict below the RMS
    for (std::size_t o = first; o < last; ++o) {
      most_bars = std::max(most_bars, result.outputs[o].contributors.size() + 1);
      verdict_line = verdict_line || (cols >= 3 && result.outputs[o].rms_max);
    }
    const double rows = std::ceil(static_cast<double>(panels) / static_cast<double>(cols));
    const double row_px = 90.0 + 20.0 * (verdict_line ? 3.0 : 2.0) +
                          std::max(80.0, 17.0 * (static_cast<double>(most_bars) + 0.5));
    p.pdf_height_px = static_cast<int>(std::min(30.0 + rows * row_px, 600.0));
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
                  Short(*out.rms_max) + " " + UnitLabel(unit) + ")";
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
      // A value's text beside its bar, as a fraction of the axis: a character
      // is about 1.4 % of report.pdf's plot across the figure, 2.8 % of a
      // panel of two to a row and 7 % of one of three (whose names take
      // half of it), the gap and box 1.5 characters more.
      const double char_share = cols >= 3 ? 0.07 : cols == 2 ? 0.028 : 0.014;
      const auto text_share = [&](double rms) {
        return (static_cast<double>(Sig(rms, digits).size()) + 1.5) * char_share;
      };
      // Each bar's variance as it is shown (index n: the total); an uncoupled
      // contributor computed as rounding reads 0, as in the tables.
      std::vector<double> shown(n + 1, out.variance);
      for (std::size_t c = 0; c < n; ++c) shown[c] = WithoutRounding(out.contributors[c].variance, out.variance);
      double widest = 0.0;
      for (const double v : shown) widest = std::max(widest, text_share(std::sqrt(v)));
      // Room for the values beside the bars, and past the requirement's line.
      panel.x.max = top > 0 ? top * std::max(1.4, 1.0 / (1.0 - std::min(widest, 0.6))) : 1.0;
      // A value whose text would reach the requirement's line is written
      // past it (its box covered the line, which then seemed to stop at it);
      // with a character to spare, for the estimate's error (wafer_stage's
      // 0.8068 ended on the line at 1.5).
      const auto label_at = [&](double rms) {
        return out.rms_max && rms < *out.rms_max &&
                       *out.rms_max - rms < (text_share(rms) + char_share) * *panel.x.max
                   ? *out.rms_max
                   : rms;
      };
      panel.x.minor_grid = false;
      panel.x.label = "RMS [" + UnitLabel(unit) + "]";
      panel.x.format = "%g";
      // At most 5 steps, 3 with three panels to a row, 2 there for labels
      // of four digits or more (gnuplot's own, then "10002000", ran together).
      if (top > 0) {
        const double wide = *panel.x.max >= 999.5 || *panel.x.max < 0.01;
        const double step = NiceStep(*panel.x.max / (cols >= 3 ? (wide ? 2.0 : 3.0) : 5.0));
        for (int k = 0; k * step <= *panel.x.max * (1 + 1e-12); ++k)
          panel.x.tics.push_back({k * step, SignificantText(k * step)});
      }
      panel.y2.shown = false;
      for (std::size_t i = 0; i <= n; ++i) {
        const bool total = i == n;
        const std::size_t c = total ? n : order[i];
        // Top to bottom: the largest contributor at n + 1.3, the total at 1.
        const double position = total ? 1.0 : static_cast<double>(n - i) + 1.3;
        const double var = shown[c];
        ++row;
        csv << panel_index << ',' << CsvNumber(position) << ',' << CsvNumber(std::sqrt(var)) << ','
            << Sig(std::sqrt(var), digits) << ',' << CsvField(out.name) << ',' << CsvField(unit) << ','
            << (total ? "total" : CsvField(out.contributors[c].name)) << ','
            << CsvNumber(out.variance > 0 ? 100.0 * var / out.variance : 0.0) << ','
            << (out.rms_max ? CsvNumber(*out.rms_max) : "") << ','
            << (out.rms_max ? (out.pass() ? "pass" : "FAIL") : "") << ',' << row << ',' << CsvNumber(label_at(std::sqrt(var)))
            << '\n';
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
      values.x_column = 12;
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
