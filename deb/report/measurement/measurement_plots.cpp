#include "deb/report/measurement/measurement_plots.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <set>
#include <sstream>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/plot_files.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"
#include "deb/spectra/band_rms.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr const char* kContextColour = "#8c8c8c";  // reference curves and criteria not met
constexpr const char* kContextDash = "(6,4)";

// A title of several lines; lines after the first are details, a size smaller.
std::string Lines(const std::vector<std::string>& lines) {
  std::string title;
  for (std::size_t i = 0; i < lines.size(); ++i) title += i ? "\n{/=11 " + lines[i] + "}" : lines[i];
  return title;
}

// 0.95 -> "95"
std::string Percent(double fraction) { return Short(std::round(fraction * 1e4) / 100.0); }


// Logarithmic frequency axis over [lo_hz, hi_hz]: plain numbers where they
// stay short, powers of ten over wide or extreme ranges.
FigureAxis FrequencyAxis(double lo_hz, double hi_hz) {
  const bool powers = std::log10(hi_hz / lo_hz) > 6.0 || lo_hz < 1e-3 || hi_hz > 1e5;
  FigureAxis a;
  a.scale = AxisScale::kLog;
  a.format = powers ? "10^{%L}" : "%g";
  a.min = lo_hz;
  a.max = hi_hz;
  a.label = "frequency [Hz]";
  // Under two decades the powers of ten alone leave the axis nearly bare: label 2 and 5 too.
  if (!powers && std::log10(hi_hz / lo_hz) < 2.0) {
    for (double decade = std::pow(10.0, std::floor(std::log10(lo_hz))); decade <= hi_hz; decade *= 10.0)
      for (double m : {2.0, 5.0})
        if (m * decade >= lo_hz && m * decade <= hi_hz) a.tics.push_back({m * decade, Short(m * decade)});
    a.tics_added = true;
  }
  return a;
}

// Whole decades around the values in [bottom, top], at most `decades` below
// the top: deeper roll-offs only squeeze the figure. Needs top > 0.
std::pair<double, double> DecadeRange(double bottom, double top, double decades) {
  const double lo = std::max(bottom, top * std::pow(10.0, -decades));
  const double y0 = std::pow(10.0, std::floor(std::log10(lo))), y1 = std::pow(10.0, std::ceil(std::log10(top)));
  return {y0, y1 > y0 ? y1 : 10.0 * y0};
}

// A log y axis of whole decades over [bottom, top] (DecadeRange); nothing
// above 0: a linear axis and a note saying so.
void LogY(FigurePanel& panel, double bottom, double top, double decades) {
  if (!(top > 0.0)) {
    panel.y.min = 0.1;
    panel.y.max = 10.0;
    panel.note = "every value is zero";
    return;
  }
  const auto [y0, y1] = DecadeRange(bottom, top, decades);
  panel.y.scale = AxisScale::kLog;
  panel.y.format = "10^{%L}";
  panel.y.min = y0;
  panel.y.max = y1;
}

std::string SpectrumLabel(const std::string& unit, bool asd) {
  if (unit.empty()) return asd ? "ASD [unit/√Hz, unit not declared]" : "PSD [unit^{2}/Hz, unit not declared]";
  const std::string u = DisplayUnit(unit);
  return asd ? "ASD [" + UnitLabel(AsdUnitLabel(u)) + "]" : "PSD [" + UnitLabel(PsdUnitLabel(u)) + "]";
}

// One curve of a log-log spectrum figure; values <= 0 are not drawn.
struct Curve {
  std::string column;  // CSV header
  std::string title;   // key entry, enhanced text
  std::vector<double> y;
  std::vector<double> lo, hi;  // an interval to shade, or empty
  std::string colour;
  std::string dash = "solid";
  double width = 2.0;
};

struct Figure {
  std::string name, caption, comment;  // comment: the CSV's first line
  std::vector<std::string> title;      // lines
  std::string ylabel, key_title;
  std::vector<double> f_hz;            // > 0, increasing
  std::vector<Curve> curves;
  double decades = 10.0;               // of the y axis below the largest value
  std::string interval_title;          // key entry of the shaded intervals
};

