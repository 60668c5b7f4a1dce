#include "deb/report/budget/path_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/path_response.h"
#include "deb/budget/response_traces.h"
#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/parallel.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/phase_axis.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"
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

// Phase in degrees, unwrapped along the grid (steps over 180° are taken as
// wraps), shifted by whole turns so that the first frequency shown lies in
// (-180°, 180°].
std::vector<double> UnwrappedPhaseDeg(const std::vector<double>& phase_rad, const std::vector<double>& f,
                                      double lo_hz) {
  std::vector<double> deg(phase_rad.size());
  double turns = 0.0;
  for (std::size_t i = 0; i < phase_rad.size(); ++i) {
    if (i) {
      const double step = phase_rad[i] - phase_rad[i - 1];
      if (step > kPi) turns -= 1.0;
      else if (step < -kPi) turns += 1.0;
    }
    deg[i] = (phase_rad[i] + 2.0 * kPi * turns) * 180.0 / kPi;
  }
  std::size_t first = 0;
  while (first + 1 < f.size() && f[first] < lo_hz) ++first;
  if (!deg.empty()) {
    const double shift = 360.0 * std::ceil((deg[first] - 180.0) / 360.0);
    for (double& d : deg) d -= shift;
  }
  return deg;
}

// Bode magnitude over phase of one (path, output) pair, for the contributors
// `users` (indices into the outline's contributors, the first one's source
// feeding `r`).
Plot PathPlot(const BudgetResult& result, const std::vector<std::size_t>& users, std::size_t o, const PathResponse& r,
              const std::string& suffix) {
  const std::vector<double>& f = r.Frequencies(result.grid.f_hz());
  const BudgetOutline& budget = result.outline;
  const Contributor& contributor = budget.contributors[users.front()];
  const OutputResult& output = result.outputs[o];
  const bool weighted = budget.outputs[o].weighting.has_value();
  const std::size_t m = r.gain2.size();
  std::string names;
  for (std::size_t c : users) names += (names.empty() ? "" : ", ") + budget.contributors[c].name;
  Plot p;
  p.name = "path_" + FileStem(contributor.path) + "_to_" + FileStem(output.name) + suffix;
  p.kind = PlotKind::kPath;
  p.output = static_cast<int>(o);
  const std::optional<std::pair<double, double>>& path_poles = result.traces->poles_hz[users.front()];
  const std::pair<double, double> poles_hz = path_poles.value_or(std::make_pair(0.0, 0.0));
  const FrequencyRange display = DisplayRange(result.outputs[o], result.grid);
  const FrequencyRange range = PathRange(path_poles, display, result.grid);
  const bool widened = range.lo_hz < display.lo_hz || range.hi_hz > display.hi_hz;
  const std::string poles = (poles_hz.first == poles_hz.second ? Sig(poles_hz.first)
                                                                 : Sig(poles_hz.first) + "–" + Sig(poles_hz.second)) +
                            " Hz";
  // The path with the inputs its contributors drive, if they select some: "closed(F_act)".
  const std::string through = ContributorPathKey(contributor);
  p.label = "path " + through + " to " + output.name + ", used by " + names;
  p.caption = "Bode magnitude and phase (unwrapped) of the transfer through path " + through + " to " +
              output.name + (weighted ? ", weighting included" : "") +
              ", per source channel, from source unit " + UnitText(budget.SourceOf(contributor).unit) + "; used by " +
              (users.size() == 1 ? "contributor " : std::to_string(users.size()) + " contributors: ") + names + "." +
              RangeCaption(range) +
              (widened ? " The range reaches half a decade beyond the natural frequency of every pole of the path (f_n " +
                             poles + ")."
                       : "");

  std::vector<std::vector<double>> phase_deg(m);
  for (std::size_t k = 0; k < m; ++k) phase_deg[k] = UnwrappedPhaseDeg(r.phase_rad[k], f, range.lo_hz);
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.outline.name << ": |h| in " << r.unit
      << " and unwrapped phase in degrees of path " << through << " to output " << output.name
      << ", per source channel; used by " << names << "\n";
  csv << "frequency_hz";
  for (const auto& ch : r.channels) csv << ',' << CsvField(ch);
  for (const auto& ch : r.channels) csv << ',' << CsvField(ch + " phase_deg");
  csv << '\n';
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
    for (std::size_t k = 0; k < m; ++k) csv << ',' << CsvNumber(phase_deg[k][i]);
    csv << '\n';
  }
  p.csv = csv.str();
  const double floor = top > 0.0 ? std::pow(10.0, std::floor(std::log10(std::max(bottom, top * std::pow(10.0, -kDecades))))) : 0.0;

  FigurePanel mag, phase;
  mag.x = FrequencyFigureAxis(range, result.grid,
                              widened ? std::string(kDisplayTailNote) + ", widened to the path's poles (f_{n} " + poles + ")"
                                      : kDisplayTailNote);
  phase.x = mag.x;
  mag.y.label = "magnitude |h| [" + UnitLabel(r.unit) + "]";
  mag.y.scale = AxisScale::kLog;
  mag.y.format = "10^{%L}";
  mag.y2.shown = phase.y2.shown = false;
  if (top > 0.0) {
    mag.y.min = floor;
    mag.y.max = std::pow(10.0, std::ceil(std::log10(top * 1.2)));
  } else {
    mag.y.min = 0.1;
    mag.y.max = 10.0;
    mag.note = "zero transfer at every frequency";
  }
  mag.key.title = "source channel";
  mag.height = 1.6;
  phase.y.label = "phase [°]";
  phase.y.format = "%g";
  phase.key.placement = KeyPlacement::kNone;
  const std::string data = p.name + ".csv";
  // One channel of several sources: the curve is the path's, named so.
  const bool one_curve = m == 1 && users.size() > 1;
  if (one_curve) mag.key.title = "path";
  const auto name = [&](std::size_t k) {
    return one_curve ? contributor.path : k < r.channels.size() ? r.channels[k] : std::to_string(k + 1);
  };
  const std::vector<std::vector<std::size_t>> groups = CoincidentChannels(r.gain2, f, range, floor);
  // Markers spaced over the rows a curve has, about kChannelMarkers of them.
  const std::size_t rows = static_cast<std::size_t>(std::count(p.csv.begin(), p.csv.end(), '\n')) - 2;
  const std::size_t interval = std::max<std::size_t>(1, rows / kChannelMarkers);
  double phase_lo = HUGE_VAL, phase_hi = -HUGE_VAL;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t k = groups[g].front();
    // One channel: the contributor's own style, or black for a path several
    // contributors share; several channels: the channel family, with markers.
    SeriesStyle st = m == 1 && users.size() == 1 ? ContributorStyle(users.front()) : ChannelStyle(k);
    if (one_curve) {
      st.colour = kTotalColour;
      st.dash = "solid";
      st.point_type = 0;
    }
    std::string title;
    for (std::size_t j : groups[g]) title += (title.empty() ? "" : " = ") + Enhanced(name(j));
    FigureSeries s;
    s.name = title;
    s.key = title + (channel_top[k] == 0.0 ? " (zero)" : channel_top[k] < floor ? " (below the axis)" : "");
    s.data = data;
    s.y_columns = {k + 2};
    s.colour = st.colour;
    s.dash = st.dash;
    if (st.point_type) {
      // Markers of successive curves are staggered along x, so that curves
      // running close together keep their markers apart.
      s.point_type = st.point_type;
      s.marker_every = static_cast<int>(interval);
      s.marker_first = static_cast<int>((g * interval) / groups.size());
    }
    mag.series.push_back(s);
    // A zero transfer has no phase, and one below the magnitude axis
    // (numerically zero, or negligible) only a meaningless one.
    if (channel_top[k] == 0.0 || channel_top[k] < floor) continue;
    FigureSeries ph = s;
    ph.key.clear();
    ph.y_columns = {2 + m + k};
    phase.series.push_back(ph);
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f[i] >= range.lo_hz && f[i] <= range.hi_hz) {
        phase_lo = std::min(phase_lo, phase_deg[k][i]);
        phase_hi = std::max(phase_hi, phase_deg[k][i]);
      }
  }
  if (phase_hi >= phase_lo) {  // whole steps of 45° · 2^k, at most 5 of them, at least 90° tall
    SetPhaseAxis(phase.y, phase_lo, phase_hi, 90.0);
  }
  p.figure.title = "path " + Enhanced(through) + " → " + Enhanced(output.name) +
                   (weighted ? " (weighted)" : "") + ", used by " +
                   (users.size() <= 3 ? Enhanced(names) : std::to_string(users.size()) + " contributors");
  p.figure.panels = {std::move(mag), std::move(phase)};
  p.script = EmitFigure(p.figure);
  if (groups.size() < m)
    p.caption += " Channels whose curves coincide are drawn once and named together (a = b).";
  return p;
}

}  // namespace

