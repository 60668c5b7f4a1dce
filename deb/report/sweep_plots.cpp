#include "deb/report/sweep_plots.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "deb/core/error.h"
#include "deb/report/plot_style.h"
#include "deb/version.h"

namespace deb::report {

std::vector<Plot> SweepPlots(const SweepSpec& spec, const std::vector<BudgetResult>& results) {
  const auto rows = spec.Variants();
  DEB_DEMAND(rows.size() == results.size());
  std::vector<Plot> plots;
  if (results.empty() || spec.parameters.empty()) return plots;
  // Variants grouped by the values of parameters 2..n, each group ordered by parameter 1.
  std::map<std::vector<double>, std::vector<std::size_t>> groups;
  std::vector<std::vector<double>> order;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<double> rest(rows[i].begin() + 1, rows[i].end());
    if (!groups.count(rest)) order.push_back(rest);
    groups[rest].push_back(i);
  }
  for (auto& [rest, members] : groups)
    std::stable_sort(members.begin(), members.end(),
                     [&](std::size_t a, std::size_t b) { return rows[a][0] < rows[b][0]; });
  const char* dashes[] = {"solid", "(10,5)", "(3,4)", "(12,4,3,4)", "(20,6)", "(2,2)"};

  for (std::size_t o = 0; o < results[0].outputs.size(); ++o) {
    const OutputResult& out0 = results[0].outputs[o];
    Plot p;
    p.name = FileStem(out0.name) + "_sweep";
    p.kind = PlotKind::kOverview;
    p.output = static_cast<int>(o);
    p.caption = "RMS of " + out0.name + " against " + spec.parameters[0].key_path +
                "; colour: contributor (total black), dash: values of the other parameters.";
    std::ostringstream csv;
    csv << "# deb " << DEB_VERSION << ", sweep, output " << out0.name << " RMS in " << out0.unit
        << "; one block per combination of the other parameters\n";
    std::size_t block = 0;
    std::vector<std::string> clauses, legend_dashes;
    const std::string file = Quote(p.name + ".csv");
    for (const auto& rest : order) {
      std::string label;
      for (std::size_t k = 1; k < spec.parameters.size(); ++k)
        label += (k > 1 ? ", " : "") + spec.parameters[k].key_path + " = " + spec.parameters[k].Text(rest[k - 1]);
      if (block) csv << "\n\n";
      csv << "# " << (label.empty() ? "all variants" : label) << "\n" << CsvField(spec.parameters[0].key_path);
      for (const auto& c : out0.contributors) csv << ',' << CsvField(c.name);
      csv << ",total\n";
      for (std::size_t i : groups[rest]) {
        const OutputResult& r = results[i].outputs[o];
        csv << CsvNumber(rows[i][0]);
        for (const auto& c : r.contributors) csv << ',' << CsvNumber(std::sqrt(c.variance));
        csv << ',' << CsvNumber(r.rms()) << '\n';
      }
      const std::string dash = dashes[block % 6];
      // One block: each curve names itself. Several: the key names the
      // colours (contributors) and the dashes (the other parameters) apart,
      // so it has contributors + blocks entries, not their product.
      const bool own_titles = order.size() == 1;
      const auto title = [&](const std::string& name) {
        return own_titles ? " title " + Quote(Enhanced(name)) : std::string(" notitle");
      };
      for (std::size_t c = 0; c < out0.contributors.size(); ++c)
        clauses.push_back(file + " index " + std::to_string(block) + " using 1:" + std::to_string(c + 2) +
                          " with linespoints pointtype 7 pointsize 0.6 linewidth 1.5 linecolor rgb " +
                          Quote(ContributorStyle(c).colour) + " dashtype " + dash + title(out0.contributors[c].name));
      clauses.push_back(file + " index " + std::to_string(block) + " using 1:" +
                        std::to_string(out0.contributors.size() + 2) +
                        " with linespoints pointtype 7 pointsize 0.6 linewidth 2.5 linecolor rgb " +
                        Quote(kTotalColour) + " dashtype " + dash + title("total"));
      if (!own_titles)
        legend_dashes.push_back("keyentry with lines linewidth 1.5 linecolor rgb '#606060' dashtype " + dash +
                                " title " + Quote(Enhanced(label)));
      ++block;
    }
    if (order.size() > 1) {
      std::vector<std::string> keys;
      for (std::size_t c = 0; c < out0.contributors.size(); ++c)
        keys.push_back("keyentry with linespoints pointtype 7 pointsize 0.6 linewidth 1.5 linecolor rgb " +
                       Quote(ContributorStyle(c).colour) + " title " + Quote(Enhanced(out0.contributors[c].name)));
      keys.push_back("keyentry with linespoints pointtype 7 pointsize 0.6 linewidth 2.5 linecolor rgb " +
                     Quote(kTotalColour) + " title 'total'");
      keys.insert(keys.end(), legend_dashes.begin(), legend_dashes.end());
      clauses.insert(clauses.end(), keys.begin(), keys.end());
    }
    p.csv = csv.str();
    std::ostringstream s;
    s << "reset\n" << StylePreamble();
    s << "set title " << Quote(Enhanced(out0.name)) << "\n";
    s << "set xlabel " << Quote(Enhanced(spec.parameters[0].key_path)) << "\n";
    s << "set ylabel " << Quote("RMS [" + UnitLabel(out0.unit) + "]") << "\n";
    s << "set key outside right top\nset yrange [0:*]\n";
    if (!spec.parameters[0].texts.empty()) {  // a textual parameter: its index on the axis, named
      const auto& texts = spec.parameters[0].texts;
      s << "set xrange [-0.5:" << texts.size() - 0.5 << "]\nset xtics (";
      for (std::size_t i = 0; i < texts.size(); ++i) s << (i ? ", " : "") << Quote(Enhanced(texts[i])) << " " << i;
      s << ")\n";
    }
    if (out0.rms_max)
      s << "set arrow from graph 0, first " << CsvNumber(*out0.rms_max) << " to graph 1, first "
        << CsvNumber(*out0.rms_max) << " nohead linewidth 1.5 linecolor rgb " << Quote(kRequirementColour)
        << " dashtype " << kRequirementDash << "\n";
    s << "plot ";
    for (std::size_t i = 0; i < clauses.size(); ++i) s << (i ? ", \\\n     " : "") << clauses[i];
    s << "\n";
    p.script = s.str();
    plots.push_back(std::move(p));
  }
  return plots;
}

}  // namespace deb::report
