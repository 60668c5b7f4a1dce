#include "deb/report/compare/overlay_plots.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <fstream>
#include <sstream>

#include "deb/budget/comparison.h"
#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#include "deb/core/parallel.h"
#include "deb/core/rounding_zero.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/figure_script.h"
#include "deb/report/figure/gnuplot_runner.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {

bool ShownInComparison(const OutputResult& o, std::size_t c) {
  return o.contributors[c].variance >= kNegligibleShare * o.variance;
}

namespace {

// How far A's curves are mixed with white: pale enough for B's dashes to
// read over them, dark enough to read on their own.
constexpr double kPaleShare = 0.55;

// One data block per result (gnuplot `index`): frequency, then per
// contributor and the total, PSD or CPS, at the points a reader can see in
// `range` (PlotPoints; the run's CSVs hold the whole grid).
void Block(std::ostringstream& csv, const std::string& label, const BudgetResult& r, const OutputResult& o, bool cps,
           const FrequencyRange& range) {
  csv << "# " << label << "\nfrequency_hz";
  for (const auto& c : o.contributors) csv << ',' << CsvField(c.name);
  csv << ",total\n";
  const auto& f = r.grid.f_hz();
  std::vector<const std::vector<double>*> drawn = {cps ? &o.total_cps : &o.total_psd};
  for (const auto& c : o.contributors) drawn.push_back(cps ? &c.cps : &c.psd);
  for (std::size_t k : PlotPoints(f, drawn, range.lo_hz, range.hi_hz, cps ? PlotScale::kLinear : PlotScale::kLog)) {
    csv << CsvNumber(f[k]);
    for (const auto& c : o.contributors) csv << ',' << CsvNumber(cps ? c.cps[k] : c.psd[k]);
    csv << ',' << CsvNumber(cps ? o.total_cps[k] : o.total_psd[k]) << '\n';
  }
}

// Largest and smallest positive total PSD of o within range.
void PsdExtent(const BudgetResult& r, const OutputResult& o, const FrequencyRange& range, double& top,
               double& bottom) {
  const auto& f = r.grid.f_hz();
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (f[k] < range.lo_hz || f[k] > range.hi_hz) continue;
    top = std::max(top, o.total_psd[k]);
    for (const auto& c : o.contributors)
      if (c.psd[k] > 0.0) bottom = std::min(bottom, c.psd[k]);
  }
}

