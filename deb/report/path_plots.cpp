#include "deb/report/path_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "deb/budget/path_response.h"
#include "deb/core/parallel.h"
#include "deb/report/plot_points.h"
#include "deb/report/plot_style.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr double kDecades = 8.0;  // of magnitude shown below the peak
// Curves closer than this everywhere they are visible are drawn as one
// (a line is about 0.01 decade wide on an 8-decade axis).
constexpr double kCoincidentDecades = 5e-3;

// Channels grouped by coincident magnitude, each group in channel order and
// the groups ordered by their first channel. Two channels coincide when at
// every frequency of `range` where either reaches `floor`, both are positive
// and within kCoincidentDecades; channels that never reach `floor` stay alone.
std::vector<std::vector<std::size_t>> CoincidentChannels(const std::vector<std::vector<double>>& gain2,
                                                         const std::vector<double>& f, const FrequencyRange& range,
                                                         double floor) {
  const double floor2 = floor * floor, tol = 2.0 * kCoincidentDecades;  // in decades of |h|^2
  const auto visible = [&](std::size_t k) {
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f[i] >= range.lo_hz && f[i] <= range.hi_hz && gain2[k][i] > 0.0 && gain2[k][i] >= floor2) return true;
    return false;
  };
  const auto coincide = [&](std::size_t a, std::size_t b) {
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f[i] < range.lo_hz || f[i] > range.hi_hz) continue;
      const double x = gain2[a][i], y = gain2[b][i];
      if (x < floor2 && y < floor2) continue;
      if (!(x > 0.0 && y > 0.0) || std::abs(std::log10(x / y)) > tol) return false;
    }
    return true;
  };
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t k = 0; k < gain2.size(); ++k) {
    bool joined = false;
    if (floor > 0.0 && visible(k))
      for (auto& g : groups)
        if (visible(g.front()) && coincide(g.front(), k)) {
          g.push_back(k);
          joined = true;
          break;
        }
    if (!joined) groups.push_back({k});
  }
  return groups;
}

Plot PathPlot(const Budget& budget, const BudgetResult& result, std::size_t c, std::size_t o, const PathResponse& r) {
  const std::vector<double>& f = result.grid.f_hz();
  const Contributor& contributor = budget.contributors[c];
  const Output& output = budget.outputs[o];
  const std::size_t m = r.gain2.size();
  Plot p;
  p.name = "path_" + FileStem(contributor.name) + "_to_" + FileStem(output.name);
  p.kind = PlotKind::kPath;
  p.output = static_cast<int>(o);
  std::pair<double, double> poles_hz{0.0, 0.0};
  const FrequencyRange display = DisplayRange(result.outputs[o], result.grid);
  const FrequencyRange range = PathRange(*result.paths.at(ContributorPathKey(contributor)), display, result.grid, &poles_hz);
  const bool widened = range.lo_hz < display.lo_hz || range.hi_hz > display.hi_hz;
  const std::string poles = (poles_hz.first == poles_hz.second ? Sig(poles_hz.first)
                                                                 : Sig(poles_hz.first) + "–" + Sig(poles_hz.second)) +
                            " Hz";
  p.caption = "Magnitude of the transfer from " + contributor.name + " (source " + contributor.source + ", path " +
              contributor.path + ") to " + output.name + (output.weighting ? ", weighting included" : "") +
              ", per source channel." + RangeCaption(range) +
              (widened ? " The range reaches half a decade beyond the natural frequency of every pole of the path (f_n " +
                             poles + ")."
                       : "");

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.budget_name << ": |h| from contributor "
      << contributor.name << " to output " << output.name << " in " << r.unit << ", per source channel\n";
  csv << "frequency_hz";
  for (const auto& ch : r.channels) csv << ',' << CsvField(ch);
  csv << '\n';
  // y range from what is shown: the display range of the output.
  double top = 0.0, bottom = HUGE_VAL;
  std::vector<double> channel_top(m, 0.0);
  std::vector<const std::vector<double>*> drawn;
  for (const auto& g : r.gain2) drawn.push_back(&g);
  for (std::size_t i : PlotPoints(f, drawn, range.lo_hz, range.hi_hz)) {
    csv << CsvNumber(f[i]);
    const bool shown = f[i] >= range.lo_hz && f[i] <= range.hi_hz;
    for (std::size_t k = 0; k < m; ++k) {
      const double mag = std::sqrt(r.gain2[k][i]);
      csv << ',' << CsvNumber(mag);
      if (mag > 0.0 && shown) {
        top = std::max(top, mag);
        bottom = std::min(bottom, mag);
        channel_top[k] = std::max(channel_top[k], mag);
      }
    }
    csv << '\n';
  }
  p.csv = csv.str();
  const double floor = top > 0.0 ? std::pow(10.0, std::floor(std::log10(std::max(bottom, top * std::pow(10.0, -kDecades))))) : 0.0;

  std::ostringstream s;
  s << "reset\n" << StylePreamble();
  s << FrequencyAxis(range, result.grid,
                     widened ? std::string(kDisplayTailNote) + ", widened to the path's poles (f_{n} " + poles + ")"
                             : kDisplayTailNote);
  s << "set title " << Quote("path " + Enhanced(contributor.name) + " → " + Enhanced(output.name) + " (" +
                             Enhanced(contributor.path) + (output.weighting ? ", weighted" : "") + ")")
    << "\n";
  s << "set ylabel " << Quote("magnitude |h| [" + UnitLabel(r.unit) + "]") << "\n";
  s << "set logscale y 10\nset format y '10^{%L}'\n";
  if (top > 0.0) {
    s << "set yrange [" << CsvNumber(floor) << ":"
      << CsvNumber(std::pow(10.0, std::ceil(std::log10(top * 1.2)))) << "]\n";
  } else {
    s << "set yrange [0.1:10]\nset label 1 'zero transfer at every frequency' at graph 0.5,0.5 center\n";
  }
  s << "set key outside right top Left reverse title 'source channel'\n";
  const std::string data = Quote(p.name + ".csv");
  const auto name = [&](std::size_t k) { return k < r.channels.size() ? r.channels[k] : std::to_string(k + 1); };
  const std::vector<std::vector<std::size_t>> groups = CoincidentChannels(r.gain2, f, range, floor);
  // Markers spaced over the rows a curve has, about kChannelMarkers of them.
  const std::size_t rows = static_cast<std::size_t>(std::count(p.csv.begin(), p.csv.end(), '\n')) - 2;
  const std::size_t interval = std::max<std::size_t>(1, rows / kChannelMarkers);
  s << "plot ";
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t k = groups[g].front();
    // One channel: the contributor's own style; several: the channel family.
    const SeriesStyle st = m == 1 ? ContributorStyle(c) : ChannelStyle(k);
    const std::string col = "column(" + std::to_string(k + 2) + ")";
    std::string title;
    for (std::size_t j : groups[g]) title += (title.empty() ? "" : " = ") + Enhanced(name(j));
    const std::string line = "linecolor rgb " + Quote(st.colour) + " dashtype " + st.dash + " linewidth 2";
    const std::string key =
        Quote(title + (channel_top[k] == 0.0 ? " (zero)" : channel_top[k] < floor ? " (below the axis)" : ""));
    const std::string curve = data + " using 1:(" + col + " > 0 ? " + col + " : NaN)";
    s << (g ? ", \\\n     " : "");
    if (!st.point_type) {
      s << curve << " with lines " << line << " title " << key;
      continue;
    }
    // The markers of successive curves are staggered along x, so that curves
    // running close together keep their markers apart; the key shows both.
    const std::string marker = "pointtype " + std::to_string(st.point_type) + " pointsize 1.1";
    s << curve << " with lines " << line << " notitle, \\\n     " << curve << " every " << interval
      << "::" << (g * interval) / groups.size() << " with points " << marker << " linewidth 2 linecolor rgb " << Quote(st.colour)
      << " notitle, \\\n     keyentry with linespoints " << marker << " " << line << " title " << key;
  }
  s << "\n";
  p.script = s.str();
  if (groups.size() < m)
    p.caption += " Channels whose curves coincide are drawn once and named together (a = b).";
  return p;
}

}  // namespace

