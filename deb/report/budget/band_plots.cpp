#include "deb/report/budget/band_plots.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "deb/budget/failure_guidance.h"
#include "deb/core/error.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr const char* kBarEdge = "#303030";
constexpr const char* kRestColour = "#c8c8c8";  // the bar of the contributors past the largest

// One group of bars: a band, or a band requirement's range.
struct Group {
  double lo_hz = 0.0, hi_hz = 0.0;
  double variance = 0.0;
  std::vector<double> contributor_variance;
  std::optional<BandRequirementResult> requirement;
};

bool SameBand(double lo_a, double hi_a, double lo_b, double hi_b) {
  return std::fabs(lo_a / lo_b - 1.0) < 1e-9 && std::fabs(hi_a / hi_b - 1.0) < 1e-9;
}

}  // namespace

std::vector<BandBar> BandBars(const OutputResult& out, const FrequencyGrid& grid, std::string* what) {
  PlotLevel level = GroupLevel(out, grid, "");
  const bool grouped =
      out.contributors.size() > kMostBarsPerBand && level.out.contributors.size() < out.contributors.size();
  if (!grouped) {  // the contributors themselves
    level.out = out;
    level.styles.clear();
    level.members.clear();
    for (std::size_t c = 0; c < out.contributors.size(); ++c) {
      level.styles.push_back(ContributorStyle(c));
      level.members.push_back({c});
    }
  }
  std::string words = grouped ? "each top-level group (the sum of its members, \"name/\") and contributor in no group"
                              : "each contributor";
  std::vector<BandBar> bars;
  for (std::size_t i : ShareOrder(level.out))
    bars.push_back(
        {level.out.contributors[i].name, level.styles[i], level.members[i], level.out.contributors[i].variance});
  if (bars.size() > kMostBarsPerBand) {
    BandBar rest;
    rest.name = "the other " + std::to_string(bars.size() - (kMostBarsPerBand - 1));
    rest.style.colour = kRestColour;
    for (std::size_t i = kMostBarsPerBand - 1; i < bars.size(); ++i) {
      rest.members.insert(rest.members.end(), bars[i].members.begin(), bars[i].members.end());
      rest.variance += bars[i].variance;
    }
    bars.resize(kMostBarsPerBand - 1);
    bars.push_back(std::move(rest));
    words += " (the " + std::to_string(kMostBarsPerBand - 1) + " largest, then the rest in one bar)";
  }
  if (what) *what = words;
  return bars;
}

