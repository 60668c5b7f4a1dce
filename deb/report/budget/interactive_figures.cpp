#include "deb/report/budget/interactive_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "deb/budget/failure_guidance.h"
#include "deb/budget/path_response.h"
#include "deb/budget/response_traces.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/report/budget/band_plots.h"
#include "deb/report/budget/embedded_scripts.h"
#include "deb/report/budget/path_plots.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot.h"
#include "deb/report/figure/plot_points.h"
#include "deb/report/figure/plot_style.h"

namespace deb::report {
namespace {

using nlohmann::json;

// `value` rounded to `digits` significant digits, so that the JSON holds
// the short text ("1.234e-18"), not 17 digits.
double Rounded(double value, int digits) {
  if (!std::isfinite(value) || value == 0.0) return value;
  // value to `digits` significant digits, as the nearest double: an integer
  // times or over an exact power of ten (10^0..10^22) is correctly rounded,
  // as strtod of the printed digits would be, without the text.
  constexpr double kExact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const int shift = digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(value))));
  if (shift >= 0 && shift <= 22) return std::round(value * kExact[shift]) / kExact[shift];
  if (shift < 0 && -shift <= 22) return std::round(value / kExact[-shift]) * kExact[-shift];
  char text[32];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  return std::strtod(text, nullptr);
}

// Values at the kept points; a log axis cannot show v <= 0: null there.
json Series(const std::vector<double>& v, const std::vector<std::size_t>& keep, bool log_axis) {
  json out = json::array();
  for (std::size_t i : keep) {
    if (log_axis && !(v[i] > 0.0))
      out.push_back(nullptr);
    else
      out.push_back(Rounded(v[i], 4));
  }
  return out;
}

json Frequencies(const std::vector<double>& f, const std::vector<std::size_t>& keep) {
  json out = json::array();
  for (std::size_t i : keep) out.push_back(Rounded(f[i], 7));
  return out;
}

json OutputData(const BudgetResult& result, const OutputResult& out) {
  const std::vector<double>& f = result.grid.f_hz();
  // The CPS and PSD stack what the PNG and PDF figures stack: the top-level
  // groups (each the sum of its members) and the contributors outside any
  // group, or the contributors of a budget without groups.
  const PlotLevel level = GroupLevel(out, result.grid, "");
  const OutputResult& items = level.out;
  std::vector<const std::vector<double>*> psd = {&out.total_psd}, cps = {&out.total_cps};
  for (const ContributorResult& c : items.contributors) {
    psd.push_back(&c.psd);
    cps.push_back(&c.cps);
  }
  const std::vector<std::size_t> keep = FigurePoints(f, psd, cps);
  const FrequencyRange shown = DisplayRange(out, result.grid);
  const double limit2 = out.rms_max ? *out.rms_max * *out.rms_max : 0.0;
  const std::optional<double> crossing =
      out.rms_max ? CpsCrossingHz(f, out.total_psd, out.total_cps, limit2) : std::nullopt;
  json o = {{"name", out.name},
            {"unit", UnitText(out.unit)},
            {"variance_unit", Squared(UnitText(VarianceUnit(out.unit)))},
            {"rms", out.rms()},
            {"rms_max", out.rms_max ? json(*out.rms_max) : json(nullptr)},
            {"crossing_hz", crossing ? json(*crossing) : json(nullptr)},  // where the CPS reaches rms_max^2
            {"pass", out.AllPass()},
            {"display_hz", {shown.lo_hz, shown.hi_hz}},
            {"f", Frequencies(f, keep)},
            {"total_psd", Series(out.total_psd, keep, true)},
            {"total_cps", Series(out.total_cps, keep, false)}};
  // Largest first: the bottom of the stack, the head of the legend (as the tables).
  json names = json::array(), colours = json::array(), psds = json::array(), cpss = json::array();
  for (std::size_t k : ShareOrder(items)) {
    const ContributorResult& c = items.contributors[k];
    names.push_back(c.name);
    colours.push_back(level.styles[k].colour);
    psds.push_back(Series(c.psd, keep, true));
    cpss.push_back(Series(c.cps, keep, false));
  }
  o["contributors"] = names;  // the items stacked: groups ("name/") and contributors
  o["colours"] = colours;
  o["psd"] = psds;
  o["cps"] = cpss;
  // The band chart, as its PNG: the same bars (BandBars).
  const std::vector<BandBar> bars = BandBars(out, result.grid);
  json band_names = json::array(), band_colours = json::array();
  for (const BandBar& bar : bars) {
    band_names.push_back(bar.name);
    band_colours.push_back(bar.style.colour);
  }
  o["band_contributors"] = band_names;
  o["band_colours"] = band_colours;
  json bands = json::array(), band_variance = json::array();
  for (const BandResult& b : out.bands) {
    bands.push_back(Short(b.band.lo_hz) + "–" + Short(b.band.hi_hz));
    json per = json::array();
    for (const BandBar& bar : bars) per.push_back(Rounded(bar.Of(b.contributor_variance), 4));
    band_variance.push_back(per);
  }
  o["bands"] = bands;
  o["band_variance"] = band_variance;  // [band][contributor]
  // Measured references: drawn on the CPS (from the lowest frequency each covers), never stacked.
  json references = json::array();
  for (const ReferenceResult& r : out.references) {
    json cps = json::array();
    for (std::size_t i : keep)
      cps.push_back(f[i] >= r.covered_lo_hz && f[i] <= r.covered_hi_hz ? json(Rounded(r.cps[i], 4)) : json(nullptr));
    references.push_back({{"name", r.name}, {"rms", Rounded(std::sqrt(r.variance), 4)}, {"cps", cps}});
  }
  o["references"] = references;
  return o;
}