Plot LogLogPlot(const Figure& fig) {
  Plot p;
  p.name = fig.name;
  p.kind = PlotKind::kSpectrum;
  p.caption = fig.caption;
  std::vector<const std::vector<double>*> drawn;
  for (const Curve& c : fig.curves) {
    drawn.push_back(&c.y);
    if (!c.lo.empty()) drawn.insert(drawn.end(), {&c.lo, &c.hi});
  }
  const double lo_hz = fig.f_hz.front(), hi_hz = fig.f_hz.back();
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ": " << fig.comment << "\nf_hz";
  for (const Curve& c : fig.curves) {
    csv << ',' << CsvField(c.column);
    if (!c.lo.empty()) csv << ',' << CsvField(c.column + "_lo") << ',' << CsvField(c.column + "_hi");
  }
  csv << '\n';
  double top = 0.0, bottom = HUGE_VAL;
  for (std::size_t k : PlotPoints(fig.f_hz, drawn, lo_hz, hi_hz)) {
    csv << CsvNumber(fig.f_hz[k]);
    for (const std::vector<double>* s : drawn) {
      const double v = (*s)[k];
      csv << ',' << CsvNumber(v);
      if (v > 0.0) {
        top = std::max(top, v);
        bottom = std::min(bottom, v);
      }
    }
    csv << '\n';
  }
  p.csv = csv.str();

  FigurePanel panel;
  panel.title = Lines(fig.title);
  panel.x = FrequencyAxis(lo_hz, hi_hz);
  LogY(panel, bottom, top, fig.decades);
  panel.y.label = fig.ylabel;
  panel.y2.shown = false;
  panel.key.title = fig.key_title;
  const std::string data = StandaloneDataFile(p.name);
  std::vector<FigureSeries> lines;
  std::size_t column = 2;
  for (const Curve& c : fig.curves) {
    FigureSeries line;
    line.name = c.column;
    line.key = c.title;
    line.data = data;
    line.y_columns = {column++};
    line.colour = c.colour;
    line.dash = c.dash;
    line.width = c.width;
    lines.push_back(line);
    if (!c.lo.empty()) {
      // Shaded under the lines, light enough that crossing intervals stay apart.
      FigureSeries interval;
      interval.name = c.column + " interval";
      interval.kind = SeriesKind::kFilled;
      interval.data = data;
      interval.low_columns = {column};
      interval.y_columns = {column + 1};
      interval.colour = c.colour;
      interval.fill_opacity = 0.22;
      panel.series.push_back(interval);
      column += 2;
    }
  }
  if (!panel.series.empty() && !fig.interval_title.empty()) {
    FigureAnnotation entry;
    entry.kind = AnnotationKind::kKeyEntry;
    entry.fill_sample = true;
    entry.colour = "#a0a0a0";
    entry.key = fig.interval_title;
    panel.annotations.push_back(entry);
  }
  panel.series.insert(panel.series.end(), lines.begin(), lines.end());
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

// Bins above 0 Hz: a log frequency axis shows only those, and needs two.
// @throws InputError naming the plot otherwise (e.g. a 2-sample segment).
std::vector<std::size_t> PositiveBins(const std::vector<double>& f_hz, const std::string& name) {
  std::vector<std::size_t> bins;
  for (std::size_t k = 0; k < f_hz.size(); ++k)
    if (f_hz[k] > 0.0) bins.push_back(k);
  if (bins.size() < 2)
    throw InputError("cannot draw plot " + name + ": it needs at least 2 frequencies above 0 Hz, the spectrum has " +
                     std::to_string(bins.size()) + " (use a longer segment, or --no-plots)");
  return bins;
}

std::vector<double> Column(const Eigen::MatrixXd& m, Eigen::Index c, const std::vector<std::size_t>& rows,
                           double factor = 1.0, bool root = false) {
  std::vector<double> v;
  v.reserve(rows.size());
  for (std::size_t k : rows) {
    const double x = factor * m(static_cast<Eigen::Index>(k), c);
    v.push_back(root ? std::sqrt(std::max(x, 0.0)) : x);
  }
  return v;
}

std::vector<double> Pick(const std::vector<double>& x, const std::vector<std::size_t>& rows) {
  std::vector<double> v;
  for (std::size_t k : rows) v.push_back(x[k]);
  return v;
}

// "hann window, 4096-sample segments, 50 % overlap, 31 mean averages, Δf = 0.244 Hz, f_s = 1000 Hz"
std::string WelchSettings(const WelchProvenance& w) {
  const double overlap = w.segment_length > 0 ? 100.0 * w.overlap_samples / w.segment_length : 0.0;
  return Enhanced(ToString(w.window)) + " window, " + std::to_string(w.segment_length) + "-sample segments, " +
         Short(std::round(overlap * 10.0) / 10.0) + " % overlap, " + std::to_string(w.segments) + " " +
         ToString(w.averaging) + " averages, Δf = " + Sig(w.resolution_hz) + " Hz, f_{s} = " + Short(w.rate_hz) +
         " Hz";
}

std::string SeriesText(ThirdOctaveSeries series) {
  switch (series) {
    case ThirdOctaveSeries::kBase2From1Hz: return "base-2 centres from 1 Hz";
    case ThirdOctaveSeries::kIecBase2: return "IEC 61260 base-2 centres";
    case ThirdOctaveSeries::kIecBase10: return "IEC 61260 base-10 centres";
  }
  return "";
}

}  // namespace

