#include "deb/report/compare/sensitivity_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "deb/version.h"

namespace deb::report {

std::vector<TornadoBar> TornadoBars(const std::vector<Sensitivity>& all, const OutputResult& output) {
  std::vector<const Sensitivity*> totals;
  for (const Sensitivity& s : all)
    if (s.output == output.name && s.contributor == "total") totals.push_back(&s);
  std::stable_sort(totals.begin(), totals.end(), [](const Sensitivity* a, const Sensitivity* b) {
    return std::abs(a->elasticity) > std::abs(b->elasticity);
  });
  const double var = output.variance;
  std::vector<TornadoBar> bars;
  double largest = 0.0;
  for (const Sensitivity* t : totals) {
    bars.push_back({t->parameter, "total", 0, t->elasticity});
    largest = std::max(largest, std::abs(t->elasticity));
    std::vector<TornadoBar> parts;
    for (const Sensitivity& s : all)
      if (s.output == output.name && s.parameter == t->parameter && s.contributor != "total" && var > 0.0)
        for (std::size_t c = 0; c < output.contributors.size(); ++c)
          if (output.contributors[c].name == s.contributor) parts.push_back({s.parameter, s.contributor, c, s.d_variance_d_log_p / var});
    std::stable_sort(parts.begin(), parts.end(),
                     [](const TornadoBar& a, const TornadoBar& b) { return std::abs(a.value) > std::abs(b.value); });
    for (const TornadoBar& p : parts) largest = std::max(largest, std::abs(p.value));
    bars.insert(bars.end(), parts.begin(), parts.end());
  }
  bars.erase(std::remove_if(bars.begin(), bars.end(),
                            [&](const TornadoBar& b) { return b.contributor != "total" && std::abs(b.value) < 1e-3 * largest; }),
             bars.end());
  return bars;
}

std::vector<Plot> TornadoPlots(const std::vector<Sensitivity>& all, const BudgetResult& nominal,
                               const std::map<std::string, std::string>& labels) {
  const auto label = [&](const std::string& key) {
    const auto it = labels.find(key);
    return it == labels.end() ? key : it->second;
  };
  std::vector<Plot> plots;
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& out = nominal.outputs[o];
    const std::vector<TornadoBar> bars = TornadoBars(all, out);
    if (bars.empty()) continue;
    Plot p;
    p.name = FileStem(out.name) + "_tornado";
    p.kind = PlotKind::kOverview;
    p.output = static_cast<int>(o);
    // In the PDF as tall as its bars need (36 px a bar): at the overview's
    // 600 px, five bars took a page each.
    p.pdf_height_px = static_cast<int>(std::min<std::size_t>(600, 150 + 36 * bars.size()));
    p.caption = "Elasticity of the variance of " + out.name +
                " (d var / var per dp / p) per parameter, largest on top (black), with each contributor's share "
                "of it, (d var_c / d ln p) / var, in its colour.";
    double m = 0.0;
    std::ostringstream csv;
    csv << "# deb " << DEB_VERSION << ", sensitivity, output " << out.name
        << ": elasticity of the total variance, and each contributor's share of it; top to bottom\n";
    csv << "position,value,parameter,contributor,colour_index,label\n";
    const std::size_t n = bars.size();
    for (std::size_t i = 0; i < n; ++i) {
      const TornadoBar& b = bars[i];
      m = std::max(m, std::abs(b.value));
      csv << (n - 1 - i) << ',' << CsvNumber(b.value) << ',' << CsvField(b.parameter) << ',' << CsvField(b.contributor)
          << ',' << (b.contributor == "total" ? -1 : static_cast<long>(b.contributor_index)) << ','
          << CsvField(SigLabel(b.value, 3)) << '\n';  // "-2.93·10^{-5}", as the tables print it (not "-2.93e-05")
    }
    p.csv = csv.str();
    if (!(m > 0.0)) m = 1.0;

    // Bars top to bottom at y = n-1 .. 0, named on the y axis; the total's
    // bars black, each contributor's share in its colour, narrower.
    FigurePanel panel;
    panel.title = Enhanced(out.name + ": elasticity of the variance, by parameter");
    panel.key.placement = KeyPlacement::kNone;
    panel.x.label = "elasticity (d var / var) / (dp / p)";
    panel.x.min = -1.3 * m;  // symmetric about 0, the largest bar + 30 %: room for its value
    panel.x.max = 1.3 * m;
    panel.x.minor_grid = false;
    panel.y.min = -0.7;
    panel.y.max = static_cast<double>(n) - 0.3;
    panel.y.grid = panel.y.minor_grid = false;
    for (std::size_t i = 0; i < n; ++i) {
      const TornadoBar& b = bars[i];
      panel.y.tics.push_back({static_cast<double>(n - 1 - i),
                              Enhanced(b.contributor == "total" ? label(b.parameter) + ": total" : "of which " + b.contributor)});
    }
    panel.y2.shown = false;
    const std::string data = p.name + ".csv";
    const auto bars_of = [&](const std::string& name, double colour_index, const std::string& colour, double height) {
      FigureSeries s;
      s.name = name;
      s.kind = SeriesKind::kHorizontalBars;
      s.data = data;
      s.x_column = 2;
      s.y_columns = {1};
      s.where_column = 5;
      s.where_value = colour_index;
      s.colour = colour;
      s.bar_height = height;
      return s;
    };
    panel.series.push_back(bars_of("total", -1.0, kTotalColour, 0.72));
    for (std::size_t c = 0; c < out.contributors.size(); ++c)
      panel.series.push_back(
          bars_of(out.contributors[c].name, static_cast<double>(c), ContributorStyle(c).colour, 0.52));
    FigureSeries values;  // at the bar ends, outside them
    values.name = "values";
    values.kind = SeriesKind::kLabels;
    values.data = data;
    values.x_column = 2;
    values.y_columns = {1};
    values.label_column = 6;
    values.labels_beside_end = true;
    panel.series.push_back(values);
    FigureAnnotation zero;
    zero.kind = AnnotationKind::kVerticalLine;
    zero.x0 = 0.0;
    zero.colour = "#404040";
    zero.width = 1.0;
    panel.annotations.push_back(zero);
    p.figure.panels.push_back(std::move(panel));
    p.script = EmitFigure(p.figure);
    plots.push_back(std::move(p));
  }
  return plots;
}

}  // namespace deb::report
