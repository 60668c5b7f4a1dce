#include "deb/report/budget/spectrum_plots.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>

#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {


// "floor: 12.3 (78.1 %)" for a key whose title names the unit; a
// contributor that is zero on this output (by symmetry), or computes as
// rounding there (RoundingZero), reads "floor: 0 (0 %)", as in the tables.
std::string Entry(const std::string& name, double variance, double total_variance, int digits) {
  if (total_variance > 0.0) variance = WithoutRounding(variance, total_variance);
  std::string s = Enhanced(name) + ": " + (variance > 0.0 ? SigLabel(std::sqrt(variance), digits) : "0");
  if (total_variance > 0.0) s += " (" + (variance > 0.0 ? Share(variance, total_variance) : std::string("0 %")) + ")";
  return s;
}

// "measured (reference): 1.23, 0.216–1.94e+03 Hz": a reference's key entry, its RMS over what it covers.
std::string ReferenceKey(const ReferenceResult& r, int digits) {
  return Enhanced(r.name) + " (reference): " + SigLabel(std::sqrt(r.variance), digits) + ", " +
         SigLabel(r.covered_lo_hz, 3) + "–" + SigLabel(r.covered_hi_hz, 3) + " Hz";
}

// A reference's curve: grey dashed, column `column` of `data` shown as
// value / y_divisor, keyed with ReferenceKey (the CPS and the PSD plot alike).
FigureSeries ReferenceSeries(const ReferenceResult& r, int digits, const std::string& data, std::size_t column,
                             double y_divisor) {
  FigureSeries m;
  m.name = "measured: " + r.name;
  m.key = ReferenceKey(r, digits);
  m.data = data;
  m.y_columns = {column};
  m.y_divisor = y_divisor;
  m.colour = kReferenceColour;
  m.dash = kReferenceDash;
  m.width = 2.5;
  return m;
}

// " Weighted by <description>; metric: <metric>." from output o's outline
// (none in a result made without one) and `out`, a level of it: what the
// plotted quantity is, stated in the caption.
std::string WeightingCaption(const BudgetResult& result, std::size_t o, const OutputResult& out) {
  std::string s;
  const std::vector<OutputOutline>& outlines = result.outline.outputs;
  const WeightingOutline* weighting =
      o < outlines.size() && outlines[o].weighting ? &*outlines[o].weighting : nullptr;
  if (weighting)
    s += " The output is weighted by " +
         (weighting->description.empty() ? std::string("a weighting filter") : weighting->description) +
         " (filter unit " + UnitText(weighting->unit) + ").";
  if (out.metric) s += " Metric: " + out.metric->Describe() + " (the PSD is that of the metric).";
  return s;
}

// The stacked CPS's data: frequency, each item's and the total's (reverse)
// cumulative variance, then each reference's (NaN outside what it covers),
// thinned for a linear variance axis over the shown range.
std::string StackedCsv(const BudgetResult& result, const OutputResult& out, const std::vector<std::vector<double>>& series,
                       const std::vector<double>& total, const std::vector<ReferenceResult>& refs,
                       const FrequencyRange& range, bool reverse, const std::string& unit) {
  const std::vector<double>& f = result.grid.f_hz();
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.outline.name << ", output " << out.name << ": "
      << (reverse ? "variance from f to " + CsvNumber(result.grid.max_hz()) + " Hz"
                  : "variance from " + CsvNumber(result.grid.min_hz()) + " Hz to f")
      << " in (" << unit << ")^2, per contributor and total\n";
  csv << "frequency_hz";
  for (const auto& c : out.contributors) csv << ',' << CsvField(c.name);
  csv << ",total";
  for (const ReferenceResult& r : refs) csv << ',' << CsvField("measured: " + r.name);
  csv << '\n';
  std::vector<const std::vector<double>*> drawn = {&total};
  for (const auto& s : series) drawn.push_back(&s);
  for (const ReferenceResult& r : refs) drawn.push_back(&r.cps);
  for (std::size_t k : PlotPoints(f, drawn, range.lo_hz, range.hi_hz, PlotScale::kLinear)) {
    csv << CsvNumber(f[k]);
    for (const auto& s : series) csv << ',' << CsvNumber(s[k]);
    csv << ',' << CsvNumber(total[k]);
    for (const ReferenceResult& r : refs)
      csv << ',' << (f[k] >= r.covered_lo_hz && f[k] <= r.covered_hi_hz ? CsvNumber(r.cps[k]) : std::string("NaN"));
    csv << '\n';
  }
  return csv.str();
}

// The variance axis of a CPS fits the budget: a limit or a reference more
// than kFarAbove times the total variance is not scaled to (a passing budget
// would fill the bottom of the figure); the limit is then named at the top
// instead, and a reference runs off the top. y_max leaves 12 % headroom for
// the marker's label.
constexpr double kFarAbove = 3.0;
struct CpsAxisFit {
  double y_max = 0.0;
  bool limit_above = false, reference_above = false;
};

