#include "deb/report/overlay_plots.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#include "deb/core/parallel.h"
#include "deb/report/gnuplot_runner.h"
#include "deb/report/plot_style.h"
#include "deb/version.h"

namespace deb::report {
namespace {

// One data block per result (gnuplot `index`): frequency, then per
// contributor and the total, PSD or CPS.
void Block(std::ostringstream& csv, const std::string& label, const BudgetResult& r, const OutputResult& o,
           bool cps) {
  csv << "# " << label << "\nfrequency_hz";
  for (const auto& c : o.contributors) csv << ',' << CsvField(c.name);
  csv << ",total\n";
  const auto& f = r.grid.f_hz();
  for (std::size_t k = 0; k < f.size(); ++k) {
    csv << CsvNumber(f[k]);
    for (const auto& c : o.contributors) csv << ',' << CsvNumber(cps ? c.cps[k] : c.psd[k]);
    csv << ',' << CsvNumber(cps ? o.total_cps[k] : o.total_psd[k]) << '\n';
  }
}

Plot Overlay(const std::string& label_a, const BudgetResult& a, const OutputResult& oa, const std::string& label_b,
             const BudgetResult& b, const OutputResult& ob, bool cps) {
  Plot p;
  p.name = FileStem(oa.name) + (cps ? "_cps_overlay" : "_psd_overlay");
  p.kind = cps ? PlotKind::kCps : PlotKind::kSpectrum;
  p.caption = std::string(cps ? "Cumulative power spectrum" : "Power spectral density") + " of " + oa.name + ": " +
              label_a + " solid, " + label_b + " dashed; total in black.";
  std::ostringstream csv;
  csv << "# deb " << DEB_VERSION << ", compare, output " << oa.name << ": " << (cps ? "CPS in " : "PSD in ")
      << (cps ? VarianceUnit(oa.unit) : VarianceUnit(oa.unit) + "/Hz") << "; block 0 " << label_a << ", block 1 "
      << label_b << "\n";
  Block(csv, label_a, a, oa, cps);
  csv << "\n\n";
  Block(csv, label_b, b, ob, cps);
  p.csv = csv.str();

  std::ostringstream s;
  s << "reset\n" << StylePreamble();
  s << "set title " << Quote(Enhanced(oa.name + ": " + label_a + " (solid) vs " + label_b + " (dashed)")) << "\n";
  s << "set logscale x 10\nset format x '10^{%L}'\nset xlabel 'frequency [Hz]'\n";
  s << "set logscale y 10\nset format y '10^{%L}'\n";
  s << "set ylabel " << Quote(cps ? "CPS [" + UnitLabel(VarianceUnit(oa.unit)) + "]"
                                  : "PSD [" + UnitLabel(VarianceUnit(oa.unit) + "/Hz") + "]")
    << "\n";
  s << "set key outside right top\n";
  std::vector<std::string> clauses;
  const std::string file = Quote(p.name + ".csv");
  const std::size_t na = oa.contributors.size();
  for (int block = 0; block < 2; ++block) {
    const OutputResult& o = block == 0 ? oa : ob;
    const std::string label = block == 0 ? label_a : label_b;
    const std::string dash = block == 0 ? "solid" : "(8,5)";
    for (std::size_t c = 0; c < o.contributors.size(); ++c) {
      // B's contributors take the colour of A's namesake, else one of their own.
      std::size_t style = na + c;
      for (std::size_t d = 0; d < na; ++d)
        if (oa.contributors[d].name == o.contributors[c].name) style = d;
      if (block == 0) style = c;
      clauses.push_back(file + " index " + std::to_string(block) + " using 1:(column(" + std::to_string(c + 2) +
                        ") > 0 ? column(" + std::to_string(c + 2) + ") : NaN) with lines linewidth 1.5 linecolor rgb " +
                        Quote(ContributorStyle(style).colour) + " dashtype " + dash + " title " +
                        Quote(Enhanced(label + ": " + o.contributors[c].name)));
    }
    const std::string total = std::to_string(o.contributors.size() + 2);
    clauses.push_back(file + " index " + std::to_string(block) + " using 1:(column(" + total + ") > 0 ? column(" +
                      total + ") : NaN) with lines linewidth 2.5 linecolor rgb " + Quote(kTotalColour) +
                      " dashtype " + dash + " title " + Quote(Enhanced(label + ": total")));
  }
  s << "plot ";
  for (std::size_t i = 0; i < clauses.size(); ++i) s << (i ? ", \\\n     " : "") << clauses[i];
  s << "\n";
  p.script = s.str();
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
        RunGnuplot(gnuplot, plots_dir,
                   TerminalCommand(Terminal::kPng) + "set output " + Quote(p.name + ".png") + "\nload " +
                       Quote(p.name + ".gp") + "\nunset output\n",
                   "plot " + p.name);
      },
      threads);
}

}  // namespace deb::report
