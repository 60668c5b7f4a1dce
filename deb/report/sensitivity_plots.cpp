#include "deb/report/sensitivity_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/report/plot_style.h"
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

std::vector<Plot> TornadoPlots(const std::vector<Sensitivity>& all, const BudgetResult& nominal) {
  std::vector<Plot> plots;
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& out = nominal.outputs[o];
    const std::vector<TornadoBar> bars = TornadoBars(all, out);
    if (bars.empty()) continue;
    Plot p;
    p.name = FileStem(out.name) + "_tornado";
    p.kind = PlotKind::kOverview;
    p.output = static_cast<int>(o);
    p.caption = "Elasticity of the variance of " + out.name +
                " (d var / var per dp / p) per parameter, largest on top (black), with each contributor's share "
                "of it, (d var_c / d ln p) / var, in its colour.";
    double m = 0.0;
    std::ostringstream csv;
    csv << "# deb " << DEB_VERSION << ", sensitivity, output " << out.name
        << ": elasticity of the total variance, and each contributor's share of it; top to bottom\n";
    csv << "position,value,parameter,contributor,colour_index\n";
    const std::size_t n = bars.size();
    for (std::size_t i = 0; i < n; ++i) {
      const TornadoBar& b = bars[i];
      m = std::max(m, std::abs(b.value));
      csv << (n - 1 - i) << ',' << CsvNumber(b.value) << ',' << CsvField(b.parameter) << ',' << CsvField(b.contributor)
          << ',' << (b.contributor == "total" ? -1 : static_cast<long>(b.contributor_index)) << '\n';
    }
    p.csv = csv.str();
    if (!(m > 0.0)) m = 1.0;

    std::ostringstream s;
    s << "reset\n" << StylePreamble();
    s << "set title " << Quote(Enhanced(out.name + ": elasticity of the variance, by parameter")) << "\n";
    s << "set xlabel " << Quote("elasticity (d var / var) / (dp / p)") << "\n";
    s << "set xrange [" << CsvNumber(-1.3 * m) << ":" << CsvNumber(1.3 * m) << "]\n";
    s << "set yrange [-0.7:" << n - 0.3 << "]\nunset grid\nset grid xtics linestyle 101\nset ytics scale 0 (";
    for (std::size_t i = 0; i < n; ++i) {
      const TornadoBar& b = bars[i];
      const std::string label = b.contributor == "total" ? b.parameter + ": total" : "of which " + b.contributor;
      s << (i ? ", " : "") << Quote(Enhanced(label)) << " " << n - 1 - i;
    }
    s << ")\nset arrow 1 from 0, graph 0 to 0, graph 1 nohead linecolor rgb '#404040' linewidth 1\n";
    s << "set key off\n";
    const std::string file = Quote(p.name + ".csv");
    std::vector<std::string> clauses;
    // The total's bars, then each contributor's in its colour.
    clauses.push_back(file + " using (column(5) < 0 ? column(2) / 2 : NaN):1:(abs(column(2)) / 2):(0.36) "
                             "with boxxyerror fillstyle solid 1.0 linecolor rgb " + Quote(kTotalColour));
    for (std::size_t c = 0; c < out.contributors.size(); ++c)
      clauses.push_back(file + " using (column(5) == " + std::to_string(c) +
                        " ? column(2) / 2 : NaN):1:(abs(column(2)) / 2):(0.26) with boxxyerror fillstyle solid 1.0 "
                        "linecolor rgb " + Quote(ContributorStyle(c).colour));
    // Values at the bar ends, outside them.
    clauses.push_back(file + " using (column(2) >= 0 ? column(2) : NaN):1:(sprintf('%.3g', column(2))) "
                             "with labels left offset 0.6,0 font ',10'");
    clauses.push_back(file + " using (column(2) < 0 ? column(2) : NaN):1:(sprintf('%.3g', column(2))) "
                             "with labels right offset -0.6,0 font ',10'");
    s << "plot ";
    for (std::size_t i = 0; i < clauses.size(); ++i) s << (i ? ", \\\n     " : "") << clauses[i];
    s << "\n";
    p.script = s.str();
    plots.push_back(std::move(p));
  }
  return plots;
}

}  // namespace deb::report
