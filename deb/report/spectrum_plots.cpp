#include "deb/report/spectrum_plots.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "deb/report/plot_points.h"
#include "deb/report/plot_style.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {

std::string Col(std::size_t column) { return "column(" + std::to_string(column) + ")"; }

// "floor: 12.3 (78.1 %)" for a key whose title names the unit.
std::string Entry(const std::string& name, double variance, double total_variance) {
  std::string s = Enhanced(name) + ": " + SigLabel(std::sqrt(variance));
  if (total_variance > 0.0) s += " (" + Share(variance, total_variance) + ")";
  return s;
}

// Smallest "nice" step (1, 2, 2.5, 5 x 10^n) not below x.
double NiceStep(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10.0 * p;
}

// Stacked CPS (reverse = false) or reverse CPS of one output.
Plot StackedPlot(const BudgetResult& result, std::size_t o, bool reverse) {
  const OutputResult& out = result.outputs[o];
  const std::size_t n = out.contributors.size();
  const std::vector<double>& f = result.grid.f_hz();
  Plot p;
  p.name = FileStem(out.name) + (reverse ? "_reverse_cps" : "_cps");
  p.kind = reverse ? PlotKind::kReverseCps : PlotKind::kCps;
  p.output = static_cast<int>(o);
  const FrequencyRange range = DisplayRange(out, result.grid);
  p.caption = std::string(reverse ? "Reverse cumulative power spectrum (variance above f)" :
                                    "Cumulative power spectrum (variance below f)") +
              " of " + out.name + ", contributors stacked by share; left axis variance, right axis RMS." +
              RangeCaption(range);

  std::vector<std::vector<double>> series(n);
  for (std::size_t c = 0; c < n; ++c)
    series[c] = reverse ? ReverseCps(out.contributors[c].cps) : out.contributors[c].cps;
  const std::vector<double> total = reverse ? ReverseCps(out.total_cps) : out.total_cps;
  const std::string unit = DisplayUnit(out.unit);

  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.budget_name << ", output " << out.name << ": "
      << (reverse ? "variance from f to " + CsvNumber(result.grid.max_hz()) + " Hz"
                  : "variance from " + CsvNumber(result.grid.min_hz()) + " Hz to f")
      << " in (" << unit << ")^2, per contributor and total\n";
  csv << "frequency_hz";
  for (const auto& c : out.contributors) csv << ',' << CsvField(c.name);
  csv << ",total\n";
  std::vector<const std::vector<double>*> drawn = {&total};
  for (const auto& s : series) drawn.push_back(&s);
  for (std::size_t k : PlotPoints(f, drawn, range.lo_hz, range.hi_hz, PlotScale::kLinear)) {
    csv << CsvNumber(f[k]);
    for (std::size_t c = 0; c < n; ++c) csv << ',' << CsvNumber(series[c][k]);
    csv << ',' << CsvNumber(total[k]) << '\n';
  }
  p.csv = csv.str();

  const double y_max = std::max({out.variance, out.rms_max ? *out.rms_max * *out.rms_max : 0.0, 1e-300}) * 1.06;
  // Variance axis in units of 10^e where the numbers would be long.
  const int e = static_cast<int>(std::floor(std::log10(y_max)));
  const double scale = (e >= 4 || e <= -3) ? std::pow(10.0, e) : 1.0;
  const std::string per = scale == 1.0 ? "" : "/" + CsvNumber(scale);
  const std::string scale_label = scale == 1.0 ? "" : "10^{" + std::to_string(e) + "} ";
  std::ostringstream s;
  s << "reset\n" << StylePreamble() << FrequencyAxis(range, result.grid);
  s << "set title " << Quote(Enhanced(out.name) + (reverse ? ": reverse cumulative power spectrum, stacked by share"
                                                            : ": cumulative power spectrum, stacked by share"))
    << "\n";
  s << "set ylabel " << Quote(std::string(reverse ? "variance above f" : "cumulative variance") + " [" +
                              scale_label + UnitLabel(VarianceUnit(unit)) + "]")
    << "\n";
  s << "set y2label " << Quote(std::string(reverse ? "RMS above f" : "cumulative RMS") + " [" + UnitLabel(unit) + "]")
    << "\n";
  s << "set yrange [0:" << CsvNumber(y_max / scale) << "]\nset y2range [0:" << CsvNumber(y_max / scale) << "]\n";
  s << "set format y '%g'\nset ytics nomirror\n" << RmsTics(y_max, scale, {{out.rms(), Sig(out.rms())}, {out.rms_max.value_or(0.0), Short(out.rms_max.value_or(0.0))}})
    << "\n";
  s << "set key outside right top Left reverse invert title " << Quote("RMS [" + UnitLabel(unit) + "] (share)")
    << "\n";
  const std::string data = Quote(p.name + ".csv");
  const std::vector<std::size_t> order = ShareOrder(out);
  std::vector<std::string> plots, edges;
  std::string below = "0";
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t c = order[i];
    const SeriesStyle st = ContributorStyle(c);
    const std::string top = i == 0 ? Col(2 + c) : below + "+" + Col(2 + c);
    for (std::string& clause :
         FillClauses(st, data + " using 1:((" + below + ")" + per + "):((" + top + ")" + per + ")", "filledcurves",
                     "title " + Quote(Entry(out.contributors[c].name, out.contributors[c].variance, out.variance))))
      plots.push_back(std::move(clause));
    // Boundary to the next layer: white between dark layers, near-black
    // between light ones, so that neighbours stay apart in greyscale too.
    if (i + 1 < order.size()) {
      const double l = 0.5 * (st.lightness + ContributorStyle(order[i + 1]).lightness);
      edges.push_back(data + " using 1:((" + top + ")" + per + ") with lines linecolor rgb " +
                      Quote(l < 58.0 ? "#ffffff" : "#262626") + " linewidth 1.1 notitle");
    }
    below = top;
  }
  plots.insert(plots.end(), edges.begin(), edges.end());
  plots.push_back(data + " using 1:(" + Col(2 + n) + per + ") with lines linecolor rgb " + Quote(kTotalColour) +
                  " linewidth 2.5 title " + Quote("total: " + SigLabel(out.rms())));
  if (out.rms_max) {
    plots.push_back(CsvNumber(*out.rms_max * *out.rms_max / scale) + " with lines linecolor rgb " +
                    Quote(kRequirementColour) + " dashtype " + kRequirementDash + " linewidth 2 title " +
                    Quote("requirement: " + Short(*out.rms_max) + (out.pass() ? " (pass)" : " (FAIL)")));
  }
  s << "plot ";
  for (std::size_t i = 0; i < plots.size(); ++i) s << (i ? ", \\\n     " : "") << plots[i];
  s << "\n";
  p.script = s.str();
  return p;
}