CpsAxisFit FitCpsAxis(const OutputResult& out, const std::vector<ReferenceResult>& refs) {
  const double limit2 = out.rms_max ? *out.rms_max * *out.rms_max : 0.0;
  const auto fits = [&](double v) { return !(out.variance > 0.0) || v <= kFarAbove * out.variance; };
  CpsAxisFit fit;
  double top = std::max(out.variance, 1e-300);
  fit.limit_above = out.rms_max && !fits(limit2);
  if (!fit.limit_above) top = std::max(top, limit2);
  for (const ReferenceResult& r : refs) {
    if (fits(r.variance)) top = std::max(top, r.variance);
    else fit.reference_above = true;
  }
  fit.y_max = top * 1.12;
  return fit;
}

// The stacked layers, the largest on top of the stack and first in the key
// (the key reads top to bottom like the stack): layer order[i] lies on the
// layers order[i+1..n-1]; then the boundaries between them.
void AddLayers(FigurePanel& panel, const PlotLevel& level, const std::string& data, double scale, int digits) {
  const OutputResult& out = level.out;
  const std::vector<std::size_t> order = ShareOrder(out);
  std::vector<FigureSeries> edges;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t c = order[i];
    const SeriesStyle& st = level.styles[c];
    FigureSeries layer;
    layer.name = out.contributors[c].name;
    layer.key = Entry(out.contributors[c].name, out.contributors[c].variance, out.variance, digits);
    layer.kind = SeriesKind::kFilled;
    layer.data = data;
    for (std::size_t j = i + 1; j < order.size(); ++j) layer.low_columns.push_back(2 + order[j]);
    layer.y_columns = layer.low_columns;
    layer.y_columns.push_back(2 + c);
    layer.y_divisor = scale;
    layer.colour = st.colour;
    layer.fill_pattern = st.fill_pattern;
    layer.hatch_colour = st.hatch_colour;
    // Boundary to the layer below: white between dark layers, near-black
    // between light ones, so that neighbours stay apart in greyscale too.
    if (i + 1 < order.size()) {
      FigureSeries edge;
      edge.name = "edge below " + layer.name;
      edge.data = data;
      edge.y_columns = layer.low_columns;
      edge.y_divisor = scale;
      const double l = 0.5 * (st.lightness + level.styles[order[i + 1]].lightness);
      edge.colour = l < 58.0 ? "#ffffff" : "#262626";
      edge.width = 1.1;
      edges.push_back(edge);
    }
    panel.series.push_back(std::move(layer));
  }
  panel.series.insert(panel.series.end(), edges.begin(), edges.end());
}

// The requirement: named at the top of the plot (and in the key as a line)
// when far above, else a line, with a marker and a vertical line where the
// cumulative RMS reaches it (they keep it visible when the limit is a sliver
// at the axis' foot).
void AddRequirement(FigurePanel& panel, const BudgetResult& result, const OutputResult& out, const FrequencyRange& range,
                    bool above_axis, bool reverse, double scale, int digits) {
  if (!out.rms_max) return;
  const double limit2 = *out.rms_max * *out.rms_max;
  const std::string unit = DisplayUnit(out.unit);
  if (above_axis) {
    FigureAnnotation above;
    above.kind = AnnotationKind::kText;
    above.x0 = 0.02;
    above.y0 = 0.95;
    above.colour = kRequirementColour;
    // Short, at the top left where a CPS is low: the share of the limit's
    // variance used is in the caption (the longer text ran into optical_table's
    // curve where it levels off near the top).
    above.label = "↑ requirement " + Short(*out.rms_max) + " " + UnitLabel(unit) + " RMS, above the axis";
    panel.annotations.push_back(above);
    FigureAnnotation entry;
    entry.kind = AnnotationKind::kKeyEntry;
    entry.colour = kRequirementColour;
    entry.dash = kRequirementDash;
    entry.point_type = 0;
    entry.key = "requirement: " + Short(*out.rms_max) + " (pass, above the axis)";
    panel.annotations.push_back(entry);
    return;
  }
  FigureAnnotation limit;
  limit.kind = AnnotationKind::kHorizontalLine;
  limit.y0 = limit2 / scale;
  limit.colour = kRequirementColour;
  limit.dash = kRequirementDash;
  limit.key = "requirement: " + Short(*out.rms_max) + (out.pass() ? " (pass)" : " (FAIL)");
  panel.annotations.push_back(limit);
  const std::optional<double> cross =
      reverse ? std::nullopt : CpsCrossingHz(result.grid.f_hz(), out.total_psd, out.total_cps, limit2);
  if (!cross || *cross < range.lo_hz || *cross > range.hi_hz) return;
  FigureAnnotation v;
  v.kind = AnnotationKind::kVerticalLine;
  v.x0 = *cross;
  v.colour = kRequirementColour;
  // Dotted, told from the dashed requirement line; thinner than it too,
  // which makes gnuplot's SVG terminal start a path of its own (at one
  // width it kept the requirement line's dashes for both).
  v.dash = "(4,6)";
  v.width = 1.6;
  panel.annotations.push_back(v);
  FigureAnnotation m;
  m.kind = AnnotationKind::kMarker;
  m.x0 = *cross;
  m.y0 = limit2 / scale;
  m.colour = kRequirementColour;
  // Named in the key: a label beside the point would lie over the stacked layers.
  m.key = "RMS reaches " + Short(*out.rms_max) + " " + UnitLabel(unit) + " at " + SigLabel(*cross, digits) + " Hz";
  panel.annotations.push_back(m);
}

