#include "deb/report/compare/sweep_plots.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <string>

#include "deb/budget/sweep_ranking.h"
#include "deb/core/error.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "deb/version.h"

namespace deb::report {
namespace {

// Variants grouped by the values of parameters 2..n (first seen first),
// each group ordered by parameter 1.
struct Groups {
  std::vector<std::vector<double>> order;
  std::map<std::vector<double>, std::vector<std::size_t>> members;
};

Groups GroupByRest(const std::vector<std::vector<double>>& rows) {
  Groups g;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<double> rest(rows[i].begin() + 1, rows[i].end());
    if (!g.members.count(rest)) g.order.push_back(rest);
    g.members[rest].push_back(i);
  }
  for (auto& [rest, members] : g.members)
    std::stable_sort(members.begin(), members.end(),
                     [&](std::size_t a, std::size_t b) { return rows[a][0] < rows[b][0]; });
  return g;
}

// The axis of parameter p: labelled by its title; a textual parameter's
// values named at their indices, the range padded by `pad` at either end.
FigureAxis ParameterAxis(const SweepParameter& p, double pad) {
  FigureAxis a;
  a.label = Enhanced(p.AxisTitle());
  if (p.texts.empty()) return a;
  a.min = -pad;
  a.max = static_cast<double>(p.texts.size()) - 1.0 + pad;
  for (std::size_t i = 0; i < p.texts.size(); ++i) a.tics.push_back({static_cast<double>(i), Enhanced(p.texts[i])});
  return a;
}

// Positive numeric values over two decades or more (a log: range) go on a log axis.
bool LogAxis(const SweepParameter& p) {
  if (!p.texts.empty() || p.values.empty()) return false;
  const auto [lo, hi] = std::minmax_element(p.values.begin(), p.values.end());
  return *lo > 0.0 && *hi >= 100.0 * *lo;
}

std::string RestLabel(const SweepSpec& spec, const std::vector<double>& rest) {
  std::string label;
  for (std::size_t k = 1; k < spec.parameters.size(); ++k)
    label += (k > 1 ? ", " : "") + spec.parameters[k].Setting(rest[k - 1]);
  return label;
}

Plot SmallMultiples(const SweepSpec& spec, const std::vector<std::vector<double>>& rows,
                    const std::vector<BudgetResult>& results, std::size_t o, const Groups& groups) {
  const OutputResult& out0 = results[0].outputs[o];
  const SweepParameter& first = spec.parameters[0];
  const std::size_t panels = std::min(groups.order.size(), kMaxSweepPanels);
  Plot p;
  p.name = FileStem(out0.name) + "_sweep";
  p.kind = PlotKind::kOverview;
  // Up to four panels at a run's figure height: with the map beside it, two
  // figures to a page of sweep.pdf (at the overview's height each took one).
  if (panels <= 4) p.pdf_height_px = 420;
  p.output = static_cast<int>(o);
  p.caption = "RMS of " + out0.name + " against " + first.Name() +
              (groups.order.size() > 1 ? ", one panel per value of the other parameters" : "") +
              "; colour: contributor, total in black" + (out0.rms_max ? ", requirement dashed red" : "") + ".";
  if (groups.order.size() > panels)
    p.caption += " The first " + std::to_string(panels) + " of " + std::to_string(groups.order.size()) +
                 " combinations are drawn; sweep.csv holds all.";

  // One RMS axis for every panel: from 0 to the largest total or the requirement.
  // A total computed as rounding (RoundingZero: an axis the variant leaves
  // unexcited) does not set the axis: nizamoglu2015_sweep's beta_velocity at
  // K_v = h = 0, 4e-11, stretched it over 12 decades; its line runs off the
  // bottom.
  double highest = 0.0, lowest = HUGE_VAL;
  for (const BudgetResult& r : results) highest = std::max(highest, r.outputs[o].rms());
  double top = std::max(out0.rms_max.value_or(0.0), highest);
  bool rounding = false;
  for (const BudgetResult& r : results) {
    const double rms = r.outputs[o].rms();
    if (rms > 0.0 && RoundingZero(rms * rms, highest * highest)) rounding = true;
    else if (rms > 0.0) lowest = std::min(lowest, rms);
  }
  if (!(top > 0.0)) top = 1.0;
  // Totals more than 5x apart on a log axis: on a linear one, the
  // nizamoglu2015 sweep's K_v = 0 (80-110 um/s) squeezed the 10-20 that
  // matter into the bottom seventh of every panel.
  const bool log_rms = lowest < HUGE_VAL && top / lowest > 5.0;
  // On a log axis, down to the smallest contributor too (the floor fell off
  // nizamoglu2015_sweep's z_position from K_v = 55 on, the axis ending at
  // its lowest total), but over three decades at most.
  double bottom = lowest;
  for (const BudgetResult& r : results)
    for (const ContributorResult& c : r.outputs[o].contributors)
      if (c.variance > 0.0 && !RoundingZero(c.variance, highest * highest)) bottom = std::min(bottom, std::sqrt(c.variance));
  bottom = std::max(bottom, top * 1e-3);
  if (log_rms) p.caption += " RMS on a log axis: the totals span more than a factor 5.";
  if (rounding)
    p.caption += " A variant computed as rounding (≈ 0: the model leaves the output unexcited there) runs off the "
                 "bottom of the axis.";

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", sweep, output " << out0.name << " RMS in " << out0.unit
      << "; one block per combination of the other parameters\n";
  for (std::size_t b = 0; b < groups.order.size(); ++b) {
    const auto& rest = groups.order[b];
    const std::string label = RestLabel(spec, rest);
    if (b) csv << "\n\n";
    csv << "# " << (label.empty() ? "all variants" : label) << "\n" << CsvField(first.key_path);
    for (const auto& c : out0.contributors) csv << ',' << CsvField(c.name);
    csv << ",total\n";
    for (std::size_t i : groups.members.at(rest)) {
      const OutputResult& r = results[i].outputs[o];
      csv << CsvNumber(rows[i][0]);
      for (const auto& c : r.contributors) csv << ',' << CsvNumber(std::sqrt(c.variance));
      csv << ',' << CsvNumber(r.rms()) << '\n';
    }
  }
  p.csv = csv.str();

  const std::size_t cols = panels <= 3 ? panels : panels <= 4 ? 2 : panels <= 9 ? 3 : 4;
  // The unit in the title too: report.pdf's narrow canvas has no room left
  // of a multiplot's fixed margin for the y label, which the PNG shows.
  const std::string title = Enhanced(out0.name) + ": RMS [" + UnitLabel(out0.unit) + "] against " + Enhanced(first.Name());
  p.figure.title = title;
  p.figure.columns = cols;
  const std::string file = p.name + ".csv";
  for (std::size_t b = 0; b < panels; ++b) {
    FigurePanel panel;
    panel.title = panels > 1 ? Enhanced(RestLabel(spec, groups.order[b])) : title;
    panel.x = ParameterAxis(first, 0.5);
    if (LogAxis(first)) panel.x.scale = AxisScale::kLog;
    // The axis named under the bottom panel of each column only: above it,
    // the name ran into the title of the panel below.
    if (b + cols < panels) panel.x.label = "";
    panel.y.label = panels == 1 || b % cols == 0 ? "RMS [" + UnitLabel(out0.unit) + "]" : "";  // the left column's
    // One RMS axis for every panel.
    if (log_rms) {
      panel.y.scale = AxisScale::kLog;
      panel.y.min = std::pow(10.0, std::floor(std::log10(bottom / 2.0)));
      panel.y.max = top * 1.5;
    } else {
      panel.y.min = 0.0;
      panel.y.max = top * 1.08;
    }
    panel.y2.shown = false;
    // The key once, with the first panel, beside the panels.
    panel.key.placement =
        panels == 1 ? KeyPlacement::kOutsideRight : b == 0 ? KeyPlacement::kBesideGrid : KeyPlacement::kNone;
    const auto curve = [&](const std::string& name, std::size_t column) {
      FigureSeries s;
      s.name = name;
      s.key = b == 0 ? Enhanced(name) : "";
      s.data = file;
      s.block = static_cast<int>(b);
      s.y_columns = {column};
      s.point_type = 7;  // a dot at each variant
      s.point_size = 0.6;
      return s;
    };
    for (std::size_t c = 0; c < out0.contributors.size(); ++c) {
      FigureSeries s = curve(out0.contributors[c].name, c + 2);
      s.colour = ContributorStyle(c).colour;
      s.width = 3.0;
      panel.series.push_back(std::move(s));
    }
    // The total thin over contributors three times as wide, as in a run's
    // PSD: a contributor that is all of the total (the sweep's sensor_noise
    // from K_v = 25 on) still shows beside it.
    FigureSeries t = curve("total", out0.contributors.size() + 2);
    t.colour = kTotalColour;
    t.width = 1.0;
    panel.series.push_back(std::move(t));
    if (out0.rms_max) {
      FigureAnnotation limit;
      limit.kind = AnnotationKind::kHorizontalLine;
      limit.y0 = *out0.rms_max;
      limit.colour = kRequirementColour;
      limit.dash = kRequirementDash;
      limit.width = 1.5;
      if (b == 0) limit.key = "requirement: " + Short(*out0.rms_max);
      panel.annotations.push_back(limit);
    }
    p.figure.panels.push_back(std::move(panel));
  }
  p.script = EmitFigure(p.figure);
  return p;
}

// Indices of values sorted ascending.
std::vector<std::size_t> Ascending(const std::vector<double>& v) {
  std::vector<std::size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  return idx;
}

// A logarithmic colour bar over the RMS values [lo, hi], with at most
// kMapDecades of colour below the highest: a variant that is zero but for
// rounding (an axis decoupled by symmetry) would otherwise stretch the bar
// over 13 decades and paint the map one colour. Lower values take the
// lightest colour (the ring still marks the best), said in the bar's label
// and appended to `caption`. Ticks at 1, 2, 5 per decade; the ends labelled
// with the lowest and highest value shown unless a tick is within 8 % of the
// bar (a line of text on the bar of a map in report.pdf's 420 px: at 4 %,
// nizamoglu2015_sweep's "112" sat on the tick "100").
void LogColourBar(FigureAxis& bar, double lo, double hi, std::string& caption) {
  bar.scale = AxisScale::kLog;
  bar.format = "%g";
  constexpr double kMapDecades = 3.0;
  const double bottom = std::max(lo, hi * std::pow(10.0, -kMapDecades));
  if (bottom > lo) {
    bar.min = bottom;
    bar.max = hi;
    bar.label += " (below " + SigLabel(bottom, 3) + ": lightest)";
    caption += " Colours span 3 decades below the highest RMS; lower values (down to " + Sig(lo, 3) +
             ") take the lightest.";
  }
  for (int d = static_cast<int>(std::floor(std::log10(bottom))); d <= static_cast<int>(std::ceil(std::log10(hi))); ++d)
    for (const double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, d);
      if (v >= bottom * 0.999 && v <= hi * 1.001) bar.tics.push_back({v, Short(v)});
    }
  const double span = std::log(hi / bottom);
  for (const double end : {bottom, hi}) {
    bool near = false;
    for (const auto& [v, label] : bar.tics) near = near || std::fabs(std::log(v / end)) < 0.08 * span;
    if (!near) bar.tics.push_back({end, SigLabel(end, 3)});
  }
  std::sort(bar.tics.begin(), bar.tics.end());
}