Plot SpectrumPlot(const BudgetResult& result, std::size_t o, bool asd) {
  const OutputResult& out = result.outputs[o];
  const std::size_t n = out.contributors.size();
  const std::vector<double>& f = result.grid.f_hz();
  const std::string unit = DisplayUnit(out.unit);
  const std::string quantity = asd ? "ASD" : "PSD";
  const std::string unit_text = asd ? AsdUnitLabel(unit) : PsdUnitLabel(unit);
  Plot p;
  p.name = FileStem(out.name) + (asd ? "_asd" : "_psd");
  p.kind = PlotKind::kSpectrum;
  p.output = static_cast<int>(o);
  const FrequencyRange range = DisplayRange(out, result.grid);
  p.caption = (asd ? "Amplitude spectral density" : "Power spectral density (one-sided)") + std::string(" of ") +
              out.name + " per contributor and in total." + RangeCaption(range);

  const auto value = [&](double psd) { return asd ? std::sqrt(psd) : psd; };
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", budget " << result.budget_name << ", output " << out.name
      << ": one-sided " << quantity << " in " << unit_text << ", per contributor and total\n";
  csv << "frequency_hz";
  for (const auto& c : out.contributors) csv << ',' << CsvField(c.name);
  csv << ",total\n";
  double top = 0.0, bottom = HUGE_VAL;
  std::vector<const std::vector<double>*> drawn = {&out.total_psd};
  for (const auto& c : out.contributors) drawn.push_back(&c.psd);
  for (std::size_t k : PlotPoints(f, drawn, range.lo_hz, range.hi_hz)) {
    csv << CsvNumber(f[k]);
    const bool shown = f[k] >= range.lo_hz && f[k] <= range.hi_hz;
    for (std::size_t c = 0; c < n; ++c) {
      const double v = value(out.contributors[c].psd[k]);
      csv << ',' << CsvNumber(v);
      if (v > 0.0 && shown) bottom = std::min(bottom, v);
    }
    const double v = value(out.total_psd[k]);
    csv << ',' << CsvNumber(v) << '\n';
    if (shown) top = std::max(top, v);
  }
  p.csv = csv.str();

  std::ostringstream s;
  s << "reset\n" << StylePreamble() << FrequencyAxis(range, result.grid);
  s << "set title " << Quote(Enhanced(out.name) + ": " + (asd ? "amplitude" : "power") + " spectral density") << "\n";
  s << "set ylabel " << Quote(quantity + " [" + UnitLabel(unit_text) + "]") << "\n";
  s << "set logscale y 10\nset format y '10^{%L}'\n";
  // At most 10 decades (PSD) below the peak: deeper roll-offs only squeeze the figure.
  const double decades = asd ? 5.0 : 10.0;
  if (top > 0.0) {
    const double lo = std::max(bottom, top * std::pow(10.0, -decades));
    s << "set yrange [" << CsvNumber(std::pow(10.0, std::floor(std::log10(lo)))) << ":"
      << CsvNumber(std::pow(10.0, std::ceil(std::log10(top)))) << "]\n";
  } else {
    s << "set yrange [0.1:10]\nset label 1 'every contributor is zero on this output' at graph 0.5,0.5 center\n";
  }
  s << "set key outside right top Left reverse title " << Quote("RMS [" + UnitLabel(unit) + "] (share)") << "\n";
  const std::string data = Quote(p.name + ".csv");
  const auto positive = [](std::size_t col) { return "(" + Col(col) + " > 0 ? " + Col(col) + " : NaN)"; };
  s << "plot " << data << " using 1:" << positive(2 + n) << " with lines linecolor rgb " << Quote(kTotalColour)
    << " linewidth 2.5 title " << Quote("total: " + SigLabel(out.rms()));
  for (std::size_t c : ShareOrder(out)) {
    const SeriesStyle st = ContributorStyle(c);
    s << ", \\\n     " << data << " using 1:" << positive(2 + c) << " with lines linecolor rgb " << Quote(st.colour)
      << " dashtype " << st.dash << " linewidth 2 title "
      << Quote(Entry(out.contributors[c].name, out.contributors[c].variance, out.variance));
  }
  s << "\n";
  p.script = s.str();
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

std::string FrequencyAxis(const FrequencyRange& range, const FrequencyGrid& grid, const std::string& shown) {
  const double decades = std::log10(range.hi_hz / range.lo_hz);
  const bool powers = decades > 6.0 || range.lo_hz < 1e-3 || range.hi_hz > 1e5;
  std::ostringstream os;
  os << "set logscale x 10\nset format x " << (powers ? "'10^{%L}'" : "'%g'") << "\nset xrange ["
     << CsvNumber(range.lo_hz) << ":" << CsvNumber(range.hi_hz) << "]\n";
  // The note is a second, smaller line of the x label: gnuplot reserves room
  // for it, so it never meets the frame, the tic labels or the key.
  std::string label = "frequency [Hz]";
  if (range.trimmed)
    label += "\n{/*0.8 grid: " + HzLabel(grid.min_hz()) + " to " + HzLabel(grid.max_hz()) + " Hz; shown: " + shown + "}";
  os << "set xlabel " << (range.trimmed ? QuoteLines(label) : Quote(label)) << "\n";
  if (decades > 6.0) os << "set grid nomxtics\n";
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

std::string RmsTics(double variance_max, double scale, const std::vector<std::pair<double, std::string>>& marked_rms) {
  const double rms_max = std::sqrt(variance_max);
  const double step = NiceStep(rms_max / 6.0);
  const double gap = 0.04 * variance_max;  // closest two labels may sit, in variance
  const auto near_marked = [&](double r) {
    for (const auto& [m, label] : marked_rms)
      if (m > 0.0 && std::fabs(r * r - m * m) < 1.5 * gap) return true;
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
  std::ostringstream os;
  os << "set y2tics nomirror (";
  for (std::size_t i = 0; i < tics.size(); ++i)
    os << (i ? ", " : "") << Quote(tics[i].second) << " " << CsvNumber(tics[i].first * tics[i].first / scale);
  os << ")";
  return os.str();
}

std::vector<Plot> SpectrumPlots(const BudgetResult& result, std::size_t output,
                                const ReportOptions& options) {
  std::vector<Plot> plots;
  plots.push_back(StackedPlot(result, output, false));
  if (options.reverse_cps) plots.push_back(StackedPlot(result, output, true));
  plots.push_back(SpectrumPlot(result, output, options.asd));
  return plots;
}

}  // namespace deb::report