// Stacked CPS (reverse = false) or reverse CPS of one output at one level
// (its items in `level.out.contributors`).
Plot StackedPlot(const BudgetResult& result, std::size_t o, const PlotLevel& level, bool reverse, int digits) {
  const OutputResult& out = level.out;
  const std::size_t n = out.contributors.size();
  Plot p;
  p.name = FileStem(out.name) + (reverse ? "_reverse_cps" : "_cps");
  p.kind = reverse ? PlotKind::kReverseCps : PlotKind::kCps;
  p.output = static_cast<int>(o);
  const FrequencyRange range = level.range;
  const std::string unit = DisplayUnit(out.unit);
  // The references' cumulative variance, over what each covers (forward CPS only).
  const std::vector<ReferenceResult> none;
  const std::vector<ReferenceResult>& refs = reverse ? none : out.references;
  p.caption = std::string(reverse ? "Reverse cumulative power spectrum (variance above f)" :
                                    "Cumulative power spectrum (variance below f)") +
              " of " + out.name + ", " + level.items +
              " stacked by share, the largest on top and first in the key; left axis variance, "
              "right axis RMS." +
              WeightingCaption(result, o, out) + RangeCaption(range);
  if (!refs.empty())
    p.caption += " Grey dashed: the measured reference(s), never summed: the variance from the lowest frequency "
                 "each covers to f (the table compares it with the budget's over the same range).";

  std::vector<std::vector<double>> series(n);
  for (std::size_t c = 0; c < n; ++c)
    series[c] = reverse ? ReverseCps(out.contributors[c].cps) : out.contributors[c].cps;
  const std::vector<double> total = reverse ? ReverseCps(out.total_cps) : out.total_cps;
  p.csv = StackedCsv(result, out, series, total, refs, range, reverse, unit);

  const CpsAxisFit fit = FitCpsAxis(out, refs);
  const double y_max = fit.y_max;
  if (fit.limit_above)
    p.caption += " The requirement (" + Short(*out.rms_max) + " " + UnitText(out.unit) +
                 ") lies above the axis, which fits the budget: it uses " +
                 Share(out.variance, *out.rms_max * *out.rms_max) + " of the requirement's variance.";
  if (fit.reference_above)
    p.caption += " A reference more than " + Short(kFarAbove) + "× the budget's variance runs off the top.";
  // Variance axis in units of 10^e where the numbers would be long.
  const int e = static_cast<int>(std::floor(std::log10(y_max)));
  const double scale = (e >= 4 || e <= -3) ? std::pow(10.0, e) : 1.0;
  const std::string scale_label = scale == 1.0 ? "" : "10^{" + std::to_string(e) + "} ";

  FigurePanel panel;
  panel.title = CpsTitle(out, digits) + (reverse ? " (reverse CPS)" : "");
  panel.x = FrequencyFigureAxis(range, result.grid);
  panel.y.label = std::string(reverse ? "variance above f" : "cumulative variance") + " [" + scale_label +
                  UnitLabel(VarianceUnit(unit)) + "]";
  panel.y.min = 0.0;
  panel.y.max = y_max / scale;
  panel.y.format = "%g";
  panel.y2 = panel.y;
  panel.y2.label = std::string(reverse ? "RMS above f" : "cumulative RMS") + " [" + UnitLabel(unit) + "]";
  panel.y2.format.clear();
  panel.y2.tics = RmsTicList(y_max, scale,
                             {{out.rms(), SigLabel(out.rms(), digits)},
                              {out.rms_max.value_or(0.0), Short(out.rms_max.value_or(0.0))}});
  panel.key.title = "RMS [" + UnitLabel(unit) + "] (share)";
  const std::string data = p.name + ".csv";
  AddLayers(panel, level, data, scale, digits);
  AddRequirement(panel, result, out, range, fit.limit_above, reverse, scale, digits);
  for (std::size_t i = 0; i < refs.size(); ++i)  // over the layers, under the total
    panel.series.push_back(ReferenceSeries(refs[i], digits, data, 3 + n + i, scale));
  FigureSeries t;  // drawn last: never under a layer
  t.name = "total";
  t.key = "total: " + SigLabel(out.rms(), digits);
  t.data = data;
  t.y_columns = {2 + n};
  t.y_divisor = scale;
  t.colour = kTotalColour;
  t.width = 2.5;
  panel.series.push_back(t);
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

// The range of the positive values a log axis shows.
struct LogRange {
  double top = 0.0, bottom = HUGE_VAL;
};

// The PSD (or ASD) figure's data: frequency, each item's and the total's
// density, then each reference's (NaN outside what it covers). `range`
// takes the shown positive values: every item and reference for the bottom,
// the total and the references for the top; `rows` the grid's rows it holds.
std::string SpectrumCsv(const BudgetResult& result, const OutputResult& out, const FrequencyRange& shown_range, bool asd,
                        LogRange& range, std::vector<std::size_t>& rows) {
  const std::vector<double>& f = result.grid.f_hz();
  const auto value = [&](double psd) { return asd ? std::sqrt(psd) : psd; };
  const std::string unit = DisplayUnit(out.unit);
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.outline.name << ", output " << out.name << ": one-sided "
      << (asd ? "ASD" : "PSD") << " in " << (asd ? AsdUnitLabel(unit) : PsdUnitLabel(unit))
      << ", per contributor and total\n";
  csv << "frequency_hz";
  for (const auto& c : out.contributors) csv << ',' << CsvField(c.name);
  csv << ",total";
  for (const ReferenceResult& r : out.references) csv << ',' << CsvField("measured: " + r.name);
  csv << '\n';
  std::vector<const std::vector<double>*> drawn = {&out.total_psd};
  for (const auto& c : out.contributors) drawn.push_back(&c.psd);
  for (const ReferenceResult& r : out.references) drawn.push_back(&r.psd);
  rows = PlotPoints(f, drawn, shown_range.lo_hz, shown_range.hi_hz);
  for (std::size_t k : rows) {
    csv << CsvNumber(f[k]);
    const bool shown = f[k] >= shown_range.lo_hz && f[k] <= shown_range.hi_hz;
    for (const ContributorResult& c : out.contributors) {
      const double v = value(c.psd[k]);
      csv << ',' << CsvNumber(v);
      if (v > 0.0 && shown) range.bottom = std::min(range.bottom, v);
    }
    const double v = value(out.total_psd[k]);
    csv << ',' << CsvNumber(v);
    if (shown) range.top = std::max(range.top, v);
    // A reference outside the part of the grid it covers: no point (NaN).
    for (const ReferenceResult& r : out.references) {
      const bool covered = f[k] >= r.covered_lo_hz && f[k] <= r.covered_hi_hz;
      csv << ',' << (covered ? CsvNumber(value(r.psd[k])) : std::string("NaN"));
      if (covered && shown) range.top = std::max(range.top, value(r.psd[k]));
    }
    csv << '\n';
  }
  return csv.str();
}

// Band limits as flat levels: a PSD of rms_max^2 / (hi - lo) over the band
// (square-rooted for an ASD); each shown one widens a non-empty range.
void AddBandLimits(FigurePanel& panel, const OutputResult& out, const FrequencyRange& shown, bool asd, LogRange& range) {
  for (const BandRequirementResult& b : out.band_requirements) {
    const BandRequirement& r = b.requirement;
    const double psd = r.rms_max * r.rms_max / (r.hi_hz - r.lo_hz);
    const double level = asd ? std::sqrt(psd) : psd;
    FigureAnnotation a;
    a.kind = AnnotationKind::kSegment;
    a.x0 = std::max(r.lo_hz, shown.lo_hz);
    a.x1 = std::min(r.hi_hz, shown.hi_hz);
    a.y0 = a.y1 = level;
    a.colour = kRequirementColour;
    a.dash = kRequirementDash;
    a.width = 2.0;
    // Behind the curves: a flat contributor at the limit's level (metrology_frame's
    // head_noise at 4.0e-4 against 4.03e-4) was hidden under it.
    a.behind = true;
    a.bracket = true;  // its band's edges: unlike a group's dashed curve in a similar red
    a.key = "band limit " + HzLabel(r.lo_hz) + "–" + HzLabel(r.hi_hz) + " Hz: " + Short(r.rms_max) +
            (b.pass() ? " (pass)" : " (FAIL)");
    if (!(a.x1 > a.x0)) continue;
    panel.annotations.push_back(a);
    if (range.top > 0.0) {
      range.top = std::max(range.top, level);
      range.bottom = std::min(range.bottom, level);
    }
  }
}

// Tones have no density: a marker each, on the total at its frequency,
// labelled with its RMS (the largest kMaxToneLabels labelled). Returns
// whether any is shown.
bool AddToneMarkers(FigurePanel& panel, const BudgetResult& result, const PlotLevel& level, const FrequencyRange& shown,
                    bool asd, bool has_data, int digits) {
  const OutputResult& out = level.out;
  const std::vector<double>& f = result.grid.f_hz();
  struct ToneMark {
    double f_hz, variance;
    std::size_t contributor;
  };
  std::vector<ToneMark> tones;
  for (std::size_t c = 0; c < out.contributors.size(); ++c)
    for (const ContributorResult::Tone& t : out.contributors[c].tones)
      if (t.f_hz >= shown.lo_hz && t.f_hz <= shown.hi_hz) tones.push_back({t.f_hz, t.variance, c});
  std::stable_sort(tones.begin(), tones.end(), [](const ToneMark& a, const ToneMark& b) { return a.variance > b.variance; });
  constexpr std::size_t kMaxToneLabels = 8;
  for (std::size_t i = 0; i < tones.size() && i < 4 * kMaxToneLabels; ++i) {
    const ToneMark& t = tones[i];
    const std::size_t k = static_cast<std::size_t>(std::lower_bound(f.begin(), f.end(), t.f_hz) - f.begin());
    const double psd = out.total_psd[std::min(k, f.size() - 1)];
    const double on_total = asd ? std::sqrt(psd) : psd;
    FigureAnnotation m;
    m.kind = AnnotationKind::kMarker;
    m.x0 = t.f_hz;
    m.y0 = has_data ? std::max(on_total, *panel.y.min) : 1.0;
    m.colour = level.styles[t.contributor].colour;
    m.label_colour = "#202020";  // a light contributor colour would not read over the curves
    m.point_type = 9;  // a triangle
    if (i < kMaxToneLabels)
      m.label = Enhanced(out.contributors[t.contributor].name) + " " + Short(t.f_hz) + " Hz: " +
                SigLabel(std::sqrt(t.variance), digits) + " " + UnitLabel(DisplayUnit(out.unit)) + " RMS";
    m.label_dx = 0.8;
    m.label_dy = 0.8 + 1.2 * static_cast<double>(i % 3);
    panel.annotations.push_back(m);
  }
  return !tones.empty();
}

Plot SpectrumPlot(const BudgetResult& result, std::size_t o, const PlotLevel& level, bool asd, int digits) {
  const OutputResult& out = level.out;
  const std::size_t n = out.contributors.size();
  const std::string unit = DisplayUnit(out.unit);
  const std::string quantity = asd ? "ASD" : "PSD";
  const std::string unit_text = asd ? AsdUnitLabel(unit) : PsdUnitLabel(unit);
  Plot p;
  p.name = FileStem(out.name) + (asd ? "_asd" : "_psd");
  p.kind = PlotKind::kSpectrum;
  p.output = static_cast<int>(o);
  const FrequencyRange shown = level.range;
  p.caption = (asd ? "Amplitude spectral density" : "Power spectral density (one-sided)") + std::string(" of ") +
              out.name + " per " + level.item + ", largest first in the key, and in total (the thin black line over them)." +
              WeightingCaption(result, o, out) + RangeCaption(shown);
  if (!out.band_requirements.empty())
    p.caption += std::string(" Each red bracket, spanning its band, is a band requirement drawn as the flat ") + quantity +
                 " that would use the band's whole allowance (rms_max² spread evenly over the band" +
                 (asd ? ", square-rooted" : "") + "): a curve above it over the whole band fails that band.";
  LogRange range;
  std::vector<std::size_t> rows;
  p.csv = SpectrumCsv(result, out, shown, asd, range, rows);
  if (!out.references.empty())
    p.caption += " Grey dashed: the measured reference(s), never summed (the report's table compares them band by "
                 "band).";

  FigurePanel panel;
  panel.title = Enhanced(out.name) + ": " + (asd ? "amplitude" : "power") + " spectral density, " +
                SigLabel(out.rms(), digits) + " " + UnitLabel(unit) + " RMS";
  panel.x = FrequencyFigureAxis(shown, result.grid);
  panel.y.label = quantity + " [" + UnitLabel(unit_text) + "]";
  panel.y.scale = AxisScale::kLog;
  panel.y.format = "10^{%L}";
  panel.y2.shown = false;
  AddBandLimits(panel, out, shown, asd, range);
  // At most 10 decades (PSD) below the peak: deeper roll-offs only squeeze the figure.
  const double decades = asd ? 5.0 : 10.0;
  if (range.top > 0.0) {
    const double lo = std::max(range.bottom, range.top * std::pow(10.0, -decades));
    panel.y.min = std::pow(10.0, std::floor(std::log10(lo)));
    panel.y.max = std::pow(10.0, std::ceil(std::log10(range.top * 1.5)));
  } else {
    panel.y.min = 0.1;
    panel.y.max = 10.0;
    panel.note = "every contributor is zero on this output";
  }
  if (AddToneMarkers(panel, result, level, shown, asd, range.top > 0.0, digits)) {
    p.caption += " Triangles mark tones (sinusoids, no density): each at its frequency on the total, labelled with "
                 "its RMS; the CPS steps there by its variance.";
    // Their labels keep off the curves, on the CSV's rows.
    const std::vector<double>& f = result.grid.f_hz();
    std::vector<const std::vector<double>*> drawn = {&out.total_psd};
    for (const auto& c : out.contributors) drawn.push_back(&c.psd);
    for (const std::vector<double>* psd : drawn) {
      auto& curve = panel.label_obstacles.emplace_back();
      for (std::size_t k : rows) curve.push_back({f[k], asd ? std::sqrt((*psd)[k]) : (*psd)[k]});
    }
  }
  panel.key.title = "RMS [" + UnitLabel(unit) + "] (share)";
  const std::string data = p.name + ".csv";
  for (std::size_t c : ShareOrder(out)) {
    const SeriesStyle& st = level.styles[c];
    FigureSeries s;
    s.name = out.contributors[c].name;
    s.key = Entry(out.contributors[c].name, out.contributors[c].variance, out.variance, digits);
    s.data = data;
    s.y_columns = {2 + c};
    s.colour = st.colour;
    s.dash = st.dash;
    s.width = 2.0;  // twice the total's width: thicker, the dashes of close curves ran together
    panel.series.push_back(std::move(s));
  }
  for (std::size_t i = 0; i < out.references.size(); ++i)
    panel.series.push_back(ReferenceSeries(out.references[i], digits, data, 3 + n + i, 1.0));
  // The total last, a thin line over the contributors: a contributor that
  // is all of the total shows on both sides of it.
  FigureSeries t;
  t.name = "total";
  t.key = "total: " + SigLabel(out.rms(), digits);
  t.data = data;
  t.y_columns = {2 + n};
  t.colour = kTotalColour;
  t.width = 1.0;
  panel.series.push_back(t);
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace

FrequencyRange DisplayRange(const OutputResult& output, const FrequencyGrid& grid) {
  const std::vector<double>& f = grid.f_hz();
  double lo = HUGE_VAL, hi = 0.0;
  for (const ContributorResult& c : output.contributors) {
    if (!(c.variance > 0.0)) continue;
    const double tail = kDisplayTail * c.variance;
    std::size_t first = 0, last = f.size() - 1;
    while (first + 1 < f.size() && c.cps[first + 1] <= tail) ++first;
    while (last > 0 && c.variance - c.cps[last - 1] <= tail) --last;
    lo = std::min(lo, f[first]);
    hi = std::max(hi, f[last]);
  }
  FrequencyRange r{grid.min_hz(), grid.max_hz(), false};
  if (!(hi > 0.0)) return r;
  lo = std::max(std::pow(10.0, std::floor(std::log10(lo) + 1e-9)), grid.min_hz());
  hi = std::min(std::pow(10.0, std::ceil(std::log10(hi) - 1e-9)), grid.max_hz());
  if (hi < 10.0 * lo) {  // at least one decade, within the grid
    const double mid = std::sqrt(lo * hi);
    lo = std::max(mid / std::sqrt(10.0), grid.min_hz());
    hi = std::min(lo * 10.0, grid.max_hz());
  }
  r.trimmed = lo > grid.min_hz() * (1 + 1e-9) || hi < grid.max_hz() * (1 - 1e-9);
  if (r.trimmed) {
    r.lo_hz = lo;
    r.hi_hz = hi;
  }
  return r;
}

std::string RangeCaption(const FrequencyRange& range) {
  return range.trimmed ? " Shown: " + Short(range.lo_hz) + "–" + Short(range.hi_hz) +
                             " Hz; the CSV covers the whole grid."
                       : "";
}


double NiceStep(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10.0 * p;
}

std::string CpsTitle(const OutputResult& output, int digits) {
  const std::string unit = UnitLabel(DisplayUnit(output.unit));
  std::string s = Enhanced(output.name) + ": " + SigLabel(output.rms(), digits) + " " + unit + " RMS";
  if (!output.rms_max) return s;
  const double limit = *output.rms_max;
  if (output.pass()) return s + ", pass (limit " + Short(limit) + " " + unit + ")";
  return s + ", FAIL " + SigLabel(output.rms() / limit, digits) + "× over " + Short(limit) + " " + unit;
}

FigureAxis FrequencyFigureAxis(const FrequencyRange& range, const FrequencyGrid& grid, const std::string& shown) {
  const double decades = std::log10(range.hi_hz / range.lo_hz);
  const bool powers = decades > 6.0 || range.lo_hz < 1e-3 || range.hi_hz > 1e5;
  FigureAxis a;
  a.scale = AxisScale::kLog;
  a.format = powers ? "10^{%L}" : "%g";
  a.min = range.lo_hz;
  a.max = range.hi_hz;
  // The note is a second, smaller line of the x label: gnuplot reserves room
  // for it, so it never meets the frame, the tic labels or the key. At 0.9
  // of the label's size it is 6.5 pt in report.pdf (0.8 made 5.9 pt).
  a.label = "frequency [Hz]";
  if (range.trimmed)
    a.label += "\n{/*0.9 grid: " + HzLabel(grid.min_hz()) + " to " + HzLabel(grid.max_hz()) + " Hz; shown: " + shown + "}";
  a.minor_grid = decades <= 6.0;
  return a;
}

std::string FrequencyAxis(const FrequencyRange& range, const FrequencyGrid& grid, const std::string& shown) {
  const FigureAxis a = FrequencyFigureAxis(range, grid, shown);
  std::ostringstream os;
  os << "set logscale x 10\nset format x " << Quote(a.format) << "\nset xrange [" << CsvNumber(*a.min) << ":"
     << CsvNumber(*a.max) << "]\n";
  os << "set xlabel " << (range.trimmed ? QuoteLines(a.label) : Quote(a.label)) << "\n";
  if (!a.minor_grid) os << "set grid nomxtics\n";
  return os.str();
}

std::vector<std::size_t> ShareOrder(const OutputResult& output) {
  std::vector<std::size_t> order(output.contributors.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return output.contributors[a].variance > output.contributors[b].variance;
  });
  return order;
}

std::vector<std::pair<double, std::string>> RmsTicList(double variance_max, double scale,
                                                       const std::vector<std::pair<double, std::string>>& marked_rms) {
  const double rms_max = std::sqrt(variance_max);
  const double step = NiceStep(rms_max / 6.0);
  // Closest two labels may sit, in variance: 8 % of the axis, a label's
  // height and a gap in report.pdf's CPS figures where they are drawn at
  // 2/3 of their height to stay on a page (FittedFigureHeights; at 4 % "0.2"
  // sat on "0" at full height, at 5.5 % "0.5" on "0" at 2/3).
  const double gap = 0.08 * variance_max;
  const auto near_marked = [&](double r) {
    for (const auto& [m, label] : marked_rms)
      if (m > 0.0 && std::fabs(r * r - m * m) < 0.12 * variance_max) return true;  // 12 %: a round tic gives way
    return false;
  };
  std::vector<std::pair<double, std::string>> tics = {{0.0, "0"}};
  for (int k = 1; k * step <= rms_max * (1 + 1e-12); ++k) {
    const double r = k * step;
    if (r * r - tics.back().first * tics.back().first < gap || near_marked(r)) continue;
    tics.push_back({r, Short(r)});
  }
  std::vector<double> marked;
  for (const auto& mark : marked_rms) {  // closer than `gap` to an earlier marked value: gives way
    const double m = mark.first;
    const std::string& label = mark.second;
    if (m * m < gap || std::any_of(marked.begin(), marked.end(), [&](double x) { return std::fabs(x * x - m * m) < gap; }))
      continue;
    marked.push_back(m);
    tics.push_back({m, label});
  }
  std::sort(tics.begin(), tics.end());
  for (auto& t : tics) t.first = t.first * t.first / scale;  // to the variance axis
  return tics;
}

std::string RmsTics(double variance_max, double scale, const std::vector<std::pair<double, std::string>>& marked_rms) {
  const auto tics = RmsTicList(variance_max, scale, marked_rms);
  std::ostringstream os;
  os << "set y2tics nomirror (";
  for (std::size_t i = 0; i < tics.size(); ++i) os << (i ? ", " : "") << Quote(tics[i].second) << " " << CsvNumber(tics[i].first);
  os << ")";
  return os.str();
}

namespace {

// A drill-down of `output`: its layers (level->out.contributors, already
// set) under `total`, a part of the output (a group's sum, a contributor),
// named "<output> · <part>", with no requirement, bands or references, shown
// over its own range.
void DrillDown(const OutputResult& output, const ContributorResult& total, const std::string& part,
               const FrequencyGrid& grid, PlotLevel* level) {
  OutputResult& out = level->out;
  out.total_psd = total.psd;
  out.total_cps = total.cps;
  out.variance = total.variance;
  out.bands.clear();
  out.band_requirements.clear();
  out.references.clear();
  out.rms_max.reset();
  out.name = output.name + " · " + part;
  level->range = DisplayRange(out, grid);
}

}  // namespace

PlotLevel GroupLevel(const OutputResult& output, const FrequencyGrid& grid, const std::string& group) {
  PlotLevel level;
  const std::vector<GroupResult> groups = ComputeGroups(output);
  const std::size_t n = output.contributors.size();
  level.range = DisplayRange(output, grid);
  if (groups.empty()) {
    level.out = output;
    for (std::size_t c = 0; c < n; ++c) {
      level.styles.push_back(ContributorStyle(c));
      level.members.push_back({c});
    }
    return level;
  }
  OutputResult& out = level.out;
  out = output;
  out.contributors.clear();
  // A group summed into one item "name/": PSD, CPS, variance and tones of its members at any depth.
  const auto summed = [&](const GroupResult& g) {
    ContributorResult c;
    c.name = g.name + "/";
    c.group = g.path;
    c.psd.assign(output.total_psd.size(), 0.0);
    c.cps.assign(output.total_cps.size(), 0.0);
    for (std::size_t i : g.all_contributors) {
      const ContributorResult& member = output.contributors[i];
      for (std::size_t k = 0; k < c.psd.size(); ++k) {
        c.psd[k] += member.psd[k];
        c.cps[k] += member.cps[k];
      }
      c.variance += member.variance;
      c.tones.insert(c.tones.end(), member.tones.begin(), member.tones.end());
    }
    return c;
  };
  for (std::size_t c = 0; c < n; ++c)
    if (output.contributors[c].group == group) {
      out.contributors.push_back(output.contributors[c]);
      level.styles.push_back(ContributorStyle(c));
      level.members.push_back({c});
    }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t cut = groups[g].path.rfind('/');
    const std::string parent = cut == std::string::npos ? "" : groups[g].path.substr(0, cut);
    if (parent != group) continue;
    out.contributors.push_back(summed(groups[g]));
    level.styles.push_back(GroupStyle(n, g));
    level.members.push_back(groups[g].all_contributors);
  }
  if (group.empty()) {  // the whole output: its total, requirements and references stay
    level.items = "top-level groups (each the sum of its members, a layer \"name/\") and contributors in no group";
    level.item = "top-level group (the sum of its members, \"name/\") and contributor in no group";
    return level;
  }
  for (const GroupResult& g : groups)
    if (g.path == group) DrillDown(output, summed(g), group, grid, &level);
  level.items = "members (a subgroup summed into one layer \"name/\")";
  level.item = "member";
  return level;
}