Plot WelchPsdPlot(const PsdEstimate& e, const std::string& source, bool bounds, const std::string& name) {
  const std::vector<std::size_t> bins = PositiveBins(e.f_hz, name);
  const WelchProvenance& w = e.provenance;
  Figure fig;
  fig.name = name;
  fig.f_hz = Pick(e.f_hz, bins);
  fig.comment = "Welch PSD of " + source + " per channel" + (bounds ? " with its chi-square bounds" : "") +
                ", one-sided, in " + (e.unit.empty() ? "unit^2/Hz" : PsdUnitLabel(DisplayUnit(e.unit)));
  fig.caption = "Welch PSD of " + source + " per channel" +
                (bounds ? ", shaded: the " + Percent(w.confidence) + " % chi-square confidence interval" : "") +
                ".";
  fig.title = {"Welch PSD of " + Enhanced(source), WelchSettings(w)};
  fig.ylabel = SpectrumLabel(e.unit, false);
  fig.key_title = "channel";
  for (Eigen::Index c = 0; c < e.psd.cols(); ++c) {
    Curve curve;
    curve.column = e.channel_names[static_cast<std::size_t>(c)];
    curve.title = Enhanced(curve.column);
    curve.y = Column(e.psd, c, bins);
    if (bounds) {
      curve.lo = Column(e.psd, c, bins, w.lower_factor);
      curve.hi = Column(e.psd, c, bins, w.upper_factor);
    }
    const SeriesStyle st = ContributorStyle(static_cast<std::size_t>(c));
    curve.colour = st.colour;
    curve.width = 1.5;
    fig.curves.push_back(std::move(curve));
  }
  if (bounds)
    fig.interval_title = Percent(w.confidence) + " % χ^{2} interval (ν = " + Sig(w.degrees_of_freedom, 3) +
                         ")";
  return LogLogPlot(fig);
}

Plot FrfPlot(const FrfEstimate& e, const std::string& unit, const std::string& source, const std::string& name) {
  const std::vector<std::size_t> bins = PositiveBins(e.f_hz, name);
  const std::vector<double> f = Pick(e.f_hz, bins);
  const std::size_t n = e.outputs.size();
  std::vector<std::vector<double>> mag(n), phase(n), coh(n);
  for (std::size_t o = 0; o < n; ++o)
    for (std::size_t k : bins) {
      const std::complex<double> h = e.h(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(o));
      mag[o].push_back(std::abs(h));
      phase[o].push_back(std::arg(h) * 180.0 / kPi);  // wrapped to (-180, 180]
      coh[o].push_back(e.coherence(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(o)));
    }
  // The points either panel needs: |H1| on its log axis, gamma^2 on its linear one.
  std::vector<const std::vector<double>*> mags, cohs;
  for (std::size_t o = 0; o < n; ++o) {
    mags.push_back(&mag[o]);
    cohs.push_back(&coh[o]);
  }
  std::vector<const std::vector<double>*> phases;
  for (std::size_t o = 0; o < n; ++o) phases.push_back(&phase[o]);
  std::vector<std::size_t> rows = PlotPoints(f, mags, f.front(), f.back());
  for (const auto* series : {&cohs, &phases}) {
    const std::vector<std::size_t> more = PlotPoints(f, *series, f.front(), f.back(), PlotScale::kLinear);
    rows.insert(rows.end(), more.begin(), more.end());
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());

  Plot p;
  p.name = name;
  p.kind = PlotKind::kSpectrum;
  p.caption = std::string(e.estimator == FrfEstimator::kH1 ? "H1" : "H2") + " frequency response from " + e.input + " to each output of " + source +
              ": magnitude (top), phase (middle) and coherence (bottom).";
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ": |H1| from " << e.input << " to each output of " << source
      << (unit.empty() ? "" : ", in " + unit) << ", the coherence gamma^2 and the phase in degrees\nf_hz";
  for (const auto& o : e.outputs) csv << ',' << CsvField("mag_" + o);
  for (const auto& o : e.outputs) csv << ',' << CsvField("coherence_" + o);
  for (const auto& o : e.outputs) csv << ',' << CsvField("phase_deg_" + o);
  csv << '\n';
  double top = 0.0, bottom = HUGE_VAL;
  for (std::size_t k : rows) {
    csv << CsvNumber(f[k]);
    for (const auto& m : mag) {
      csv << ',' << CsvNumber(m[k]);
      if (m[k] > 0.0) top = std::max(top, m[k]), bottom = std::min(bottom, m[k]);
    }
    for (const auto& c : coh) csv << ',' << CsvNumber(c[k]);
    for (const auto& ph : phase) csv << ',' << CsvNumber(ph[k]);
    csv << '\n';
  }
  p.csv = csv.str();

  const std::string data = StandaloneDataFile(name);
  const std::string est = e.estimator == FrfEstimator::kH1 ? "H_1" : "H_2";
  p.figure.title = Lines({"Frequency response (" + est + ") of " + Enhanced(source) + " from " + Enhanced(e.input),
                          WelchSettings(e.provenance)});
  // Magnitude over phase over coherence, sharing the frequency axis.
  FigurePanel magnitude, angle, coherence;
  for (FigurePanel* panel : {&magnitude, &angle, &coherence}) {
    panel->x = FrequencyAxis(f.front(), f.back());
    panel->y2.shown = false;
    panel->key.placement = KeyPlacement::kNone;
  }
  magnitude.height = 0.40;
  angle.height = 0.23;
  coherence.height = 0.33;
  LogY(magnitude, bottom, top, 10.0);
  magnitude.y.label = unit.empty() ? "magnitude |" + est + "|" : "magnitude |" + est + "| [" + UnitLabel(unit) + "]";
  magnitude.key.placement = KeyPlacement::kOutsideRight;
  magnitude.key.title = "output";
  angle.y.label = "phase [°]";
  angle.y.min = -180.0;
  angle.y.max = 180.0;
  for (int deg = -180; deg <= 180; deg += 90) angle.y.tics.push_back({static_cast<double>(deg), std::to_string(deg)});
  coherence.y.label = "coherence γ^{2}";
  coherence.y.min = 0.0;
  coherence.y.max = 1.05;
  for (const char* tic : {"0", "0.25", "0.5", "0.75", "1"}) coherence.y.tics.push_back({std::stod(tic), tic});
  for (std::size_t o = 0; o < n; ++o) {
    FigureSeries s;
    s.name = e.outputs[o];
    s.data = data;
    s.colour = ContributorStyle(o).colour;
    s.width = 1.5;
    s.y_columns = {o + 2};
    s.key = Enhanced(e.outputs[o]);
    magnitude.series.push_back(s);
    s.key.clear();
    s.y_columns = {n + o + 2};
    coherence.series.push_back(s);
    // Wrapped phase as dots: lines would draw a false vertical at every wrap.
    s.y_columns = {2 * n + o + 2};
    s.kind = SeriesKind::kPoints;
    s.point_type = 7;
    s.point_size = 0.35;
    s.width = 1.0;
    angle.series.push_back(s);
  }
  p.figure.panels = {magnitude, angle, coherence};
  p.figure.key_margin = 16.0;  // output names are short
  p.script = EmitFigure(p.figure);
  return p;
}