json PathData(const BudgetResult& result, std::size_t c, std::size_t o, const PathResponse& r) {
  const std::vector<double>& f = r.Frequencies(result.grid.f_hz());
  std::vector<std::vector<double>> magnitude;
  for (const auto& g2 : r.gain2) {
    magnitude.emplace_back(g2.size());
    std::transform(g2.begin(), g2.end(), magnitude.back().begin(), [](double g) { return std::sqrt(g); });
  }
  std::vector<const std::vector<double>*> series;
  for (const auto& m : magnitude) series.push_back(&m);
  const std::vector<std::size_t> keep = FigurePoints(f, series, {});
  // Shown first as in the report's path plots (PathRange).
  const FrequencyRange shown =
      PathRange(result.traces->poles_hz[c], DisplayRange(result.outputs[o], result.grid), result.grid);
  json p = {{"contributor", r.contributor}, {"output", r.output}, {"unit", UnitText(r.unit)},
            {"display_hz", {shown.lo_hz, shown.hi_hz}}, {"f", Frequencies(f, keep)}};
  json channels = json::array(), colours = json::array(), mags = json::array();
  for (std::size_t k = 0; k < magnitude.size(); ++k) {
    channels.push_back(k < r.channels.size() ? r.channels[k] : std::to_string(k + 1));
    colours.push_back(magnitude.size() == 1 ? ContributorStyle(c).colour : ChannelStyle(k).colour);
    mags.push_back(Series(magnitude[k], keep, true));
  }
  p["channels"] = channels;
  p["colours"] = colours;
  p["magnitude"] = mags;
  return p;
}