Plot RequirementMap(const SweepSpec& spec, const std::vector<std::vector<double>>& rows,
                    const std::vector<BudgetResult>& results, std::size_t o) {
  const OutputResult& out0 = results[0].outputs[o];
  const SweepParameter &px = spec.parameters[0], &py = spec.parameters[1];
  const std::size_t nx = px.values.size(), ny = py.values.size();
  DEB_DEMAND(rows.size() == nx * ny);  // a grid, the last parameter fastest
  const std::vector<std::size_t> ix = Ascending(px.values), iy = Ascending(py.values);
  std::vector<double> x(nx), y(ny);
  std::vector<std::vector<double>> z(nx, std::vector<double>(ny));
  for (std::size_t i = 0; i < nx; ++i) x[i] = px.values[ix[i]];
  for (std::size_t j = 0; j < ny; ++j) y[j] = py.values[iy[j]];
  double hi = 0.0;
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t j = 0; j < ny; ++j) {
      z[i][j] = results[ix[i] * ny + iy[j]].outputs[o].rms();
      hi = std::max(hi, z[i][j]);
    }
  // The colours span the values that are not rounding (a variant the model
  // leaves unexcited, RoundingZero): such a variant takes the lightest.
  double lo = HUGE_VAL;
  bool rounding = false;
  for (const auto& column : z)
    for (const double v : column) {
      if (v > 0.0 && RoundingZero(v * v, hi * hi)) rounding = true;
      else lo = std::min(lo, v);
    }
  if (!(lo < HUGE_VAL)) lo = 0.0;
  const std::size_t best = BestVariant(results, o);

  Plot p;
  p.name = FileStem(out0.name) + "_map";
  p.kind = PlotKind::kOverview;
  p.pdf_height_px = 420;  // with the small multiples, two figures to a page
  p.output = static_cast<int>(o);
  p.caption = "Total RMS of " + out0.name + " over " + px.Name() + " and " + py.Name() +
              ", interpolated between the variants (dots); the best variant (lowest RMS) ringed" +
              (out0.rms_max ? ", the requirement's contour in red" : "") + ".";
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", sweep, output " << out0.name << ": total RMS in " << out0.unit
      << "; block 0 the grid, block 1 the best variant, block 2 the requirement's contour (x, y, z, dx, dy, dz per "
         "segment)\n";
  csv << CsvField(px.key_path) << ',' << CsvField(py.key_path) << ",total\n";
  for (std::size_t i = 0; i < nx; ++i) {
    if (i) csv << '\n';  // one scan line per value of the first parameter
    for (std::size_t j = 0; j < ny; ++j) csv << CsvNumber(x[i]) << ',' << CsvNumber(y[j]) << ',' << CsvNumber(z[i][j]) << '\n';
  }
  csv << "\n\n# best\n"
      << CsvNumber(rows[best][0]) << ',' << CsvNumber(rows[best][1]) << ',' << CsvNumber(results[best].outputs[o].rms())
      << '\n';
  // One row per segment (x, y, z, dx, dy, dz), drawn as headless vectors:
  // splot would join the rows of a block into a mesh.
  std::size_t segments = 0;
  csv << "\n\n# requirement\n";
  if (out0.rms_max)
    for (const ContourSegment& c : LevelSegments(x, y, z, *out0.rms_max)) {
      csv << CsvNumber(c.x0) << ',' << CsvNumber(c.y0) << ',' << CsvNumber(*out0.rms_max) << ','
          << CsvNumber(c.x1 - c.x0) << ',' << CsvNumber(c.y1 - c.y0) << ",0\n";
      ++segments;
    }
  if (segments == 0) csv << "NaN,NaN,NaN,NaN,NaN,NaN\n";  // keeps the block, so the indices stay
  p.csv = csv.str();

  FigurePanel panel;
  panel.title = Enhanced(out0.name + ": total RMS over " + px.Name() + " and " + py.Name());
  panel.x = ParameterAxis(px, 0.0);
  panel.y = ParameterAxis(py, 0.0);
  if (LogAxis(px)) panel.x.scale = AxisScale::kLog;
  if (LogAxis(py)) panel.y.scale = AxisScale::kLog;
  if (px.texts.empty()) panel.x.min = x.front(), panel.x.max = x.back();
  if (py.texts.empty()) panel.y.min = y.front(), panel.y.max = y.back();
  panel.x.grid = panel.y.grid = panel.x.minor_grid = panel.y.minor_grid = false;
  panel.y2.shown = false;
  panel.palette = kMapPalette;
  panel.colour_axis.label = "total RMS [" + UnitLabel(out0.unit) + "]";
  if (lo > 0.0 && hi / lo > 5.0) LogColourBar(panel.colour_axis, lo, hi, p.caption);  // a bad corner would wash out the rest
  if (rounding) {
    if (!panel.colour_axis.min) panel.colour_axis.min = lo;
    p.caption += " A variant computed as rounding (≈ 0: the model leaves the output unexcited there) takes the "
                 "lightest colour and does not set the scale.";
  }
  // The key below the map, never over it.
  panel.key.placement = KeyPlacement::kBelowMap;
  const std::string file = p.name + ".csv";
  const auto layer = [&](const std::string& name, SeriesKind kind, int block) {
    FigureSeries s;
    s.name = name;
    s.kind = kind;
    s.data = file;
    s.block = block;
    s.y_columns = {2};
    s.z_column = 3;
    return s;
  };
  panel.series.push_back(layer("total RMS", SeriesKind::kHeatMap, 0));
  FigureSeries variants = layer("variants", SeriesKind::kPoints, 0);
  variants.key = "variants";
  variants.point_type = 7;
  variants.point_size = 0.8;  // seen in the PNG and in sweep.pdf, both drawn from SVG
  variants.colour = "#404040";
  panel.series.push_back(variants);
  if (out0.rms_max) {
    FigureSeries contour = layer("requirement", SeriesKind::kSegments, 2);
    contour.dx_column = 4;
    contour.dy_column = 5;
    // Short: the key is one row below the map, and gnuplot leaves out an
    // entry that runs past the canvas (a long one took 'variants' with it).
    contour.key = "requirement: " + Short(*out0.rms_max);
    if (segments == 0)
      p.caption += lo > *out0.rms_max ? " Every variant fails the requirement (" + Short(*out0.rms_max) + ")."
                                      : " Every variant meets the requirement (" + Short(*out0.rms_max) + ").";
    contour.colour = kRequirementColour;
    contour.width = 3.0;
    if (segments == 0) {  // no piece to draw: the key names the requirement by a sample of its own
      FigureAnnotation entry;
      entry.kind = AnnotationKind::kKeyEntry;
      entry.key = contour.key;
      entry.colour = contour.colour;
      entry.width = contour.width;
      entry.point_type = 0;  // a line
      panel.annotations.push_back(entry);
      contour.key.clear();
    }
    panel.series.push_back(contour);
  }
  FigureSeries ring = layer("best", SeriesKind::kPoints, 1);
  // A best of rounding (a variant the model leaves unexcited) says so.
  const double best_rms = results[best].outputs[o].rms();
  ring.key = "best: " + (best_rms > 0.0 && RoundingZero(best_rms * best_rms, hi * hi) ? std::string("≈ 0 (rounding)")
                                                                                         : SigLabel(best_rms));
  ring.point_type = 6;
  ring.point_size = 3.0;
  ring.width = 2.5;
  ring.colour = kTotalColour;
  panel.series.push_back(ring);
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace

