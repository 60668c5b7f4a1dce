#include "deb/report/budget/loop_plots.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <iterator>
#include <sstream>

#include "deb/budget/response_traces.h"
#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/phase_axis.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"
#include "deb/systems/loop_margins.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr const char* kLoopColour = "#0e5274";  // L and S: a dark blue
constexpr const char* kComplementColour = "#e66e53";  // T: orange
constexpr const char* kMarginColour = "#b2182b";

// Linear interpolation of y over log f at f_hz.
double At(const std::vector<double>& f, const std::vector<double>& y, double f_hz) {
  const auto hi = std::lower_bound(f.begin(), f.end(), f_hz);
  if (hi == f.begin()) return y.front();
  if (hi == f.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(hi - f.begin());
  const double t = std::log(f_hz / f[k - 1]) / std::log(f[k] / f[k - 1]);
  return y[k - 1] + t * (y[k] - y[k - 1]);
}

FigureSeries Line(const std::string& name, const std::string& key, const std::string& data, std::size_t column,
                  const std::string& colour) {
  FigureSeries s;
  s.name = name;
  s.key = key;
  s.data = data;
  s.y_columns = {column};
  s.colour = colour;
  return s;
}

FigureAnnotation Level(double y, const std::string& key, const std::string& dash = "(6,4)") {
  FigureAnnotation a;
  a.kind = AnnotationKind::kHorizontalLine;
  a.y0 = y;
  a.colour = "#505050";
  a.dash = dash;
  a.width = 2.0;  // 1.5 pt in a PDF, as every line
  a.key = key;
  return a;
}

FigureAnnotation Marker(double x, double y, const std::string& label) {
  FigureAnnotation a;
  a.kind = AnnotationKind::kMarker;
  a.x0 = x;
  a.y0 = y;
  a.colour = kMarginColour;
  a.label = label;
  return a;
}

// A loop's responses on its trace's frequencies: L, |L|, the unwrapped
// phase of L in degrees (at the lowest frequency in (-360, 0]: a loop's
// phase is read against -180), |S| and |T|.
struct LoopCurves {
  std::vector<double> f;
  std::vector<std::complex<double>> l;
  std::vector<double> mag, phase, s_mag, t_mag;
};

LoopCurves Curves(const LoopTrace& trace) {
  const std::size_t n = trace.f_hz.size();
  LoopCurves c{trace.f_hz, std::vector<std::complex<double>>(n), std::vector<double>(n), std::vector<double>(n),
               std::vector<double>(n), std::vector<double>(n)};
  double turns = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    c.l[i] = trace.loop_gain[i];
    c.mag[i] = std::abs(c.l[i]);
    const double arg = std::arg(c.l[i]);
    if (i) {
      const double prev = c.phase[i - 1] * kPi / 180.0 - 2.0 * kPi * turns;
      if (arg - prev > kPi) turns -= 1.0;
      else if (arg - prev < -kPi) turns += 1.0;
    }
    c.phase[i] = (arg + 2.0 * kPi * turns) * 180.0 / kPi;
    c.s_mag[i] = 1.0 / std::abs(1.0 + c.l[i]);
    c.t_mag[i] = std::abs(c.l[i] / (1.0 + c.l[i]));
  }
  const double shift = 360.0 * std::ceil(c.phase.front() / 360.0);
  for (double& p : c.phase) p -= shift;
  return c;
}

// What every figure of one loop shares.
struct LoopFigures {
  const LoopResult& loop;
  LoopCurves curves;
  std::vector<std::size_t> rows;  // of the curves, as the CSV holds them (LoopRows)
  std::string stem, name, paths, csv;
  FigureAxis x_axis;
  int digits;
};

// The Nyquist plot's window (NyquistPlot), which the rows of the data keep
// the curve's shape in.
constexpr double kNyquistReMin = -3.0, kNyquistReMax = 1.5, kNyquistImMax = 2.25;

