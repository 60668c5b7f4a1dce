#include "deb/report/compare/ratio_plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/core/error.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/compare/overlay_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"
#include "deb/version.h"

namespace deb::report {

double AtFrequency(const std::vector<double>& f_hz, const std::vector<double>& y, double f) {
  if (f_hz.empty() || f < f_hz.front() || f > f_hz.back()) return NAN;
  const auto hi = std::lower_bound(f_hz.begin(), f_hz.end(), f);
  const std::size_t k = static_cast<std::size_t>(hi - f_hz.begin());
  if (f_hz[k] == f) return y[k];
  const double t = std::log(f / f_hz[k - 1]) / std::log(f_hz[k] / f_hz[k - 1]);
  if (y[k - 1] > 0.0 && y[k] > 0.0) return y[k - 1] * std::pow(y[k] / y[k - 1], t);
  return y[k - 1] + t * (y[k] - y[k - 1]);
}

namespace {

// B / A, or NaN where either is zero (or B is not defined there).
double Ratio(double b, double a) { return a > 0.0 && b > 0.0 ? b / a : NAN; }

// One curve of a ratio plot: a contributor's (or the total's) PSD in A and
// in B, its style, and the ratio of its RMS.
struct Curve {
  std::string name;
  std::size_t style;
  const std::vector<double>* a;
  const std::vector<double>* b;
  double rms_ratio;
};

// The ratio plot's panel: the ratios in [lo, hi] over `range` on a linear
// or log axis; `data` the plot's CSV (frequency, then a column per curve).
FigurePanel RatioPanel(const OutputResult& oa, const std::string& label_a, const std::string& label_b,
                       const FrequencyGrid& grid, const FrequencyRange& range, const std::vector<Curve>& curves,
                       const std::string& data, double lo, double hi, bool linear) {
  FigurePanel panel;
  panel.title = Enhanced(oa.name + ": PSD of B / PSD of A");
  panel.x = FrequencyFigureAxis(range, grid);
  panel.y.label = "B / A";
  if (linear) {
    const double span = std::max(hi - 1.0, 1.0 - lo);
    // At least +-1e-3 around the data: ratios within rounding of 1 (an
    // output the change does not touch) would otherwise give an axis of no
    // height, which gnuplot refuses ("empty y range").
    const double pad = std::max(0.1 * span, 1e-3);
    panel.y.min = std::max(0.0, lo - pad);
    panel.y.max = hi + pad;
    panel.y.format = "%g";
  } else {
    panel.y.scale = AxisScale::kLog;
    panel.y.format = "10^{%L}";
    panel.y.min = std::pow(10.0, std::floor(std::log10(std::max(lo, 1e-6))));
    panel.y.max = std::pow(10.0, std::ceil(std::log10(std::min(hi, 1e6))));
  }
  panel.y2.shown = false;
  panel.key.title = Enhanced("B: " + label_b) + "\nover " + Enhanced("A: " + label_a) + "\nRMS of B / A";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const bool total = i + 1 == curves.size();
    FigureSeries s;
    s.name = curves[i].name;
    s.data = data;
    s.y_columns = {i + 2};
    s.key = Enhanced(curves[i].name) + " " + (std::isfinite(curves[i].rms_ratio) ? SigLabel(curves[i].rms_ratio, 4) : "–");
    s.colour = total ? kTotalColour : ContributorStyle(curves[i].style).colour;
    // As a run's PSD: contributors wide, the total thin over them, so that a
    // contributor that is all of the total (h210's sensor_noise) shows on
    // both sides of it; the line B = A thin and behind them all (it hid
    // the total at 1).
    s.width = total ? 1.0 : 2.5;
    panel.series.push_back(std::move(s));
  }
  FigureAnnotation same;
  same.kind = AnnotationKind::kHorizontalLine;
  same.y0 = 1.0;
  same.colour = "#808080";
  same.dash = "(6,4)";
  same.width = 1.0;
  same.behind = true;
  same.key = "B = A";
  panel.annotations.push_back(same);
  return panel;
}

Plot RatioPlot(const std::string& label_a, const BudgetResult& a, const OutputResult& oa, const std::string& label_b,
               const BudgetResult& b, const OutputResult& ob) {
  const std::vector<double>& fa = a.grid.f_hz();
  const std::vector<double>& fb = b.grid.f_hz();
  const bool same_grid = fa == fb;
  const auto b_at = [&](const std::vector<double>& y, std::size_t k) {
    return same_grid ? y[k] : AtFrequency(fb, y, fa[k]);
  };
  // The curves: the contributors both have (by name), then the total.
  std::vector<Curve> curves;
  for (std::size_t c = 0; c < oa.contributors.size(); ++c)
    for (std::size_t d = 0; d < ob.contributors.size(); ++d)
      if (ob.contributors[d].name == oa.contributors[c].name && ShownInComparison(oa, c) && ShownInComparison(ob, d))
        curves.push_back({oa.contributors[c].name, c, &oa.contributors[c].psd, &ob.contributors[d].psd,
                          std::sqrt(Ratio(ob.contributors[d].variance, oa.contributors[c].variance))});
  curves.push_back({"total", 0, &oa.total_psd, &ob.total_psd, std::sqrt(Ratio(ob.variance, oa.variance))});

  std::vector<std::vector<double>> ratio(curves.size(), std::vector<double>(fa.size()));
  for (std::size_t i = 0; i < curves.size(); ++i)
    for (std::size_t k = 0; k < fa.size(); ++k) ratio[i][k] = Ratio(b_at(*curves[i].b, k), (*curves[i].a)[k]);

  const FrequencyRange ra = DisplayRange(oa, a.grid), rb = DisplayRange(ob, b.grid);
  FrequencyRange range;
  range.lo_hz = std::max(std::min(ra.lo_hz, rb.lo_hz), std::max(fa.front(), fb.front()));
  range.hi_hz = std::min(std::max(ra.hi_hz, rb.hi_hz), std::min(fa.back(), fb.back()));
  range.trimmed = range.lo_hz > fa.front() * (1 + 1e-9) || range.hi_hz < fa.back() * (1 - 1e-9);

  double lo = 1.0, hi = 1.0;
  for (const auto& r : ratio)
    for (std::size_t k = 0; k < fa.size(); ++k)
      if (fa[k] >= range.lo_hz && fa[k] <= range.hi_hz && std::isfinite(r[k])) {
        lo = std::min(lo, r[k]);
        hi = std::max(hi, r[k]);
      }
  const bool linear = lo >= 1.0 / 3.0 && hi <= 3.0;

  Plot p;
  p.name = FileStem(oa.name) + "_ratio";
  p.kind = PlotKind::kSpectrum;
  p.output = -1;
  p.caption = "Ratio of the power spectral densities of " + oa.name + ", B (" + label_b + ") over A (" + label_a +
              "), per contributor both have and in total (black): above 1 B is worse at that frequency. The key "
              "gives the ratio of the RMS, B / A; a contributor below 10^-6 of its output's variance in A or in B has "
              "no ratio (the tables: from ≈0, to ≈0)." +
              RangeCaption(range);
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", compare, output " << oa.name << ": PSD of B (" << label_b << ") / PSD of A ("
      << label_a << ")" << (same_grid ? "" : ", B interpolated to A's frequencies") << "; nan where either is 0\n";
  csv << "frequency_hz";
  for (const Curve& c : curves) csv << ',' << CsvField(c.name);
  csv << '\n';
  std::vector<const std::vector<double>*> drawn;
  for (const auto& r : ratio) drawn.push_back(&r);
  for (std::size_t k :
       PlotPoints(fa, drawn, range.lo_hz, range.hi_hz, linear ? PlotScale::kLinear : PlotScale::kLog)) {
    csv << CsvNumber(fa[k]);
    for (const auto& r : ratio) csv << ',' << CsvNumber(r[k]);
    csv << '\n';
  }
  p.csv = csv.str();

  p.figure.panels.push_back(RatioPanel(oa, label_a, label_b, a.grid, range, curves, p.name + ".csv", lo, hi, linear));
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace

std::vector<Plot> RatioPlots(const std::string& label_a, const BudgetResult& a, const std::string& label_b,
                             const BudgetResult& b) {
  std::vector<Plot> plots;
  for (const OutputResult& oa : a.outputs)
    for (const OutputResult& ob : b.outputs)
      if (oa.name == ob.name && oa.unit == ob.unit) plots.push_back(RatioPlot(label_a, a, oa, label_b, b, ob));
  return plots;
}

std::vector<Plot> ComparisonPlots(const std::string& label_a, const BudgetResult& a, const std::string& label_b,
                                  const BudgetResult& b) {
  std::vector<Plot> overlays = OverlayPlots(label_a, a, label_b, b), ratios = RatioPlots(label_a, a, label_b, b);
  DEB_DEMAND(overlays.size() == 2 * ratios.size());
  std::vector<Plot> plots;
  for (std::size_t o = 0; o < ratios.size(); ++o) {
    plots.push_back(std::move(overlays[2 * o]));
    plots.push_back(std::move(overlays[2 * o + 1]));
    plots.push_back(std::move(ratios[o]));
  }
  return plots;
}

}  // namespace deb::report