constexpr const char* kCss = R"(
.verdict { margin: 1rem 0; color: #fff; }
.verdict p { margin: 0.15rem 0; padding: 0.35rem 1rem; border-radius: 4px; }
.verdict p.pass { background: #1b7837; }
.verdict p.fail { background: var(--fail); }
.verdict p.none { background: #4d4d4d; }
figure.chart .plot { position: relative; }
.rms-axis { position: absolute; font-size: 11px; color: #333; white-space: nowrap; pointer-events: none; }
.rms-axis.title { transform: translate(-50%, -50%) rotate(90deg); }
td.fail { background: #fbe3e6; }
figure.chart { border: 1px solid var(--line); padding: 0.6rem; }
figure.chart .plot { width: 100%; height: 380px; }
figure.chart .legend { font-size: 0.85rem; min-height: 3.2em; margin: 0.4rem 0; font-variant-numeric: tabular-nums; }
figure.chart .toggles { font-size: 0.85rem; }
figure.chart .toggles label { margin-right: 0.9rem; white-space: nowrap; cursor: pointer; }
figure.chart .swatch { display: inline-block; width: 0.8em; height: 0.8em; margin-right: 0.25em; vertical-align: -0.05em; }
p.noscript { border: 1px solid var(--fail); padding: 0.5rem 1rem; }
)";


// dygraphs' licence, in full in every page that carries it (the library's
// own comment only names it); holders as Debian's libjs-dygraphs lists them,
// with the browserify loader bundled into dygraph.min.js.
constexpr const char* kDygraphsLicence = R"(/*
dygraphs 2.2.1 (Debian libjs-dygraphs), with its synchronizer extension.
Copyright (c) 2006, 2009, 2011, 2012, 2013, 2017 Dan Vanderkam <danvdk@gmail.com>
Copyright (c) 2011 Paul Felix, 2011, 2013 Robert Konigsberg, 2013 David Eberlein,
2013 Google, Inc., 2014, 2022, 2023 mirabilos, 2015 Petr Shevtsov, and contributors.
Browser-pack loader: Copyright (c) 2013, 2014 James Halliday, 2013 Roman Shtylman,
2013 Esa-Matti Suuronen, 2018 Philipp Simon Schmidt.

Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies of
the Software, and to permit persons to whom the Software is furnished to do so,
subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, FITNESS
FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE AUTHORS OR
COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN
AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION
WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
*/
)";

// JSON inside <script> must not end the element ("</script>") or open a
// comment ("<!--"): '<' only occurs within JSON strings, where \u003c means the same.
std::string ScriptSafe(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (char c : json_text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::vector<std::size_t> FigurePoints(const std::vector<double>& f_hz,
                                      const std::vector<const std::vector<double>*>& log_series,
                                      const std::vector<const std::vector<double>*>& linear_series,
                                      std::size_t max_points) {
  if (f_hz.empty()) return {};
  // The drawn coordinates of the whole grid (PlotPoints' own), taken once:
  // every thinning below works on a subset of them.
  std::vector<double> x_all(f_hz.size());
  for (std::size_t k = 0; k < f_hz.size(); ++k) x_all[k] = std::log10(f_hz[k]);
  std::vector<std::vector<double>> log_y;
  for (const auto* s : log_series) log_y.push_back(LogCoordinates(*s));
  const auto gather = [](const std::vector<double>& v, const std::vector<std::size_t>& keep) {
    std::vector<double> out(keep.size());
    for (std::size_t k = 0; k < keep.size(); ++k) out[k] = v[keep[k]];
    return out;
  };
  // `keep` (indices into f_hz) thinned at `tolerance`: PlotPoints' rule over
  // the points kept so far, for log and linear series, united. A linear
  // series is scaled by the largest |value| among the points kept, as
  // PlotPoints scales by the largest it is given.
  const auto thin = [&](const std::vector<std::size_t>& keep, double tolerance) {
    const std::vector<double> x = gather(x_all, keep);
    std::vector<std::size_t> a, b;
    if (!log_y.empty()) {
      std::vector<std::vector<double>> ys;
      for (const auto& y : log_y) ys.push_back(gather(y, keep));
      a = DrawnPoints(x, ys, tolerance);
    }
    if (!linear_series.empty()) {
      std::vector<std::vector<double>> ys;
      double largest = 0.0;
      for (const auto* s : linear_series) {
        ys.push_back(gather(*s, keep));
        for (double v : ys.back()) largest = std::max(largest, std::abs(v));
      }
      const double scale = largest > 0.0 ? largest : 1.0;
      for (auto& y : ys)
        for (double& v : y) v /= scale;
      b = DrawnPoints(x, ys, tolerance);
    }
    std::vector<std::size_t> both, out;
    std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
    for (std::size_t k : both) out.push_back(keep[k]);
    return out;
  };
  std::vector<std::size_t> keep(f_hz.size());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = i;
  keep = thin(keep, 2e-3);
  // Each doubling thins what the last kept: the points a doubled tolerance
  // drops lie within it of the chords through the points it keeps, so the
  // deviation from the whole grid stays below twice the final tolerance.
  // PlotPoints keeps one point per 0.05 decade at any tolerance: stop at a
  // whole decade.
  for (double tolerance = 4e-3; keep.size() > max_points && tolerance <= 1.0; tolerance *= 2.0)
    keep = thin(keep, tolerance);
  return keep;
}

std::string FigureDataJson(const BudgetResult& result, int threads) {
  // Thinning a dense grid takes tens of ms per figure: one job per output
  // and per contributor's paths.
  std::vector<json> outputs(result.outputs.size());
  ParallelForEach(outputs.size(), [&](std::size_t o) { outputs[o] = OutputData(result, result.outputs[o]); },
                  threads);
  DEB_DEMAND(result.traces && result.traces->paths.size() == result.outline.contributors.size());
  std::vector<json> paths(result.outline.contributors.size(), json::array());
  ParallelForEach(paths.size(), [&](std::size_t c) {
    const std::vector<PathResponse>& responses = result.traces->paths[c];
    for (std::size_t o = 0; o < responses.size(); ++o) paths[c].push_back(PathData(result, c, o, responses[o]));
  }, threads);
  json data = {{"outputs", outputs}, {"paths", json::array()}};
  for (json& per_contributor : paths)
    for (json& p : per_contributor) data["paths"].push_back(std::move(p));
  return ScriptSafe(data.dump());
}

std::string FigureElement(const std::string& kind, std::size_t index, const std::string& caption_html) {
  return "<figure class=\"chart\" data-kind=\"" + HtmlEscape(kind) + "\" data-index=\"" + std::to_string(index) +
         "\">\n<div class=\"plot\"></div>\n<div class=\"legend\"></div>\n<div class=\"toggles\"></div>\n<figcaption>" +
         caption_html + "</figcaption>\n</figure>\n";
}

std::string FigureScripts(const std::string& data_json) {
  DEB_DEMAND(std::string(DygraphsJs()).find("</script") == std::string::npos);
  DEB_DEMAND(std::string(IndexFiguresJs()).find("</script") == std::string::npos);
  return std::string("<script>\n") + kDygraphsLicence + DygraphsJs() + "\n</script>\n<script type=\"application/json\" id=\"deb-figure-data\">" +
         data_json + "</script>\n<script>\n" + IndexFiguresJs() + "</script>\n";
}

std::string FigureCss() { return std::string(DygraphsCss()) + kCss; }

}  // namespace deb::report
