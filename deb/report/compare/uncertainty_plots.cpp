#include "deb/report/compare/uncertainty_plots.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_style.h"
#include "deb/uncertainty/sample_statistics.h"
#include "deb/version.h"

namespace deb::report {

namespace {

constexpr const char* kSampleColour = "#2166ac";
// Orange reads over the samples' blue bars and points and on white (a dark
// grey line vanished over the histogram's bars).
constexpr const char* kNominalColour = "#e08214";

// The requirement (dashed red) and the nominal design (dotted orange) as
// lines at their RMS, keyed with the output's unit.
void MarkRequirement(FigurePanel& panel, const StudyMetric& m, bool key, bool vertical) {
  const std::string unit = m.unit.empty() ? "" : " " + UnitLabel(m.unit);
  if (m.limit) {
    FigureAnnotation r;
    r.kind = vertical ? AnnotationKind::kVerticalLine : AnnotationKind::kHorizontalLine;
    (vertical ? r.x0 : r.y0) = *m.limit;
    r.colour = kRequirementColour;
    r.dash = kRequirementDash;
    r.key = key ? "requirement " + Short(*m.limit) + unit : "";
    panel.annotations.push_back(r);
  }
  FigureAnnotation n;
  n.kind = vertical ? AnnotationKind::kVerticalLine : AnnotationKind::kHorizontalLine;
  (vertical ? n.x0 : n.y0) = m.nominal;
  n.colour = kNominalColour;
  n.dash = "(3,4)";
  n.width = 2.0;
  n.key = key ? "nominal design " + Sig(m.nominal, 4) + unit : "";
  panel.annotations.push_back(n);
}

Plot Distribution(const StudyMetric& m, int output) {
  Plot p;
  p.name = FileStem(m.output) + "_uncertainty";
  p.kind = PlotKind::kOverview;
  p.output = output;
  std::vector<double> v = m.values;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double lo = v.front(), hi = v.back();
  // Histogram: about sqrt(N) bins, 10 to 50, over the samples' range (and
  // the requirement's when it lies just outside).
  double x_lo = lo, x_hi = hi;
  if (m.limit && *m.limit > 0.5 * lo && *m.limit < 2.0 * hi) {
    x_lo = std::min(x_lo, *m.limit);
    x_hi = std::max(x_hi, *m.limit);
  }
  if (!(x_hi > x_lo)) x_hi = x_lo + (x_lo == 0.0 ? 1.0 : 0.01 * std::abs(x_lo));
  const std::size_t bins = std::clamp<std::size_t>(static_cast<std::size_t>(std::sqrt(static_cast<double>(n))), 10, 50);
  const double width = (x_hi - x_lo) / static_cast<double>(bins);
  std::vector<std::size_t> count(bins, 0);
  for (double x : v) count[std::min(bins - 1, static_cast<std::size_t>((x - x_lo) / width))] += 1;

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", uncertainty, output " << m.output << " RMS in " << m.unit << ", " << n
      << " samples\n# block 0: histogram (bin centre, fraction of the samples per bin)\nrms,fraction\n";
  for (std::size_t b = 0; b < bins; ++b)
    csv << CsvNumber(x_lo + (static_cast<double>(b) + 0.5) * width) << ','
        << CsvNumber(static_cast<double>(count[b]) / static_cast<double>(n)) << '\n';
  csv << "\n\n# block 1: empirical CDF (RMS, fraction of the samples at or below it)\nrms,cdf\n";
  csv << CsvNumber(x_lo) << ",0\n";
  // At most about kMaxEcdfSteps steps (every stride-th order statistic and
  // the last): a step of 1/kMaxEcdfSteps is below what a figure resolves.
  const std::size_t stride = (n + kMaxEcdfSteps - 1) / kMaxEcdfSteps;
  for (std::size_t i = stride - 1; i < n; i += stride)
    csv << CsvNumber(v[i]) << ',' << CsvNumber(static_cast<double>(i + 1) / n) << '\n';
  if (n % stride != 0) csv << CsvNumber(v[n - 1]) << ",1\n";
  csv << CsvNumber(x_hi) << ",1\n";
  p.csv = csv.str();

  const std::string file = p.name + ".csv";
  std::string title = m.output + ": RMS over " + std::to_string(n) + " samples";
  if (m.limit)
    title += "\nP(RMS ≤ " + Short(*m.limit) + (m.unit.empty() ? "" : " " + UnitLabel(m.unit)) + ") = " + ProbabilityText(static_cast<double>(m.met) / static_cast<double>(n)) +
             " (95 %: " + ProbabilityText(m.p_meet.low) + " to " + ProbabilityText(m.p_meet.high) + ")";
  p.figure.title = Enhanced(title);
  p.caption = "Distribution of the RMS of " + m.output + " over the " + std::to_string(n) +
              " samples: histogram (top) and empirical CDF (bottom)" +
              (m.limit ? "; the requirement dashed red, where the CDF's height is P(meet)" : "") +
              "; the nominal design's RMS dotted orange.";

  FigurePanel hist;
  hist.x.label = "";
  hist.x.min = x_lo - width;
  hist.x.max = x_hi + width;
  hist.y.label = "fraction per bin";
  hist.y.min = 0.0;
  hist.y2.shown = false;
  hist.bar_width = 0.9 * width;
  // Beside the panels, in the margin a stack keeps anyway: inside, the
  // requirement's line ran through it in uncertainty.pdf.
  hist.key.placement = KeyPlacement::kOutsideRight;
  FigureSeries bars;
  bars.name = "histogram";
  bars.kind = SeriesKind::kBars;
  bars.data = file;
  bars.block = 0;
  bars.y_columns = {2};
  bars.colour = kSampleColour;
  hist.series.push_back(bars);
  MarkRequirement(hist, m, true, true);
  hist.height = 1.0;

  FigurePanel cdf;
  cdf.x.label = "RMS [" + UnitLabel(m.unit) + "]";
  cdf.x.min = hist.x.min;
  cdf.x.max = hist.x.max;
  cdf.y.label = "fraction ≤ RMS";
  cdf.y.min = 0.0;
  cdf.y.max = 1.0;
  cdf.y2.shown = false;
  cdf.key.placement = KeyPlacement::kNone;
  FigureSeries steps;
  steps.name = "ecdf";
  steps.kind = SeriesKind::kSteps;
  steps.data = file;
  steps.block = 1;
  steps.y_columns = {2};
  steps.colour = kSampleColour;
  cdf.series.push_back(steps);
  MarkRequirement(cdf, m, false, true);
  cdf.height = 1.0;
  p.figure.panels = {hist, cdf};
  p.script = EmitFigure(p.figure);
  return p;
}

Plot Drivers(const UncertaintyResult& r, const StudyMetric& m, int output) {
  Plot p;
  p.name = FileStem(m.output) + "_drivers";
  p.kind = PlotKind::kOverview;
  p.output = output;
  const std::vector<std::size_t> order = DriverOrder(m);
  const bool sobol = !m.sobol.empty();
  const std::size_t k = order.size();
  const double bound = RankCorrelationNoise(r.samples);
  // In the PDF as tall as its bars need (45 px a parameter): at the
  // overview's 600 px, four bars took a page and left the scatter plots the
  // next one.
  p.pdf_height_px = static_cast<int>(std::min<std::size_t>(600, 150 + 45 * k));
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", uncertainty, output " << m.output
      << ": each parameter's rank correlation with the RMS" << (sobol ? ", first-order and total Sobol indices" : "")
      << "; top to bottom; the rank correlation again where beyond the sampling noise +-" << CsvNumber(bound)
      << " (95 %), and where within it\nposition,spearman,sobol_first,sobol_total,parameter,spearman_beyond_noise,"
         "spearman_within_noise\n";
  for (std::size_t j = 0; j < k; ++j) {
    const std::size_t i = order[j];
    const bool noise = std::abs(m.spearman[i]) < bound;
    csv << (k - 1 - j) << ',' << CsvNumber(m.spearman[i]) << ',' << CsvNumber(sobol ? m.sobol[i].first : 0.0) << ','
        << CsvNumber(sobol ? m.sobol[i].total : 0.0) << ',' << CsvField(r.spec.parameters[i].name) << ','
        << CsvNumber(noise ? 0.0 : m.spearman[i]) << ',' << CsvNumber(noise ? m.spearman[i] : 0.0) << '\n';
  }
  p.csv = csv.str();
  p.caption = "What drives the RMS of " + m.output + ": each parameter's Spearman rank correlation with it" +
              std::string(sobol ? ", and its first-order (S) and total (ST) Sobol index of the variance" : "") +
              "; the strongest on top. Grey, within the dotted lines at ±" + Sig(bound, 2) +
              ": a correlation the sampling noise of " + std::to_string(r.samples) +
              " independent samples reaches (95 %), whose sign says nothing.";
  FigurePanel panel;
  panel.title = Enhanced(m.output + ": drivers of the RMS");
  panel.x.label = sobol ? "rank correlation (blue); Sobol S (orange), ST (grey)" : "rank correlation with the RMS";
  panel.x.min = -1.15;
  panel.x.max = 1.15;
  panel.x.minor_grid = false;
  panel.y.min = -0.7;
  panel.y.max = static_cast<double>(k) - 0.3;
  panel.y.grid = panel.y.minor_grid = false;
  for (std::size_t j = 0; j < k; ++j)
    panel.y.tics.push_back({static_cast<double>(k - 1 - j), Enhanced(r.spec.parameters[order[j]].name)});
  panel.y2.shown = false;
  panel.key.placement = KeyPlacement::kNone;
  const std::string file = p.name + ".csv";
  // Sobol's total index widest and lightest behind its first-order one, the
  // rank correlation thin on top.
  const auto bars = [&](const std::string& name, std::size_t column, const std::string& colour, double height) {
    FigureSeries s;
    s.name = name;
    s.kind = SeriesKind::kHorizontalBars;
    s.data = file;
    s.x_column = column;
    s.y_columns = {1};
    s.colour = colour;
    s.bar_height = height;
    return s;
  };
  panel.series.push_back(bars("spearman", 6, kSampleColour, sobol ? 0.3 : 0.6));
  panel.series.push_back(bars("spearman_within_noise", 7, "#9e9e9e", sobol ? 0.3 : 0.6));
  if (sobol) {
    FigureSeries total = bars("sobol_total", 4, "#bdbdbd", 0.7);
    FigureSeries first = bars("sobol_first", 3, "#e08214", 0.5);
    panel.series.insert(panel.series.begin(), {total, first});
  }
  FigureSeries values;
  values.name = "values";
  values.kind = SeriesKind::kLabels;
  values.data = file;
  values.x_column = 2;
  values.y_columns = {1};
  values.label_column = 2;
  values.label_format = "%.2f";
  values.labels_beside_end = true;
  panel.series.push_back(values);
  FigureAnnotation zero;
  zero.kind = AnnotationKind::kVerticalLine;
  zero.colour = "#404040";
  zero.width = 1.0;
  panel.annotations.push_back(zero);
  for (double x : {-bound, bound}) {
    FigureAnnotation band;
    band.kind = AnnotationKind::kVerticalLine;
    band.x0 = x;
    band.colour = "#707070";
    band.dash = "(2,3)";
    band.width = 1.0;
    band.behind = true;  // under the bars and their values
    panel.annotations.push_back(band);
  }
  p.figure.panels.push_back(panel);
  p.script = EmitFigure(p.figure);
  return p;
}

// "2nd", "5th", "21st".
std::string OrdinalText(std::size_t k) {
  const std::size_t tens = k % 100, ones = k % 10;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th" : ones == 1 ? "st" : ones == 2 ? "nd" : ones == 3 ? "rd" : "th";
  return std::to_string(k) + suffix;
}

Plot Scatter(const UncertaintyResult& r, const StudyMetric& m, int output) {
  Plot p;
  p.name = FileStem(m.output) + "_scatter";
  p.kind = PlotKind::kOverview;
  p.pdf_height_px = 420;  // two panels side by side, at a run figure's height
  p.output = output;
  const std::vector<std::size_t> order = DriverOrder(m);
  const std::size_t shown = std::min<std::size_t>(2, order.size());
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", uncertainty, output " << m.output << ": RMS in " << m.unit
      << " against its strongest drivers, one row per sample\nrms";
  for (std::size_t j = 0; j < shown; ++j) csv << ',' << CsvField(r.spec.parameters[order[j]].name);
  csv << '\n';
  // At most kMaxScatterPoints, every stride-th sample: more points only
  // blacken the cloud, and cost the PDF seconds and megabytes.
  const std::size_t n = m.values.size();
  const std::size_t stride = (n + kMaxScatterPoints - 1) / kMaxScatterPoints;
  std::size_t drawn = 0;
  for (std::size_t s = 0; s < n; s += stride) {
    ++drawn;
    csv << CsvNumber(m.values[s]);
    for (std::size_t j = 0; j < shown; ++j) {
      const UncertainParameter& q = r.spec.parameters[order[j]];
      csv << ',' << CsvNumber(r.parameter_values[order[j]][s] / q.unit_si);
    }
    csv << '\n';
  }
  p.csv = csv.str();
  p.caption = "The RMS of " + m.output + " of each sample against its " + (shown == 2 ? "two strongest drivers" : "driver") +
              (m.limit ? "; the requirement dashed red" : "") + ", the nominal design's RMS dotted orange." +
              (stride > 1 ? " Every " + OrdinalText(stride) + " sample is drawn, " + std::to_string(drawn) + " of " +
                                std::to_string(n) + "; the statistics take them all."
                          : "");
  p.figure.title = Enhanced(m.output + ": RMS against its strongest drivers");
  p.figure.columns = shown;
  const std::string file = p.name + ".csv";
  for (std::size_t j = 0; j < shown; ++j) {
    const UncertainParameter& q = r.spec.parameters[order[j]];
    FigurePanel panel;
    // Marked as the drivers table marks it: a correlation within the sampling noise.
    const bool noise = std::abs(m.spearman[order[j]]) < RankCorrelationNoise(r.samples);
    panel.title = Enhanced(q.name + " (rank correlation " + Sig(m.spearman[order[j]], 2) + (noise ? ", noise" : "") + ")");
    panel.x.label = Enhanced(q.name) + (q.unit.empty() ? "" : " [" + UnitLabel(q.unit) + "]");
    panel.y.label = j == 0 ? "RMS [" + UnitLabel(m.unit) + "]" : "";
    panel.y2.shown = false;
    panel.key.placement = KeyPlacement::kNone;
    FigureSeries dots;
    dots.name = "samples";
    dots.kind = SeriesKind::kPoints;
    dots.data = file;
    dots.x_column = j + 2;
    dots.y_columns = {1};
    dots.colour = kSampleColour;
    dots.point_type = 7;
    dots.point_size = 0.35;
    panel.series.push_back(dots);
    MarkRequirement(panel, m, false, false);
    p.figure.panels.push_back(panel);
  }
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace

std::string ProbabilityText(double p) { return Sig(100.0 * p, 3) + " %"; }

std::vector<std::size_t> DriverOrder(const StudyMetric& m) {
  std::vector<std::size_t> order(m.spearman.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return std::abs(m.spearman[a]) > std::abs(m.spearman[b]); });
  return order;
}

std::vector<Plot> UncertaintyPlots(const UncertaintyResult& result) {
  std::vector<Plot> plots;
  int output = -1;
  for (const StudyMetric& m : result.metrics) {
    if (!m.contributor.empty() || !m.band.empty()) continue;
    ++output;
    plots.push_back(Distribution(m, output));
    plots.push_back(Drivers(result, m, output));
    plots.push_back(Scatter(result, m, output));
  }
  return plots;
}

}  // namespace deb::report