FrequencyRange PathRange(const PathAnalysis& path, const FrequencyRange& display, const FrequencyGrid& grid,
                         std::pair<double, double>* poles_hz) {
  if (path.path().HasMeasuredData() || path.modes().empty()) return display;
  double first = HUGE_VAL, last = 0.0;
  for (const Mode& m : path.modes()) {
    if (!(m.f_n_hz >= grid.min_hz() && m.f_n_hz <= grid.max_hz())) continue;  // integrators have f_n = 0
    first = std::min(first, m.f_n_hz);
    last = std::max(last, m.f_n_hz);
  }
  if (!(last > 0.0)) return display;
  if (poles_hz) *poles_hz = {first, last};
  const double margin = std::sqrt(10.0);  // half a decade
  FrequencyRange r = display;
  if (first / margin < r.lo_hz)
    r.lo_hz = std::max(std::pow(10.0, std::floor(std::log10(first / margin) + 1e-9)), grid.min_hz());
  if (last * margin > r.hi_hz)
    r.hi_hz = std::min(std::pow(10.0, std::ceil(std::log10(last * margin) - 1e-9)), grid.max_hz());
  r.trimmed = r.lo_hz > grid.min_hz() * (1 + 1e-9) || r.hi_hz < grid.max_hz() * (1 - 1e-9);
  return r;
}

std::vector<Plot> PathPlots(const Budget& budget, const BudgetResult& result, int threads) {
  // One job per contributor (its responses on every output); the plots
  // keep contributor order whichever thread made them.
  std::vector<std::vector<Plot>> per_contributor(budget.contributors.size());
  ParallelForEach(
      per_contributor.size(),
      [&](std::size_t c) {
        const std::vector<PathResponse> r = ComputePathResponses(budget, result, c, result.grid.f_hz(), threads);
        for (std::size_t o = 0; o < budget.outputs.size(); ++o)
          per_contributor[c].push_back(PathPlot(budget, result, c, o, r[o]));
      },
      threads);
  std::vector<Plot> plots;
  for (std::vector<Plot>& part : per_contributor)
    for (Plot& p : part) plots.push_back(std::move(p));
  return plots;
}

}  // namespace deb::report