// The rows a reader can see in any of the loop's figures (PlotPoints): the
// magnitudes on log axes, the phase on its linear axis, and L itself within
// the Nyquist window (clamped to twice the window, so that the far parts of
// the curve do not set the tolerance).
std::vector<std::size_t> LoopRows(const LoopCurves& c) {
  const double lo = c.f.front(), hi = c.f.back();
  std::vector<double> re(c.f.size()), im(c.f.size());
  for (std::size_t i = 0; i < c.f.size(); ++i) {
    re[i] = std::clamp(c.l[i].real(), 2.0 * kNyquistReMin, 2.0 * kNyquistReMax);
    im[i] = std::clamp(c.l[i].imag(), -2.0 * kNyquistImMax, 2.0 * kNyquistImMax);
  }
  std::vector<std::size_t> rows = PlotPoints(c.f, {&c.mag, &c.s_mag, &c.t_mag}, lo, hi, PlotScale::kLog);
  for (const auto& more : {PlotPoints(c.f, {&c.phase}, lo, hi, PlotScale::kLinear),
                           PlotPoints(c.f, {&re, &im}, lo, hi, PlotScale::kLinear)}) {
    std::vector<std::size_t> both;
    std::set_union(rows.begin(), rows.end(), more.begin(), more.end(), std::back_inserter(both));
    rows = std::move(both);
  }
  return rows;
}

std::string LoopCsv(const LoopResult& r, const LoopCurves& c, const std::vector<std::size_t>& rows,
                    const std::string& budget, const std::string& paths) {
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << budget << ": loop gain L = -s G K (s the feedback's sign; negative feedback, s = -1: L = G K) of plant " << r.plant
      << " and controller " << r.controller << " (sign " << r.sign
      << "), S = 1/(1 + L), T = L/(1 + L); closing paths " << paths
      << "; only the rows the figures need to draw every curve as the full grid would (magnitudes to 0.002 decade, "
         "the phase and L near -1 to 0.2 %)\n";
  csv << "frequency_hz,abs_L,phase_L_deg,abs_S,abs_T,re_L,im_L\n";
  for (std::size_t i : rows)
    csv << CsvNumber(c.f[i]) << ',' << CsvNumber(c.mag[i]) << ',' << CsvNumber(c.phase[i]) << ','
        << CsvNumber(c.s_mag[i]) << ',' << CsvNumber(c.t_mag[i]) << ',' << CsvNumber(c.l[i].real()) << ','
        << CsvNumber(c.l[i].imag()) << '\n';
  return csv.str();
}

// The phase axis in whole steps of 45° · 2^k (at most 5 of them), reaching -180.
void PhaseAxis(FigurePanel& panel, const std::vector<double>& phase) {
  const auto [lo, hi] = std::minmax_element(phase.begin(), phase.end());
  SetPhaseAxis(panel.y, std::min(*lo, -180.0), std::max(*hi, -180.0));
}