std::vector<ContourSegment> LevelSegments(const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<std::vector<double>>& z, double level) {
  DEB_DEMAND(z.size() == x.size());
  std::vector<ContourSegment> out;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    DEB_DEMAND(z[i].size() == y.size() && z[i + 1].size() == y.size());
    for (std::size_t j = 0; j + 1 < y.size(); ++j) {
      // Corners counter-clockwise; an edge is crossed where its ends lie on either side of level.
      const double cx[4] = {x[i], x[i + 1], x[i + 1], x[i]}, cy[4] = {y[j], y[j], y[j + 1], y[j + 1]};
      const double cz[4] = {z[i][j], z[i + 1][j], z[i + 1][j + 1], z[i][j + 1]};
      std::vector<std::pair<double, double>> crossings;
      for (int e = 0; e < 4; ++e) {
        const int f = (e + 1) % 4;
        const bool below_e = cz[e] < level, below_f = cz[f] < level;
        if (below_e == below_f) continue;
        const double t = (level - cz[e]) / (cz[f] - cz[e]);
        crossings.emplace_back(cx[e] + t * (cx[f] - cx[e]), cy[e] + t * (cy[f] - cy[e]));
      }
      for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
        out.push_back({crossings[k].first, crossings[k].second, crossings[k + 1].first, crossings[k + 1].second});
    }
  }
  return out;
}

std::vector<Plot> SweepPlots(const SweepSpec& spec, const std::vector<BudgetResult>& results) {
  const auto rows = spec.Variants();
  DEB_DEMAND(rows.size() == results.size());
  std::vector<Plot> plots;
  if (results.empty() || spec.parameters.empty()) return plots;
  const Groups groups = GroupByRest(rows);
  const bool map = spec.mode == SweepMode::kGrid && spec.parameters.size() == 2 &&
                   spec.parameters[0].values.size() >= 2 && spec.parameters[1].values.size() >= 2;
  for (std::size_t o = 0; o < results[0].outputs.size(); ++o) {
    plots.push_back(SmallMultiples(spec, rows, results, o, groups));
    if (map) plots.push_back(RequirementMap(spec, rows, results, o));
  }
  return plots;
}

}  // namespace deb::report
