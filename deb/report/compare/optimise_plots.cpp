#include "deb/report/compare/optimise_plots.h"

#include <cmath>
#include <sstream>

#include "deb/report/compare/sweep_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "deb/version.h"

namespace deb::report {

namespace {

std::string AxisTitle(const DesignVariable& v) {
  return Enhanced(v.name) + (v.unit.empty() ? "" : " [" + UnitLabel(v.unit) + "]");
}

Plot History(const OptimiseResult& r) {
  Plot p;
  p.name = "optimise_history";
  p.kind = PlotKind::kOverview;
  p.caption = "The objective (" + r.objective.Text() + ") of every budget evaluated, by start (with gradients, each "
              "step's gradient evaluations a short plateau); the nominal design dotted. Designs where the budget "
              "failed are left out.";
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", optimise: objective of each evaluation; one block per start\n";
  for (std::size_t k = 0; k < r.starts.size(); ++k) {
    if (k) csv << "\n\n";
    csv << "# start " << k + 1 << "\nevaluation,objective\n";
    std::size_t index = 0;
    for (const DesignEvaluation& e : r.history) {
      if (e.start != static_cast<int>(k)) continue;
      ++index;
      if (std::isfinite(e.objective)) csv << index << ',' << CsvNumber(e.objective) << '\n';
    }
  }
  p.csv = csv.str();
  FigurePanel panel;
  panel.title = Enhanced("optimise: " + r.objective.Text() + " by evaluation");
  panel.x.label = "evaluation (of its start)";
  panel.y.label = Enhanced(r.objective.Text());
  panel.y2.shown = false;
  panel.key.placement = r.starts.size() > 1 ? KeyPlacement::kOutsideRight : KeyPlacement::kNone;
  for (std::size_t k = 0; k < r.starts.size(); ++k) {
    FigureSeries s;
    s.name = "start " + std::to_string(k + 1);
    s.key = k == r.best ? s.name + " (optimum)" : s.name;
    s.data = p.name + ".csv";
    s.block = static_cast<int>(k);
    s.y_columns = {2};
    s.colour = ContributorStyle(k).colour;
    s.width = k == r.best ? 2.5 : 1.2;
    s.point_type = 7;
    s.point_size = 0.4;
    panel.series.push_back(s);
  }
  FigureAnnotation nominal;
  nominal.kind = AnnotationKind::kHorizontalLine;
  nominal.y0 = r.nominal_objective;
  nominal.colour = "#404040";
  nominal.dash = "(3,4)";
  nominal.width = 1.5;
  panel.annotations.push_back(nominal);
  p.figure.panels.push_back(panel);
  p.script = EmitFigure(p.figure);
  return p;
}

Plot Map(const OptimiseResult& r, const DesignMap& m) {
  const DesignVariable &vx = r.variables[0], &vy = r.variables[1];
  std::vector<double> x, y;
  for (double v : m.x) x.push_back(v / vx.unit_si);
  for (double v : m.y) y.push_back(v / vy.unit_si);
  Plot p;
  p.name = "optimise_map";
  p.kind = PlotKind::kOverview;
  p.caption = "The objective (" + r.objective.Text() + ") over the bounds of " + vx.name + " and " + vy.name + " (" +
              std::to_string(x.size()) + " x " + std::to_string(y.size()) +
              " designs), the requirements' boundary in red, the best start's path and the optimum ringed.";
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", optimise: block 0 the grid (x, y, objective), block 1 the optimum, block 2 "
         "the requirements' boundary (x, y, z, dx, dy, dz per segment), block 3 the best start's path\n";
  csv << CsvField(vx.name) << ',' << CsvField(vy.name) << ",objective\n";
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i) csv << '\n';
    for (std::size_t j = 0; j < y.size(); ++j)
      csv << CsvNumber(x[i]) << ',' << CsvNumber(y[j]) << ',' << CsvNumber(m.objective[i][j]) << '\n';
  }
  const OptimiseStart& best = r.starts[r.best];
  csv << "\n\n# optimum\n" << CsvNumber(best.values[0] / vx.unit_si) << ',' << CsvNumber(best.values[1] / vy.unit_si)
      << ',' << CsvNumber(best.objective) << '\n';
  csv << "\n\n# boundary\n";
  std::size_t segments = 0;
  for (const ContourSegment& c : LevelSegments(x, y, m.worst_ratio, 1.0)) {
    csv << CsvNumber(c.x0) << ',' << CsvNumber(c.y0) << ",0," << CsvNumber(c.x1 - c.x0) << ','
        << CsvNumber(c.y1 - c.y0) << ",0\n";
    ++segments;
  }
  if (segments == 0) csv << "NaN,NaN,NaN,NaN,NaN,NaN\n";
  csv << "\n\n# path\n";
  for (const DesignEvaluation& e : r.history)
    if (e.start == static_cast<int>(r.best) && std::isfinite(e.objective))
      csv << CsvNumber(e.values[0] / vx.unit_si) << ',' << CsvNumber(e.values[1] / vy.unit_si) << ','
          << CsvNumber(e.objective) << '\n';
  p.csv = csv.str();

  FigurePanel panel;
  panel.title = Enhanced("optimise: " + r.objective.Text() + " over " + vx.name + " and " + vy.name);
  panel.x.label = AxisTitle(vx);
  panel.y.label = AxisTitle(vy);
  panel.x.min = x.front();
  panel.x.max = x.back();
  panel.y.min = y.front();
  panel.y.max = y.back();
  panel.x.grid = panel.y.grid = panel.x.minor_grid = panel.y.minor_grid = false;
  panel.y2.shown = false;
  panel.palette = kMapPalette;
  panel.colour_axis.label = Enhanced(r.objective.Text());
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
  panel.series.push_back(layer("objective", SeriesKind::kHeatMap, 0));
  if (segments > 0) {
    FigureSeries boundary = layer("boundary", SeriesKind::kSegments, 2);
    boundary.dx_column = 4;
    boundary.dy_column = 5;
    boundary.key = "requirements' boundary";
    boundary.colour = kRequirementColour;
    boundary.width = 3.0;
    panel.series.push_back(boundary);
  }
  FigureSeries path = layer("path", SeriesKind::kPoints, 3);
  path.key = "designs evaluated (best start)";
  path.point_type = 7;
  path.point_size = 0.5;
  path.colour = "#404040";
  panel.series.push_back(path);
  FigureSeries ring = layer("optimum", SeriesKind::kPoints, 1);
  ring.key = "optimum: " + SigLabel(best.objective);
  ring.point_type = 6;
  ring.point_size = 3.0;
  ring.width = 2.5;
  ring.colour = kTotalColour;
  panel.series.push_back(ring);
  p.figure.panels.push_back(panel);
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace

std::vector<Plot> OptimisePlots(const OptimiseResult& result, const std::optional<DesignMap>& map) {
  std::vector<Plot> plots = {History(result)};
  if (map) plots.push_back(Map(result, *map));
  return plots;
}

}  // namespace deb::report