// Bode plot of L, each gain crossover marked with its phase margin and each
// phase crossover with its gain margin.
Plot BodePlot(const LoopFigures& lf) {
  const LoopResult& r = lf.loop;
  const int digits = lf.digits;
  Plot bode;
  bode.name = lf.stem + "_bode";
  bode.kind = PlotKind::kPath;
  bode.csv = lf.csv;
  const std::string same = SameLoopText(r);
  bode.caption = "Loop gain L = −s G K (s the feedback's sign: s = −1, negative feedback, gives L = G K) of the plant G = " +
                 r.plant + " and the controller K = " + r.controller +
                 "; the loop closes the paths " + lf.paths +
                 (same.empty() ? "" : " (the budget writes the same loop also as: " + same + ")") +
                 ". Magnitude over unwrapped phase, each gain crossover marked with its "
                 "phase margin and each phase crossover with its gain margin (in dB: 20 log10 of the factor by which "
                 "the gain may grow, or shrink where negative, before the loop is unstable).";
  FigurePanel top, bottom;
  top.x = bottom.x = lf.x_axis;
  top.y.label = "|L|";
  top.y.scale = AxisScale::kLog;
  top.y.format = "10^{%L}";
  top.y2.shown = bottom.y2.shown = false;
  top.series.push_back(Line("|L|", "|L|", bode.name + ".csv", 2, kLoopColour));
  top.annotations.push_back(Level(1.0, "|L| = 1"));
  top.key.title = "loop gain";
  // As tall as the magnitude: a phase of several turns and its margins
  // were squeezed into 60 px of report.pdf beside a magnitude 1.3 times as tall.
  top.height = 1.0;
  bottom.y.label = "arg L [°]";
  bottom.y.format = "%g";
  bottom.series.push_back(Line("arg L", "", bode.name + ".csv", 3, kLoopColour));
  bottom.annotations.push_back(Level(-180.0, "arg L = -180°"));  // its own key entry: not the |L| = 1 line
  bottom.key.placement = KeyPlacement::kOutsideRight;  // the -180° line named, as |L| = 1 is above
  PhaseAxis(bottom, lf.curves.phase);
  // The margins' labels keep off the curves where they can (wafer_stage's
  // "GM 16.14 dB at 313.0 Hz" lay over the phase, beside another margin's marker).
  auto& magnitude = top.label_obstacles.emplace_back();
  auto& phase = bottom.label_obstacles.emplace_back();
  for (std::size_t k : lf.rows) {
    magnitude.push_back({lf.curves.f[k], lf.curves.mag[k]});
    phase.push_back({lf.curves.f[k], lf.curves.phase[k]});
  }
  for (const GainCrossover& c : r.margins.gain_crossovers)
    top.annotations.push_back(
        Marker(c.f_hz, 1.0, "PM " + SigLabel(c.phase_margin_deg, digits) + "° at " + SigLabel(c.f_hz, digits) + " Hz"));
  for (const PhaseCrossover& c : r.margins.phase_crossovers)
    bottom.annotations.push_back(Marker(c.f_hz, At(lf.curves.f, lf.curves.phase, c.f_hz),
                                        "GM " + SigLabel(ToDecibel(c.gain_margin), digits) + " dB at " +
                                            SigLabel(c.f_hz, digits) + " Hz"));
  bode.figure.title = lf.name + ": loop gain";
  bode.figure.panels = {std::move(top), std::move(bottom)};
  bode.script = EmitFigure(bode.figure);
  return bode;
}

// |S| and |T|, the peak of |S| marked with the modulus margin.
Plot SensitivityPlot(const LoopFigures& lf) {
  const LoopResult& r = lf.loop;
  const LoopMargins& m = r.margins;
  const LoopCurves& c = lf.curves;
  Plot st;
  st.name = lf.stem + "_sensitivity";
  st.kind = PlotKind::kPath;
  st.csv = lf.csv;
  st.caption = "Sensitivity |S| = 1/|1 + L| and complementary sensitivity |T| = |L/(1 + L)| of the loop of G = " +
               r.plant + " and K = " + r.controller + "; the peak of |S| is 1 / modulus margin.";
  FigurePanel sp;
  sp.title = lf.name + ": sensitivity and complementary sensitivity";
  sp.x = lf.x_axis;
  sp.y.label = "magnitude";
  sp.y.scale = AxisScale::kLog;
  sp.y.format = "10^{%L}";
  sp.y2.shown = false;
  sp.series.push_back(Line("|S|", "|S|", st.name + ".csv", 4, kLoopColour));
  FigureSeries t = Line("|T|", "|T|", st.name + ".csv", 5, kComplementColour);
  t.dash = "(10,5)";
  sp.series.push_back(t);
  sp.annotations.push_back(Level(1.0, "1"));
  if (m.modulus_margin > 0.0)  // 0: L passes through -1, |S| has no finite peak
    sp.annotations.push_back(Marker(m.modulus_margin_f_hz, 1.0 / m.modulus_margin,
                                    "max |S| " + SigLabel(1.0 / m.modulus_margin, lf.digits) + " (modulus margin " +
                                        SigLabel(m.modulus_margin, lf.digits) + ") at " +
                                        SigLabel(m.modulus_margin_f_hz, lf.digits) + " Hz"));
  double top_st = 1.0, bottom_st = HUGE_VAL;
  for (std::size_t i = 0; i < c.f.size(); ++i)
    for (double v : {c.s_mag[i], c.t_mag[i]}) {
      if (std::isfinite(v)) top_st = std::max(top_st, v);
      if (v > 0.0 && std::isfinite(v)) bottom_st = std::min(bottom_st, v);
    }
  sp.y.max = std::pow(10.0, std::ceil(std::log10(top_st * 2.0)));
  sp.y.min = std::min(std::max(std::pow(10.0, std::floor(std::log10(bottom_st))), *sp.y.max * 1e-8), 0.1);
  sp.key.title = "";
  st.figure.panels.push_back(std::move(sp));
  st.script = EmitFigure(st.figure);
  return st;
}