namespace {

// A plot under another name, its files with it: the script and the figure
// read the data by file name.
void Rename(Plot& p, const std::string& name) {
  const std::string old_data = p.name + ".csv";
  p.name = name;
  const std::string new_data = p.name + ".csv";
  for (std::size_t at = p.script.find(old_data); at != std::string::npos;
       at = p.script.find(old_data, at + new_data.size()))
    p.script.replace(at, old_data.size(), new_data);
  for (FigurePanel& panel : p.figure.panels)
    for (FigureSeries& series : panel.series)
      if (series.data == old_data) series.data = new_data;
}

}  // namespace

std::vector<Plot> GroupCpsPlots(const BudgetResult& result, std::size_t output, int digits) {
  const OutputResult& out = result.outputs[output];
  const std::vector<GroupResult> groups = ComputeGroups(out);
  std::vector<Plot> plots;
  for (const GroupResult& g : groups) {
    if (g.contributors.size() + g.subgroups.size() < 2) continue;
    Plot p = StackedPlot(result, output, GroupLevel(out, result.grid, g.path), false, digits);
    Rename(p, FileStem(out.name) + "_cps_group_" + FileStem(g.path));
    p.caption = "Group " + g.path + ": " + p.caption;
    plots.push_back(std::move(p));
  }
  return plots;
}