Plot CoherencePlot(const CsdEstimate& csd, const std::string& source, const std::string& name) {
  DEB_DEMAND(csd.channels >= 2);
  const std::vector<std::size_t> bins = PositiveBins(csd.f_hz, name);
  const std::vector<double> f = Pick(csd.f_hz, bins);
  const WelchProvenance& w = csd.provenance;
  std::vector<std::string> columns, labels;
  std::vector<std::vector<double>> series;
  for (int b = 0; b < csd.channels; ++b)
    for (int a = 0; a < b; ++a) {
      const std::string& na = csd.channel_names[static_cast<std::size_t>(a)];
      const std::string& nb = csd.channel_names[static_cast<std::size_t>(b)];
      columns.push_back(na + "_" + nb);
      labels.push_back(Enhanced(na) + " – " + Enhanced(nb));
      const Eigen::VectorXd g = csd.Coherence(a, b);
      std::vector<double> v;
      for (std::size_t k : bins) v.push_back(g(static_cast<Eigen::Index>(k)));
      series.push_back(std::move(v));
    }
  Plot p;
  p.name = name;
  p.kind = PlotKind::kSpectrum;
  p.caption = "Magnitude-squared coherence of every channel pair of " + source + ".";
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ": magnitude-squared coherence |S_ab|^2/(S_aa S_bb) of " << source
      << " per channel pair\nf_hz";
  for (const std::string& c : columns) csv << ',' << CsvField("coherence_" + c);
  csv << '\n';
  std::vector<const std::vector<double>*> drawn;
  for (const auto& v : series) drawn.push_back(&v);
  for (std::size_t k : PlotPoints(f, drawn, f.front(), f.back(), PlotScale::kLinear)) {
    csv << CsvNumber(f[k]);
    for (const auto& v : series) csv << ',' << CsvNumber(v[k]);
    csv << '\n';
  }
  p.csv = csv.str();

  FigurePanel panel;
  panel.title = Lines({"Coherence of " + Enhanced(source), WelchSettings(w)});
  panel.x = FrequencyAxis(f.front(), f.back());
  panel.y.label = "coherence γ^{2}";
  panel.y.min = 0.0;
  panel.y.max = 1.02;
  for (const char* tic : {"0", "0.2", "0.4", "0.6", "0.8", "1"}) panel.y.tics.push_back({std::stod(tic), tic});
  panel.y2.shown = false;
  panel.key.title = "channel pair";
  for (std::size_t i = 0; i < columns.size(); ++i) {
    FigureSeries s;
    s.name = columns[i];
    s.key = labels[i];
    s.data = StandaloneDataFile(name);
    s.y_columns = {i + 2};
    s.colour = ContributorStyle(i).colour;
    s.width = 1.5;
    panel.series.push_back(s);
  }
  // Zero true coherence: P(estimate > x) = (1 - x)^(n - 1) for n independent averages.
  const double n = 0.5 * w.degrees_of_freedom;
  if (n > 1.0 && w.confidence > 0.0 && w.confidence < 1.0) {
    const double level = 1.0 - std::pow(1.0 - w.confidence, 1.0 / (n - 1.0));
    FigureAnnotation bound;
    bound.kind = AnnotationKind::kHorizontalLine;
    bound.y0 = level;
    bound.colour = kContextColour;
    bound.dash = kContextDash;
    bound.width = 1.5;
    bound.key = "zero coherence, " + Percent(w.confidence) + " % bound: " + Sig(level, 2);
    panel.annotations.push_back(bound);
  }
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

Plot SelfNoisePlot(const PsdEstimate& sensors, const SelfNoiseEstimate& noise, const std::string& source,
                   const std::string& name) {
  DEB_DEMAND(sensors.f_hz == noise.noise.f_hz && sensors.psd.cols() == noise.noise.psd.cols());
  const std::vector<std::size_t> bins = PositiveBins(sensors.f_hz, name);
  Figure fig;
  fig.name = name;
  fig.f_hz = Pick(sensors.f_hz, bins);
  const bool three = sensors.psd.cols() == 3;
  const std::string method = three ? "three-sensor method (Sleeman et al. 2006)"
                                   : "two-sensor method (Holcomb 1989), identical sensors assumed";
  fig.comment = "PSD of each sensor of " + source + " and its self-noise, " + method + ", in " +
                (sensors.unit.empty() ? "unit^2/Hz" : PsdUnitLabel(DisplayUnit(sensors.unit)));
  fig.caption = "PSD of each sensor of " + source + " (solid) and its self-noise estimate (dashed), " + method + ".";
  fig.title = {"Sensor self-noise from " + Enhanced(source) + ": " + method, WelchSettings(sensors.provenance)};
  fig.ylabel = SpectrumLabel(sensors.unit, false);
  fig.key_title = "sensor";
  for (Eigen::Index c = 0; c < sensors.psd.cols(); ++c) {
    const std::string sensor = sensors.channel_names[static_cast<std::size_t>(c)];
    const SeriesStyle st = ContributorStyle(static_cast<std::size_t>(c));
    Curve psd;
    psd.column = sensor;
    psd.title = Enhanced(sensor) + ": PSD";
    psd.y = Column(sensors.psd, c, bins);
    psd.colour = st.colour;
    psd.width = 1.5;
    Curve n;
    n.column = sensor + "_noise";
    const int clamped = static_cast<std::size_t>(c) < noise.clamped_bins.size()
                            ? noise.clamped_bins[static_cast<std::size_t>(c)]
                            : 0;
    n.title = Enhanced(sensor) + ": self-noise" +
              (clamped > 0 ? " (" + std::to_string(clamped) + " bins < 0, not drawn)" : "");
    n.y = Column(noise.noise.psd, c, bins);
    n.colour = st.edge_colour;
    n.dash = "(10,5)";
    n.width = 2.0;
    fig.curves.push_back(std::move(psd));
    fig.curves.push_back(std::move(n));
  }
  return LogLogPlot(fig);
}

Plot SpectrumTablePlot(const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                       const std::vector<std::string>& channel_names, const std::string& unit, bool asd,
                       const std::string& title, const std::string& name) {
  const std::vector<std::size_t> bins = PositiveBins(f_hz, name);
  DEB_DEMAND(static_cast<std::size_t>(psd.cols()) == channel_names.size());
  Figure fig;
  fig.name = name;
  fig.f_hz = Pick(f_hz, bins);
  const std::string quantity = asd ? "ASD" : "PSD";
  const std::string unit_text = unit.empty() ? "" : asd ? AsdUnitLabel(DisplayUnit(unit)) : PsdUnitLabel(DisplayUnit(unit));
  fig.comment = title + ": one-sided " + quantity + (unit_text.empty() ? "" : " in " + unit_text) + " per channel";
  fig.caption = title + ": one-sided " + quantity + " per channel.";
  fig.title = {Enhanced(title)};
  fig.ylabel = SpectrumLabel(unit, asd);
  fig.key_title = "channel";
  fig.decades = asd ? 5.0 : 10.0;
  for (Eigen::Index c = 0; c < psd.cols(); ++c) {
    Curve curve;
    curve.column = channel_names[static_cast<std::size_t>(c)];
    curve.title = Enhanced(curve.column);
    curve.y = Column(psd, c, bins, 1.0, asd);
    curve.colour = ContributorStyle(static_cast<std::size_t>(c)).colour;
    fig.curves.push_back(std::move(curve));
  }
  return LogLogPlot(fig);
}

Plot PetersonPlot(PetersonModel written, const std::vector<double>& f_hz, const std::string& unit, bool asd,
                  const std::string& name) {
  DEB_DEMAND(f_hz.size() >= 2);
  const UnitConversion conv = ConvertUnit(PetersonSpectrum::kUnit, unit);
  Figure fig;
  fig.name = name;
  fig.f_hz = f_hz;
  const std::string quantity = asd ? "ASD" : "PSD";
  fig.comment = "Peterson (1993) NLNM and NHNM, vertical ground motion, one-sided " + quantity + " in " +
                (asd ? AsdUnitLabel(DisplayUnit(unit)) : PsdUnitLabel(DisplayUnit(unit)));
  fig.caption = "Peterson's (1993) new low and high noise models of vertical ground motion, " + quantity + " in " +
                UnitText(unit) + "; " + ToString(written) + " is the one written.";
  fig.title = {"Peterson (1993) noise models, vertical ground motion (USGS OFR 93-322)",
               ToString(written) == "nlnm" ? "NLNM written; NHNM for context" : "NHNM written; NLNM for context"};
  fig.ylabel = SpectrumLabel(unit, asd);
  // All of both models: in displacement or velocity they span 20+ decades.
  fig.decades = 1e3;
  for (PetersonModel m : {PetersonModel::kHigh, PetersonModel::kLow}) {
    Curve curve;
    curve.column = ToString(m);
    curve.title = m == PetersonModel::kLow ? "NLNM (new low noise model)" : "NHNM (new high noise model)";
    for (double f : f_hz) {
      const double psd = PetersonAccelerationPsd(m, f) * conv.PsdFactor(f);
      curve.y.push_back(asd ? std::sqrt(psd) : psd);
    }
    const bool main = m == written;
    curve.colour = main ? kTotalColour : kContextColour;
    curve.dash = main ? "solid" : kContextDash;
    curve.width = main ? 2.5 : 1.8;
    fig.curves.push_back(std::move(curve));
  }
  return LogLogPlot(fig);
}

namespace {

// The range of the positive levels a band chart draws.
struct LevelRange {
  double bottom = HUGE_VAL, top = 0.0;
  void Take(double level) {
    top = std::max(top, level);
    bottom = std::min(bottom, level);
  }
};

// A building criterion over the bands it covers (continued down with the
// extension), clipped to the bands analysed.
struct DrawnCriterion {
  std::string name;
  double level = 0.0, from_hz = 0.0, to_hz = 0.0;
  bool met = false;  // some channel's overall class
};

// The band chart's data blocks 0 (steps: each band's lower edge, then the
// last upper edge) and 1 (band centres); the range takes every positive RMS.
void WriteBandBlocks(std::ostream& csv, const std::vector<std::string>& channel_names,
                     const std::vector<std::vector<BandRms>>& bands, const std::vector<Classification>& verdicts,
                     LevelRange& range) {
  const std::size_t channels = bands.size(), n = bands.front().size();
  const double hi_hz = bands.front().back().band.hi_hz;
  csv << "edge_hz";
  for (const std::string& c : channel_names) csv << ',' << CsvField(c);
  csv << '\n';
  for (std::size_t i = 0; i <= n; ++i) {
    csv << CsvNumber(i < n ? bands.front()[i].band.lo_hz : hi_hz);
    for (std::size_t c = 0; c < channels; ++c) {
      const double rms = bands[c][std::min(i, n - 1)].rms;
      csv << ',' << CsvNumber(rms);
      if (rms > 0.0) range.Take(rms);
    }
    csv << '\n';
  }
  csv << "\n\ncentre_hz,lo_hz,hi_hz,points";
  for (const std::string& c : channel_names) csv << ',' << CsvField(c) << ',' << CsvField(c + "_limiting");
  csv << '\n';
  for (std::size_t i = 0; i < n; ++i) {
    const BandRms& b = bands.front()[i];
    csv << CsvNumber(b.band.centre_hz) << ',' << CsvNumber(b.band.lo_hz) << ',' << CsvNumber(b.band.hi_hz) << ','
        << b.points;
    for (std::size_t c = 0; c < channels; ++c)
      csv << ',' << CsvNumber(bands[c][i].rms) << ',' << (!verdicts.empty() && verdicts[c].limiting_band == i ? 1 : 0);
    csv << '\n';
  }
}

// The criteria over [lo_hz, hi_hz]; the range takes their levels.
std::vector<DrawnCriterion> CriteriaDrawn(const std::vector<Classification>& verdicts, const ClassifyOptions& options,
                                          double lo_hz, double hi_hz, LevelRange& range) {
  std::vector<DrawnCriterion> criteria;
  std::set<std::size_t> overall;
  for (const Classification& v : verdicts)
    if (v.overall) overall.insert(*v.overall);
  const std::vector<BuildingCriterion>& all = verdicts.front().criteria;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const BuildingCriterion& bc = all[k];
    const bool extended = options.low_frequency_extension && bc.extendable;
    const double from = extended ? lo_hz : ThirdOctaveBandNear(bc.lowest_band_hz, options.series).lo_hz;
    const double to = ThirdOctaveBandNear(bc.highest_band_hz, options.series).hi_hz;
    const double a = std::max(from, lo_hz), b = std::min(to, hi_hz);
    if (!(b > a)) continue;
    criteria.push_back({bc.name, bc.velocity_um_s, a, b, overall.count(k) > 0});
    range.Take(bc.velocity_um_s);
  }
  return criteria;
}

// Data block 2: the criteria drawn.
void WriteCriteriaBlock(std::ostream& csv, const std::vector<DrawnCriterion>& criteria) {
  csv << "\n\ncriterion,level_um_s,from_hz,to_hz,met\n";
  for (const DrawnCriterion& d : criteria)
    csv << CsvField(d.name) << ',' << CsvNumber(d.level) << ',' << CsvNumber(d.from_hz) << ','
        << CsvNumber(d.to_hz) << ',' << (d.met ? 1 : 0) << '\n';
}

// Each channel's class in words: long for the title, short for the key.
struct ChannelVerdictText {
  std::vector<std::string> title, key;
};

ChannelVerdictText VerdictText(const std::vector<Classification>& verdicts, std::size_t channels,
                               const std::string& unit_label) {
  ChannelVerdictText text;
  text.title.resize(channels);
  text.key.resize(channels);
  for (std::size_t c = 0; c < verdicts.size(); ++c) {
    const Classification& v = verdicts[c];
    const std::string met = v.overall ? Enhanced(v.criteria[*v.overall].name) : "none";
    text.title[c] = v.overall ? met + " met" : "no criterion met";
    text.key[c] = ": " + met;
    if (v.limiting_band) {
      const BandRms& b = v.bands[*v.limiting_band].band;
      text.title[c] += "; limiting band " + Sig(b.band.centre_hz) + " Hz at " + SigLabel(b.rms) + " " + unit_label;
      text.key[c] += " (limiting " + Sig(b.band.centre_hz) + " Hz)";
    }
  }
  return text;
}

// Title: what, then the class of each channel (up to three; more in the key).
std::vector<std::string> BandClassTitle(const std::vector<std::string>& channel_names, bool classified,
                                        const ChannelVerdictText& text, const ClassifyOptions& options,
                                        const std::string& source) {
  std::vector<std::string> title = {"One-third-octave band RMS of " + Enhanced(source) + " (" +
                                    SeriesText(options.series) + ")"};
  if (!classified) return title;
  const std::size_t channels = channel_names.size();
  if (channels == 1) title.push_back(text.title[0]);
  else if (channels <= 3)
    for (std::size_t c = 0; c < channels; ++c) title.push_back(Enhanced(channel_names[c]) + ": " + text.title[c]);
  else title.push_back("class of each channel in the key");
  if (options.low_frequency_extension) title.back() += " (VC continued below 8 Hz)";
  return title;
}

// The criteria named on the right axis at their level (they sit a factor 2
// apart, so the names never crowd) and drawn as lines behind the bands' steps.
void DrawCriteria(FigurePanel& panel, const std::vector<DrawnCriterion>& criteria) {
  panel.y2 = panel.y;
  panel.y2.label.clear();
  panel.y2.format.clear();
  for (const DrawnCriterion& d : criteria) panel.y2.tics.push_back({d.level, Enhanced(d.name)});
  for (const DrawnCriterion& d : criteria) {
    FigureAnnotation line;
    line.kind = AnnotationKind::kSegment;
    line.x0 = d.from_hz;
    line.x1 = d.to_hz;
    line.y0 = line.y1 = d.level;
    line.colour = d.met ? kRequirementColour : kContextColour;
    line.dash = d.met ? "solid" : kContextDash;
    line.width = d.met ? 2.0 : 1.3;
    line.behind = true;
    panel.annotations.push_back(line);
  }
}

// Channel c's steps, a point at each centre (filled where the band holds
// enough spectral lines, open where not) and, when classified, a ring on
// its limiting band.
void AddChannelSeries(FigurePanel& panel, std::size_t c, const std::string& channel, const std::string& key,
                      const std::string& data, bool classified) {
  const SeriesStyle st = ContributorStyle(c);
  FigureSeries steps;
  steps.name = channel;
  steps.key = key;
  steps.kind = SeriesKind::kSteps;
  steps.data = data;
  steps.block = 0;
  steps.y_columns = {2 + c};
  steps.colour = st.colour;
  panel.series.push_back(steps);
  FigureSeries centres;
  centres.name = channel + " centres";
  centres.kind = SeriesKind::kPoints;
  centres.data = data;
  centres.block = 1;
  centres.y_columns = {5 + 2 * c};
  centres.where_column = 4;
  centres.where_value = kFewLines;
  centres.where_test = WhereTest::kAtLeast;
  centres.colour = st.edge_colour;
  centres.point_type = 7;
  centres.point_size = 0.8;
  centres.width = 1.0;
  panel.series.push_back(centres);
  centres.name = channel + " coarse centres";
  centres.where_test = WhereTest::kLess;
  centres.point_type = 6;
  centres.point_size = 0.9;
  panel.series.push_back(centres);
  if (!classified) return;
  FigureSeries ring = centres;
  ring.name = channel + " limiting band";
  ring.where_column = 6 + 2 * c;
  ring.where_value = 1.0;
  ring.where_test = WhereTest::kEqual;
  ring.point_size = 2.6;
  ring.width = 1.5;
  ring.colour = kRequirementColour;
  panel.series.push_back(ring);
}

FigureAnnotation MarkerKeyEntry(const std::string& key, const std::string& colour, double size, double width) {
  FigureAnnotation entry;
  entry.kind = AnnotationKind::kKeyEntry;
  entry.key = key;
  entry.colour = colour;
  entry.point_type = 6;
  entry.point_size = size;
  entry.width = width;
  return entry;
}

// The key's entries for the markers and the criteria's lines, after the channels.
std::vector<FigureAnnotation> BandClassKeyEntries(bool coarse, bool classified) {
  std::vector<FigureAnnotation> entries;
  if (coarse)
    entries.push_back(MarkerKeyEntry("band with < " + std::to_string(kFewLines) + " spectral lines", "#404040", 0.9, 1.0));
  if (classified) {
    entries.push_back(MarkerKeyEntry("limiting band", kRequirementColour, 2.0, 1.5));
    FigureAnnotation met = MarkerKeyEntry("class met", kRequirementColour, 1.0, 2.0);
    met.point_type = 0;  // a line
    FigureAnnotation other = met;
    other.key = "other criteria";
    other.colour = kContextColour;
    other.dash = kContextDash;
    other.width = 1.3;
    entries.push_back(met);
    entries.push_back(other);
  }
  return entries;
}

}  // namespace