Plot Overlay(const std::string& label_a, const BudgetResult& a, const OutputResult& oa, const std::string& label_b,
             const BudgetResult& b, const OutputResult& ob, bool cps) {
  // The run's display rules: the frequencies holding all but kDisplayTail of
  // every contributor's variance (of A or B), a PSD axis at most
  // kOverlayPsdDecades deep, a linear CPS axis from 0 with RMS on the right.
  const FrequencyRange ra = DisplayRange(oa, a.grid), rb = DisplayRange(ob, b.grid);
  FrequencyRange range;
  range.lo_hz = std::min(ra.lo_hz, rb.lo_hz);
  range.hi_hz = std::max(ra.hi_hz, rb.hi_hz);
  range.trimmed = range.lo_hz > std::min(a.grid.min_hz(), b.grid.min_hz()) * (1 + 1e-9) ||
                  range.hi_hz < std::max(a.grid.max_hz(), b.grid.max_hz()) * (1 - 1e-9);
  const std::string unit = DisplayUnit(oa.unit);

  Plot p;
  p.name = FileStem(oa.name) + (cps ? "_cps_overlay" : "_psd_overlay");
  p.kind = cps ? PlotKind::kCps : PlotKind::kSpectrum;
  p.caption = std::string(cps ? "Cumulative power spectrum" : "Power spectral density") + " of " + oa.name + ": A (" +
              label_a + ") wide and pale, B (" + label_b + ") dashed over it, so that both show where they "
              "coincide; total in black; contributors below " +
              "10^-6 of the variance in both are left out." + RangeCaption(range);
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", compare, output " << oa.name << ": " << (cps ? "CPS in " : "PSD in ")
      << (cps ? VarianceUnit(unit) : VarianceUnit(unit) + "/Hz") << "; block 0 " << label_a << ", block 1 "
      << label_b << "\n";
  Block(csv, label_a, a, oa, cps, range);
  csv << "\n\n";
  Block(csv, label_b, b, ob, cps, range);
  p.csv = csv.str();

  FigurePanel panel;
  panel.title = Enhanced(oa.name + (cps ? ": cumulative power spectrum" : ": power spectral density"));
  panel.x = FrequencyFigureAxis(range, a.grid);
  double scale = 1.0;  // CPS: variance in units of `scale`
  const std::optional<double> req = oa.rms_max ? oa.rms_max : ob.rms_max;
  if (cps) {
    const double y_max = std::max({oa.variance, ob.variance, req ? *req * *req : 0.0, 1e-300}) * 1.06;
    const int e = static_cast<int>(std::floor(std::log10(y_max)));
    scale = (e >= 4 || e <= -3) ? std::pow(10.0, e) : 1.0;
    const std::string scale_label = scale == 1.0 ? "" : "10^{" + std::to_string(e) + "} ";
    panel.y.label = "cumulative variance [" + scale_label + UnitLabel(VarianceUnit(unit)) + "]";
    panel.y.min = 0.0;
    panel.y.max = y_max / scale;
    panel.y.format = "%g";
    panel.y2 = panel.y;
    panel.y2.label = "cumulative RMS [" + UnitLabel(unit) + "]";
    panel.y2.format.clear();
    panel.y2.tics = RmsTicList(y_max, scale,
                               {{std::sqrt(oa.variance), Sig(std::sqrt(oa.variance))},
                                {std::sqrt(ob.variance), Sig(std::sqrt(ob.variance))},
                                {req.value_or(0.0), Short(req.value_or(0.0))}});
  } else {
    double top = 0.0, bottom = HUGE_VAL;
    PsdExtent(a, oa, range, top, bottom);
    PsdExtent(b, ob, range, top, bottom);
    panel.y.label = "PSD [" + UnitLabel(VarianceUnit(unit) + "/Hz") + "]";
    panel.y.scale = AxisScale::kLog;
    panel.y.format = "10^{%L}";
    if (top > 0.0) {
      const double lo = std::max(bottom, top * std::pow(10.0, -kOverlayPsdDecades));
      panel.y.min = std::pow(10.0, std::floor(std::log10(lo)));
      panel.y.max = std::pow(10.0, std::ceil(std::log10(top)));
    }
    panel.y2.shown = false;
  }
  // Who A and B are heads the key (labels are user text).
  panel.key.title = Enhanced("A: " + label_a) + " (wide, pale)\n" + Enhanced("B: " + label_b) + " (dashed)\nRMS [" +
                    UnitLabel(unit) + "]";
  const std::string file = p.name + ".csv";
  const std::size_t na = oa.contributors.size();
  for (int block = 0; block < 2; ++block) {
    const OutputResult& o = block == 0 ? oa : ob;
    const OutputResult& other = block == 0 ? ob : oa;
    const std::string side = block == 0 ? "A" : "B";
    const auto curve = [&](const std::string& name, std::size_t column) {
      FigureSeries s;
      s.name = side + ": " + name;
      s.data = file;
      s.block = block;
      s.y_columns = {column};
      s.y_divisor = scale;
      s.dash = block == 0 ? "solid" : "(8,5)";
      return s;
    };
    for (std::size_t c = 0; c < o.contributors.size(); ++c) {
      // Left out where negligible on both sides (a namesake on the other side counts).
      bool shown = ShownInComparison(o, c);
      for (std::size_t d = 0; d < other.contributors.size(); ++d)
        if (other.contributors[d].name == o.contributors[c].name && ShownInComparison(other, d)) shown = true;
      if (!shown) continue;
      // B's contributors take the colour of A's namesake, else one of their own.
      std::size_t style = na + c;
      for (std::size_t d = 0; d < na; ++d)
        if (oa.contributors[d].name == o.contributors[c].name) style = d;
      if (block == 0) style = c;
      FigureSeries s = curve(o.contributors[c].name, c + 2);
      // As the tables give it: 4 digits (12.07 against 12.05 is what is compared), rounding as 0.
      s.key = side + ": " + Enhanced(o.contributors[c].name) + " " +
              SigLabel(std::sqrt(WithoutRounding(o.contributors[c].variance, o.variance)), 4);
      // A wide and pale under B, dashed in full colour: where the two
      // coincide, B's dashes lie on A's band instead of vanishing in it.
      s.colour = block == 0 ? Tint(ContributorStyle(style).colour, kPaleShare) : ContributorStyle(style).colour;
      s.width = block == 0 ? 5.5 : 2.5;
      panel.series.push_back(std::move(s));
    }
    FigureSeries t = curve("total", o.contributors.size() + 2);
    t.key = side + ": total " + SigLabel(std::sqrt(o.variance), 4);
    t.colour = block == 0 ? Tint(kTotalColour, kPaleShare) : kTotalColour;
    // Each total thinner than its contributors, as in a run's PSD: a
    // contributor that is all of it (h210's sensor_noise) shows on both
    // sides instead of vanishing under it.
    t.width = block == 0 ? 2.5 : 1.0;
    panel.series.push_back(std::move(t));
  }
  if (cps && req) {
    FigureAnnotation limit;
    limit.kind = AnnotationKind::kHorizontalLine;
    limit.y0 = *req * *req / scale;
    limit.colour = kRequirementColour;
    limit.dash = kRequirementDash;
    limit.key = "requirement: " + Short(*req) + " (A " + (oa.pass() ? "pass" : "FAIL") + ", B " +
                (ob.pass() ? "pass" : "FAIL") + ")";
    panel.annotations.push_back(limit);
  }
  p.figure.panels.push_back(std::move(panel));
  p.script = EmitFigure(p.figure);
  return p;
}

}  // namespace

std::vector<Plot> OverlayPlots(const std::string& label_a, const BudgetResult& a, const std::string& label_b,
                               const BudgetResult& b) {
  std::vector<Plot> plots;
  for (const OutputResult& oa : a.outputs)
    for (const OutputResult& ob : b.outputs)
      if (oa.name == ob.name && oa.unit == ob.unit) {
        plots.push_back(Overlay(label_a, a, oa, label_b, b, ob, false));
        plots.push_back(Overlay(label_a, a, oa, label_b, b, ob, true));
      }
  return plots;
}

void WritePlotsAsPng(const std::vector<Plot>& plots, const std::string& plots_dir, int threads) {
  if (plots.empty()) return;
  const std::string gnuplot = FindGnuplot("");
  namespace fs = std::filesystem;
  for (const Plot& p : plots) {
    WriteTextFile((fs::path(plots_dir) / (p.name + ".csv")).string(), p.csv);
    WriteGnuplotScript((fs::path(plots_dir) / (p.name + ".gp")).string(), p.script);
  }
  // One gnuplot process per plot, `threads` at a time.
  ParallelForEach(
      plots.size(),
      [&](std::size_t i) {
        const Plot& p = plots[i];
        const std::string png = p.name + ".png";
        RunGnuplot(gnuplot, plots_dir, FormatDrawCommands(PlotFormat::kPng, png, p.name + ".gp"), "plot " + p.name);
        FinishPlotFile(PlotFormat::kPng, (std::filesystem::path(plots_dir) / png).string());
      },
      threads);
}

}  // namespace deb::report