PlotLevel ChannelLevel(const OutputResult& output, const FrequencyGrid& grid, std::size_t contributor) {
  const ContributorResult& c = output.contributors[contributor];
  PlotLevel level;
  OutputResult& out = level.out;
  out = output;
  out.contributors.clear();
  // A channel the model does not couple to the output (by symmetry: h0's x
  // and y geophones on z_velocity) adds nothing: named in the caption, not
  // drawn or keyed. Each channel keeps its colour (ChannelStyle of its index).
  std::string none;
  for (std::size_t k = 0; k < c.channels.size(); ++k) {
    const ContributorResult::ChannelPart& part = c.channels[k];
    if (RoundingZero(part.variance, c.variance)) {
      none += (none.empty() ? "" : ", ") + part.channel;
      continue;
    }
    ContributorResult layer;
    layer.name = "channel " + part.channel;
    layer.source = c.source;
    layer.path = c.path;
    layer.psd = part.psd;
    layer.cps = part.cps;
    layer.variance = WithoutRounding(part.variance, c.variance);
    out.contributors.push_back(std::move(layer));
    level.styles.push_back(ChannelStyle(k));
    level.members.emplace_back();
  }
  DrillDown(output, c, c.name, grid, &level);
  level.items = c.cross_variance != 0.0
                    ? "source channels (each |H|² S of one channel; the total also holds the cross terms between "
                      "correlated channels, " +
                          Sig(c.cross_variance, 4) + " " + Squared(UnitText(VarianceUnit(output.unit))) + ")"
                    : "source channels (each |H|² S of one channel; independent channels: they add up to the total)";
  if (!none.empty()) level.items += " (" + none + ": nothing of this output, not drawn)";
  level.item = "source channel";
  return level;
}