FrequencyRange PathRange(const std::optional<std::pair<double, double>>& poles, const FrequencyRange& display,
                         const FrequencyGrid& grid) {
  if (!poles) return display;
  const auto [first, last] = *poles;
  const double margin = std::sqrt(10.0);  // half a decade
  FrequencyRange r = display;
  if (first / margin < r.lo_hz)
    r.lo_hz = std::max(std::pow(10.0, std::floor(std::log10(first / margin) + 1e-9)), grid.min_hz());
  if (last * margin > r.hi_hz)
    r.hi_hz = std::min(std::pow(10.0, std::ceil(std::log10(last * margin) - 1e-9)), grid.max_hz());
  r.trimmed = r.lo_hz > grid.min_hz() * (1 + 1e-9) || r.hi_hz < grid.max_hz() * (1 - 1e-9);
  return r;
}

std::vector<Plot> PathPlots(const BudgetResult& result, int threads) {
  const BudgetOutline& budget = result.outline;
  // Contributors sharing a path, a source unit and source channels see the
  // same transfer: one plot per such group and output, naming them all.
  std::vector<std::vector<std::size_t>> groups;
  const auto same = [&](std::size_t a, std::size_t b) {
    const Contributor &ca = budget.contributors[a], &cb = budget.contributors[b];
    const SourceOutline &sa = budget.SourceOf(ca), &sb = budget.SourceOf(cb);
    // One channel is named after its source: only several channels must agree by name.
    // Contributors that drive different inputs of one path see different
    // transfers (ContributorPathKey names the inputs).
    return ContributorPathKey(ca) == ContributorPathKey(cb) && sa.unit == sb.unit &&
           sa.channels.size() == sb.channels.size() &&
           (sa.channels.size() == 1 || sa.channels == sb.channels);
  };
  for (std::size_t c = 0; c < budget.contributors.size(); ++c) {
    auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& group) { return same(group.front(), c); });
    if (g == groups.end()) groups.push_back({c});
    else g->push_back(c);
  }
  // A group whose path another group also uses (a different source unit)
  // names its plots after its first contributor, so that names stay distinct.
  std::vector<std::string> suffix(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::string& path = budget.contributors[groups[g].front()].path;
    if (std::count_if(groups.begin(), groups.end(),
                      [&](const auto& other) { return budget.contributors[other.front()].path == path; }) > 1)
      suffix[g] = "_from_" + FileStem(budget.contributors[groups[g].front()].name);
  }
  DEB_DEMAND(result.traces && result.traces->paths.size() == budget.contributors.size());
  std::vector<std::vector<Plot>> per_group(groups.size());
  ParallelForEach(
      groups.size(),
      [&](std::size_t g) {
        const std::vector<PathResponse>& r = result.traces->paths[groups[g].front()];
        for (std::size_t o = 0; o < result.outputs.size(); ++o)
          per_group[g].push_back(PathPlot(result, groups[g], o, r[o], suffix[g]));
      },
      threads);
  std::vector<Plot> plots;
  for (std::vector<Plot>& part : per_group)
    for (Plot& p : part) plots.push_back(std::move(p));
  return plots;
}

}  // namespace deb::report