Plot BandClassPlot(const std::vector<std::string>& channel_names, const std::vector<std::vector<BandRms>>& bands,
                   const std::vector<Classification>& verdicts, const ClassifyOptions& options,
                   const std::string& unit, const std::string& source, const std::string& name) {
  DEB_DEMAND(!bands.empty() && bands.size() == channel_names.size() && !bands.front().empty());
  DEB_DEMAND(verdicts.empty() || verdicts.size() == bands.size());
  const std::size_t channels = bands.size();
  const bool classified = !verdicts.empty();
  const std::string unit_label = unit.empty() ? "unit not declared" : UnitLabel(DisplayUnit(unit));
  const double lo_hz = bands.front().front().band.lo_hz, hi_hz = bands.front().back().band.hi_hz;
  Plot p;
  p.name = name;
  p.kind = PlotKind::kBands;
  p.caption = "One-third-octave band RMS of " + source + " per channel" +
              (classified ? ", against the building vibration criteria." : ".");

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ": one-third-octave band RMS of " << source << " ("
      << ToString(options.series) << " centres)" << (unit.empty() ? "" : " in " + DisplayUnit(unit))
      << "; block 0 steps, block 1 bands, block 2 criteria\n";
  LevelRange range;
  WriteBandBlocks(csv, channel_names, bands, verdicts, range);
  std::vector<DrawnCriterion> criteria;
  if (classified) {
    criteria = CriteriaDrawn(verdicts, options, lo_hz, hi_hz, range);
    WriteCriteriaBlock(csv, criteria);
  }
  p.csv = csv.str();

  const ChannelVerdictText text = VerdictText(verdicts, channels, unit_label);
  FigurePanel panel;
  panel.title = Lines(BandClassTitle(channel_names, classified, text, options, source));
  panel.x = FrequencyAxis(lo_hz, hi_hz);
  LogY(panel, range.bottom / 1.2, range.top * 1.2, 8.0);
  panel.y.label = "band RMS [" + unit_label + "]";
  panel.y2.shown = false;
  panel.key.title = "channel";
  if (!criteria.empty()) DrawCriteria(panel, criteria);
  const std::string data = StandaloneDataFile(name);
  for (std::size_t c = 0; c < channels; ++c)
    AddChannelSeries(panel, c, channel_names[c], Enhanced(channel_names[c]) + (channels == 1 ? "" : text.key[c]), data,
                     classified);
  bool coarse = false;
  for (const BandRms& b : bands.front()) coarse = coarse || b.points < kFewLines;
  const std::vector<FigureAnnotation> entries = BandClassKeyEntries(coarse, classified);
  panel.annotations.insert(panel.annotations.end(), entries.begin(), entries.end());
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace deb::report