// Nyquist plot of L near -1, with its mirror image for negative frequencies.
Plot NyquistPlot(const LoopFigures& lf) {
  const LoopResult& r = lf.loop;
  Plot ny;
  ny.name = lf.stem + "_nyquist";
  ny.kind = PlotKind::kPath;
  ny.csv = lf.csv;
  ny.caption = "Nyquist plot of L for the loop of G = " + r.plant + " and K = " + r.controller +
               " near the critical point -1 (dashed: negative frequencies), the unit circle and the circle of "
               "radius modulus margin around -1 that the curve touches.";
  FigurePanel np;
  np.title = lf.name + ": Nyquist plot of L";
  np.equal_axes = true;
  np.x.label = "Re L";
  np.y.label = "Im L";
  np.x.min = kNyquistReMin;
  np.x.max = kNyquistReMax;
  np.y.min = -kNyquistImMax;
  np.y.max = kNyquistImMax;
  np.x.format = np.y.format = "%g";
  np.x.minor_grid = false;
  np.y2.shown = false;
  FigureSeries positive = Line("L", "L(j 2π f), f > 0", ny.name + ".csv", 7, kLoopColour);
  positive.x_column = 6;
  FigureSeries negative = positive;
  negative.name = "L, f < 0";
  negative.key = "f < 0";
  negative.y_divisor = -1.0;  // the mirror image: Im L(-j w) = -Im L(j w)
  negative.dash = "(6,4)";
  negative.width = 2.0;
  np.series = {positive, negative};
  FigureAnnotation unit;
  unit.kind = AnnotationKind::kCircle;
  unit.x1 = 1.0;
  unit.colour = "#808080";
  unit.width = 2.0;
  unit.key = "unit circle";
  FigureAnnotation mm = unit;
  mm.x0 = -1.0;
  mm.x1 = r.margins.modulus_margin;
  mm.colour = kMarginColour;
  mm.dash = kRequirementDash;
  mm.width = 2.0;
  mm.key = "modulus margin " + SigLabel(r.margins.modulus_margin, lf.digits);
  // Named in the key: the unit circle always passes through -1, and the
  // modulus circle and L run close by it, so a label there sat on a curve.
  FigureAnnotation minus_one = Marker(-1.0, 0.0, "");
  minus_one.key = "critical point -1";
  minus_one.point_type = 2;  // a cross
  minus_one.colour = "#000000";
  np.annotations = {unit, mm, minus_one};
  np.key.title = "";
  ny.figure.panels.push_back(std::move(np));
  ny.script = EmitFigure(ny.figure);
  return ny;
}

}  // namespace

std::vector<Plot> LoopPlots(const BudgetResult& result, int digits) {
  std::vector<Plot> plots;
  DEB_DEMAND(result.traces && result.traces->loops.size() == result.loops.size());
  for (std::size_t loop = 0; loop < result.loops.size(); ++loop) {
    const LoopResult& r = result.loops[loop];
    const LoopTrace& trace = result.traces->loops[loop];
    if (trace.f_hz.size() < 2) continue;
    std::string paths;
    for (const std::string& p : r.paths) paths += (paths.empty() ? "" : ", ") + p;
    LoopCurves curves = Curves(trace);
    const std::vector<double>& f = curves.f;
    const FrequencyRange range{f.front(), f.back(),
                               f.front() > result.grid.min_hz() || f.back() < result.grid.max_hz()};
    const FigureAxis x_axis = FrequencyFigureAxis(range, result.grid, "where the loop's data are defined");
    std::vector<std::size_t> rows = LoopRows(curves);
    const std::string csv = LoopCsv(r, curves, rows, result.outline.name, paths);
    const LoopFigures lf{r,
                         std::move(curves),
                         std::move(rows),
                         "loop_" + FileStem(r.plant) + "_" + FileStem(r.controller),
                         "loop " + Enhanced(r.plant) + " · " + Enhanced(r.controller),
                         paths,
                         csv,
                         x_axis,
                         digits};
    plots.push_back(BodePlot(lf));
    plots.push_back(SensitivityPlot(lf));
    plots.push_back(NyquistPlot(lf));
  }
  return plots;
}

}  // namespace deb::report