Plot BandsPlot(const BudgetResult& result, std::size_t o, int digits) {
  DEB_DEMAND(o < result.outputs.size());
  const OutputResult& out = result.outputs[o];
  const std::string unit = DisplayUnit(out.unit);
  std::string what;
  const std::vector<BandBar> items = BandBars(out, result.grid, &what);
  const std::size_t n = items.size();

  std::vector<Group> groups;
  for (const BandResult& b : out.bands) groups.push_back({b.band.lo_hz, b.band.hi_hz, b.variance, b.contributor_variance, {}});
  for (const BandRequirementResult& r : out.band_requirements) {
    const auto same = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
      return SameBand(g.lo_hz, g.hi_hz, r.requirement.lo_hz, r.requirement.hi_hz);
    });
    if (same != groups.end()) {
      same->requirement = r;
      continue;
    }
    groups.push_back({r.requirement.lo_hz, r.requirement.hi_hz, r.variance,
                      VarianceWithin(out, result.grid, r.requirement.lo_hz, r.requirement.hi_hz), r});
  }
  const std::size_t bands = groups.size();

  Plot p;
  p.name = FileStem(out.name) + "_bands";
  p.kind = PlotKind::kBands;
  p.output = static_cast<int>(o);
  p.caption = "RMS of " + out.name + " per frequency band: the band's total, then " + what + ", largest first.";
  if (!out.band_requirements.empty())
    p.caption += " Each band requirement is a red bracket behind the bars of its range (a group of its own "
                 "where the range is not one of the bands); a failing total has a red outline and reads FAIL.";

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.outline.name << ", output " << out.name << ": RMS in "
      << unit << " per band, in total and per bar (" << what
      << "); failing_total: the total where the band's requirement fails\n";
  csv << "group,lo_hz,hi_hz,total,failing_total";
  for (const BandBar& item : items) csv << ',' << CsvField(item.name);
  csv << '\n';
  double top = 0.0, bottom = HUGE_VAL, smallest_total = HUGE_VAL;
  for (std::size_t b = 0; b < bands; ++b) {
    const Group& g = groups[b];
    const double total = std::sqrt(g.variance);
    const bool fails = g.requirement && !g.requirement->pass();
    csv << b + 1 << ',' << CsvNumber(g.lo_hz) << ',' << CsvNumber(g.hi_hz) << ',' << CsvNumber(total) << ','
        << CsvNumber(fails ? total : 0.0);
    top = std::max(top, total);
    if (g.requirement) top = std::max(top, g.requirement->requirement.rms_max);
    if (g.variance > 0.0) smallest_total = std::min(smallest_total, total);
    for (const BandBar& item : items) {
      const double rms = std::sqrt(item.Of(g.contributor_variance));
      csv << ',' << CsvNumber(rms);
      if (rms > 0.0) bottom = std::min(bottom, rms);
    }
    csv << '\n';
  }
  p.csv = csv.str();

  const double slot = 0.84 / static_cast<double>(n + 1);  // total + contributors share 84 % of a band
  const auto offset = [&](std::size_t slot_index) {
    return (static_cast<double>(slot_index) - 0.5 * static_cast<double>(n)) * slot;
  };
  FigurePanel panel;
  panel.title = Enhanced(out.name) + ": RMS per frequency band";
  panel.x.min = 0.5;
  panel.x.max = static_cast<double>(bands) + 0.5;
  // The unit once, on the axis, and over more than 4 bands the labels turned
  // by 30°: they do not run together where the figure is narrow (report.pdf).
  panel.x.label = "frequency band [Hz]";
  panel.x.minor_grid = false;
  if (bands > 4) panel.x.tic_rotation_deg = 30;
  for (std::size_t b = 0; b < bands; ++b)
    panel.x.tics.push_back({static_cast<double>(b + 1), std::string(b >= out.bands.size() ? "requirement\n" : "") +
                                                            HzLabel(groups[b].lo_hz) + "–" + HzLabel(groups[b].hi_hz)});
  panel.y.label = "RMS in band [" + UnitLabel(unit) + "]";
  panel.y.scale = AxisScale::kLog;
  panel.y.format = "10^{%L}";
  panel.y2.shown = false;
  if (top > 0.0) {
    // Five decades below the largest bar, deeper if a band's total needs it.
    const double lo = std::min(std::max(bottom, top * 1e-5), smallest_total);
    panel.y.min = std::pow(10.0, std::floor(std::log10(lo)));
    panel.y.max = std::pow(10.0, std::ceil(std::log10(top * 2.0)));
  } else {
    panel.y.min = 0.1;
    panel.y.max = 10.0;
    panel.note = "every contributor is zero on this output";
  }
  panel.bar_width = slot * 0.9;
  panel.key.title = "RMS [" + UnitLabel(unit) + "]";
  const std::string data = p.name + ".csv";
  FigureSeries total;
  total.name = "total";
  total.key = "total";
  total.kind = SeriesKind::kBars;
  total.data = data;
  total.x_offset = offset(0);
  total.y_columns = {4};
  total.colour = kTotalColour;
  total.edge_colour = kBarEdge;
  panel.series.push_back(total);
  for (std::size_t i = 0; i < n; ++i) {
    const SeriesStyle& st = items[i].style;
    FigureSeries s;
    s.name = items[i].name;
    s.key = Enhanced(s.name);
    s.kind = SeriesKind::kBars;
    s.data = data;
    s.x_offset = offset(i + 1);
    s.y_columns = {6 + i};
    s.colour = st.colour;
    s.fill_pattern = st.fill_pattern;
    s.hatch_colour = st.hatch_colour;
    s.edge_colour = kBarEdge;
    panel.series.push_back(s);
  }
  bool any_fail = false;
  for (std::size_t b = 0; b < bands; ++b) {
    if (!groups[b].requirement) continue;
    const BandRequirementResult& r = *groups[b].requirement;
    FigureAnnotation limit;
    limit.kind = AnnotationKind::kSegment;
    limit.x0 = static_cast<double>(b + 1) + offset(0) - 0.5 * slot;
    limit.x1 = static_cast<double>(b + 1) + offset(n) + 0.5 * slot;
    limit.y0 = limit.y1 = r.requirement.rms_max;
    limit.colour = kRequirementColour;
    limit.dash = kRequirementDash;
    limit.width = 3.0;
    limit.behind = true;  // the bars it limits in front of it: a bar over it is seen to pass it
    limit.bracket = true;
    if (panel.annotations.empty()) limit.key = "band requirement";  // one key entry for all
    panel.annotations.push_back(limit);
    FigureAnnotation text;
    text.kind = AnnotationKind::kLabel;
    text.x0 = static_cast<double>(b + 1) + offset(0) - 0.5 * slot;
    text.y0 = std::max(r.requirement.rms_max, r.rms());  // above the segment and the total bar
    text.colour = kRequirementColour;
    text.label = "≤ " + Short(r.requirement.rms_max) + (r.pass() ? ": pass" : ": FAIL, " + SigLabel(r.rms(), digits));
    text.label_dx = 0.0;
    text.label_dy = 0.9;
    panel.annotations.push_back(text);
    any_fail = any_fail || !r.pass();
  }
  if (any_fail) {  // drawn over the total bar: a red outline
    FigureSeries failing = total;
    failing.name = "failing total";
    failing.key = "total of a failing band";
    failing.y_columns = {5};
    failing.colour = kTotalColour;
    failing.edge_colour = kRequirementColour;
    failing.edge_width = 2.0;  // the black bar still shows inside it in report.pdf
    panel.series.insert(panel.series.begin() + 1, failing);
  }
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace deb::report