std::vector<Plot> ChannelCpsPlots(const BudgetResult& result, std::size_t output, int digits) {
  const OutputResult& out = result.outputs[output];
  std::vector<Plot> plots;
  for (std::size_t c = 0; c < out.contributors.size(); ++c) {
    const ContributorResult& contributor = out.contributors[c];
    std::size_t drawn = 0;
    for (const ContributorResult::ChannelPart& part : contributor.channels)
      drawn += RoundingZero(part.variance, contributor.variance) ? 0 : 1;
    if (drawn < 2) continue;
    Plot p = StackedPlot(result, output, ChannelLevel(out, result.grid, c), false, digits);
    Rename(p, FileStem(out.name) + "_cps_channels_" + FileStem(contributor.name));
    p.caption = "Contributor " + contributor.name + " by source channel: " + p.caption;
    plots.push_back(std::move(p));
  }
  return plots;
}

std::vector<Plot> SpectrumPlots(const BudgetResult& result, std::size_t output, const ReportOptions& options) {
  const PlotLevel top = GroupLevel(result.outputs[output], result.grid, "");
  std::vector<Plot> plots;
  plots.push_back(StackedPlot(result, output, top, false, options.digits));
  if (options.reverse_cps) plots.push_back(StackedPlot(result, output, top, true, options.digits));
  plots.push_back(SpectrumPlot(result, output, top, options.asd, options.digits));
  for (Plot& p : GroupCpsPlots(result, output, options.digits)) plots.push_back(std::move(p));
  for (Plot& p : ChannelCpsPlots(result, output, options.digits)) plots.push_back(std::move(p));
  return plots;
}

}  // namespace deb::report
