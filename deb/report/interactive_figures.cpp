#include "deb/report/interactive_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "deb/budget/path_response.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/report/dygraphs_source.h"
#include "deb/report/path_plots.h"
#include "deb/report/plot.h"
#include "deb/report/plot_points.h"
#include "deb/report/plot_style.h"
#include "deb/report/report_tables.h"
#include "deb/report/spectrum_plots.h"

namespace deb::report {
namespace {

using nlohmann::json;

// `value` rounded to `digits` significant digits, so that the JSON holds
// the short text ("1.234e-18"), not 17 digits.
double Rounded(double value, int digits) {
  if (!std::isfinite(value) || value == 0.0) return value;
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

// "nm^2" -> "nm²": the page can show the superscript.
std::string Squared(std::string unit) {
  for (std::size_t at = unit.find("^2"); at != std::string::npos; at = unit.find("^2", at)) unit.replace(at, 2, "²");
  return unit;
}

json Frequencies(const std::vector<double>& f, const std::vector<std::size_t>& keep) {
  json out = json::array();
  for (std::size_t i : keep) out.push_back(Rounded(f[i], 7));
  return out;
}

std::size_t BudgetIndex(const Budget& budget, const std::string& contributor) {
  for (std::size_t c = 0; c < budget.contributors.size(); ++c)
    if (budget.contributors[c].name == contributor) return c;
  return 0;
}

json OutputData(const Budget& budget, const BudgetResult& result, const OutputResult& out) {
  const std::vector<double>& f = result.grid.f_hz();
  std::vector<const std::vector<double>*> psd = {&out.total_psd}, cps = {&out.total_cps};
  for (const ContributorResult& c : out.contributors) {
    psd.push_back(&c.psd);
    cps.push_back(&c.cps);
  }
  const std::vector<std::size_t> keep = FigurePoints(f, psd, cps);
  const FrequencyRange shown = DisplayRange(out, result.grid);
  json o = {{"name", out.name},
            {"unit", UnitText(out.unit)},
            {"variance_unit", Squared(UnitText(VarianceUnit(out.unit)))},
            {"rms", out.rms()},
            {"rms_max", out.rms_max ? json(*out.rms_max) : json(nullptr)},
            {"pass", out.AllPass()},
            {"display_hz", {shown.lo_hz, shown.hi_hz}},
            {"f", Frequencies(f, keep)},
            {"total_psd", Series(out.total_psd, keep, true)},
            {"total_cps", Series(out.total_cps, keep, false)}};
  // Largest first: the bottom of the stack, the head of the legend (as the tables).
  std::vector<std::size_t> order(out.contributors.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return out.contributors[a].variance > out.contributors[b].variance;
  });
  json names = json::array(), colours = json::array(), psds = json::array(), cpss = json::array();
  for (std::size_t k : order) {
    const ContributorResult& c = out.contributors[k];
    names.push_back(c.name);
    colours.push_back(ContributorStyle(BudgetIndex(budget, c.name)).colour);
    psds.push_back(Series(c.psd, keep, true));
    cpss.push_back(Series(c.cps, keep, false));
  }
  o["contributors"] = names;
  o["colours"] = colours;
  o["psd"] = psds;
  o["cps"] = cpss;
  json bands = json::array(), band_variance = json::array();
  for (const BandResult& b : out.bands) {
    bands.push_back(Short(b.band.lo_hz) + "–" + Short(b.band.hi_hz));
    json per = json::array();
    for (std::size_t k : order) per.push_back(Rounded(b.contributor_variance[k], 4));
    band_variance.push_back(per);
  }
  o["bands"] = bands;
  o["band_variance"] = band_variance;  // [band][contributor]
  return o;
}

json PathData(const Budget& budget, const BudgetResult& result, std::size_t c, std::size_t o, const PathResponse& r) {
  const std::vector<double>& f = result.grid.f_hz();
  std::vector<std::vector<double>> magnitude;
  for (const auto& g2 : r.gain2) {
    magnitude.emplace_back(g2.size());
    std::transform(g2.begin(), g2.end(), magnitude.back().begin(), [](double g) { return std::sqrt(g); });
  }
  std::vector<const std::vector<double>*> series;
  for (const auto& m : magnitude) series.push_back(&m);
  const std::vector<std::size_t> keep = FigurePoints(f, series, {});
  // Shown first as in the report's path plots (PathRange).
  const FrequencyRange shown = PathRange(*result.paths.at(budget.contributors[c].path),
                                         DisplayRange(result.outputs[o], result.grid), result.grid);
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
.verdict { border-radius: 4px; padding: 0.6rem 1rem; margin: 1rem 0; color: #fff; }
.verdict.pass { background: #1b7837; }
.verdict.fail { background: var(--fail); }
.verdict.none { background: #4d4d4d; }
.verdict p { margin: 0.2rem 0; }
td.fail { background: #fbe3e6; }
figure.chart { border: 1px solid var(--line); padding: 0.6rem; }
figure.chart .plot { width: 100%; height: 380px; }
figure.chart .legend { font-size: 0.85rem; min-height: 3.2em; margin: 0.4rem 0; font-variant-numeric: tabular-nums; }
figure.chart .toggles { font-size: 0.85rem; }
figure.chart .toggles label { margin-right: 0.9rem; white-space: nowrap; cursor: pointer; }
figure.chart .swatch { display: inline-block; width: 0.8em; height: 0.8em; margin-right: 0.25em; vertical-align: -0.05em; }
p.noscript { border: 1px solid var(--fail); padding: 0.5rem 1rem; }
)";

// Draws every figure.chart from the data; user text reaches the page only
// through textContent or esc().
constexpr const char* kScript = R"deb_js(
(function () {
  'use strict';
  var data = JSON.parse(document.getElementById('deb-figure-data').textContent);
  function esc(s) {
    return String(s).replace(/[&<>"']/g, function (c) {
      return { '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c];
    });
  }
  function num(v) { return v === null || v === undefined || isNaN(v) ? '–' : Number(v).toPrecision(4); }
  function hz(v) { return Number(v).toPrecision(4) + ' Hz'; }
  function rows(f, series) {
    return f.map(function (x, i) { return [x].concat(series.map(function (s) { return s[i]; })); });
  }
  // Legend on hover: the frequency, each visible series' value (raw[k][row],
  // not the stacked height) and the total.
  function legendFormatter(fig) {
    return function (d) {
      if (d.x === null || d.x === undefined)
        return '<span class="hint">Hover for values; drag to zoom the frequency axis, double-click to show the whole grid.</span>';
      var row = d.dygraph.getSelection();
      var html = '<b>' + esc(fig.xText(d.x)) + '</b>';
      d.series.forEach(function (s, k) {
        if (!s.isVisible) return;
        html += ' &nbsp; <span class="swatch" style="background:' + esc(s.color) + '"></span>' + esc(fig.names[k]) +
                ': ' + esc(fig.valueText(fig.raw[k][row]));
      });
      if (fig.total) html += ' &nbsp; <b>total: ' + esc(fig.valueText(fig.total[row])) + '</b>';
      return html;
    };
  }
  function toggles(el, g, names, colours) {
    names.forEach(function (name, k) {
      var label = document.createElement('label');
      var box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = true;
      box.addEventListener('change', function () { g.setVisibility(k, box.checked); });
      var swatch = document.createElement('span');
      swatch.className = 'swatch';
      swatch.style.background = colours[k];
      label.appendChild(box);
      label.appendChild(swatch);
      label.appendChild(document.createTextNode(name));
      el.appendChild(label);
    });
  }
  // Log axes: a label per decade (every k-th decade when they would crowd:
  // one per 40 px), grid lines at 2..9 over at most 8 decades; within about a
  // decade dygraphs' own ticks.
  function decadeLabel(n) { return n >= -3 && n <= 4 ? String(Number(Math.pow(10, n).toPrecision(1))) : '10<sup>' + n + '</sup>'; }
  function logTicker(min, max, pixels, opts, g, vals) {
    if (!(min > 0) || Math.log10(max / min) < 1.3) return Dygraph.numericTicks(min, max, pixels, opts, g, vals);
    var lo = Math.floor(Math.log10(min)), hi = Math.ceil(Math.log10(max));
    var step = Math.max(1, Math.ceil((hi - lo) / Math.max(2, pixels / 40)));
    var ticks = [];
    for (var n = lo; n <= hi; n++) {
      ticks.push({ v: Math.pow(10, n), label: n % step === 0 ? decadeLabel(n) : '' });
      if (step === 1 && hi - lo <= 8) for (var m = 2; m <= 9; m++) ticks.push({ v: m * Math.pow(10, n) });
    }
    return ticks;
  }
  // The y axis's lowest label would sit on the x axis's first one.
  function yLogTicker(min, max, pixels, opts, g, vals) {
    return logTicker(min, max, pixels, opts, g, vals).map(function (t) {
      return t.v <= min * 1.05 ? { v: t.v, label: '' } : t;
    });
  }
  function draw(fig, el, extra) {
    var opts = {
      labels: ['f'].concat(fig.names.map(function (n, k) { return 's' + k; })),
      colors: fig.colours, xlabel: esc(fig.xlabel || 'frequency [Hz]'), ylabel: esc(fig.ylabel),
      labelsDiv: el.querySelector('.legend'), legend: 'always', legendFormatter: legendFormatter(fig),
      axes: { x: fig.logX === false ? {} : { logscale: true, ticker: logTicker },
              y: fig.logY ? { logscale: true, ticker: yLogTicker, axisLabelWidth: 60 } : { axisLabelWidth: 60 } },
      strokeWidth: 1.4, animatedZooms: false, connectSeparatedPoints: false
    };
    Object.keys(extra || {}).forEach(function (k) { opts[k] = extra[k]; });
    var g = new Dygraph(el.querySelector('.plot'), fig.rows, opts);
    toggles(el.querySelector('.toggles'), g, fig.names, fig.colours);
    return g;
  }
  function requirementLine(variance) {
    return function (ctx, area, g) {
      if (variance === null) return;
      var y = g.toDomYCoord(variance);
      ctx.save();
      ctx.strokeStyle = '#b2182b';
      ctx.lineWidth = 2;
      ctx.setLineDash([8, 4]);
      ctx.beginPath();
      ctx.moveTo(area.x, y);
      ctx.lineTo(area.x + area.w, y);
      ctx.stroke();
      ctx.restore();
    };
  }
  function barPlotter(e) {
    var ctx = e.drawingContext, g = e.dygraph, pts = e.points;
    var w = 0.6 * (g.toDomXCoord(1) - g.toDomXCoord(0));
    ctx.fillStyle = e.color;
    pts.forEach(function (p) {
      if (p.yval === null || isNaN(p.canvasy)) return;
      var bottom = g.toDomYCoord(p.yval_stacked - p.yval);
      ctx.fillRect(p.canvasx - w / 2, p.canvasy, w, bottom - p.canvasy);
    });
  }
  var graphs = {};
  document.querySelectorAll('figure.chart').forEach(function (el) {
    var kind = el.getAttribute('data-kind'), i = Number(el.getAttribute('data-index'));
    if (kind === 'path') {
      var p = data.paths[i];
      // As the report's plots: 8 decades below the peak, not the depth of every notch.
      var peak = Math.max.apply(null, p.magnitude.map(function (m) { return Math.max.apply(null, m); }));
      var extra = peak > 0 ? { valueRange: [Math.pow(10, Math.floor(Math.log10(peak)) - 8), Math.pow(10, Math.ceil(Math.log10(peak * 1.2)))] } : {};
      draw({ names: p.channels, colours: p.colours, raw: p.magnitude, rows: rows(p.f, p.magnitude), logY: true,
             ylabel: '|h| [' + p.unit + ']', xText: hz, valueText: function (v) { return num(v) + ' ' + p.unit; } },
           el, Object.assign({ dateWindow: p.display_hz }, extra));
      return;
    }
    var o = data.outputs[i];
    var varianceText = function (v) {
      return v === null || v === undefined ? '–' : num(v) + ' ' + o.variance_unit + ' (RMS ' + num(Math.sqrt(Math.max(v, 0))) + ' ' + o.unit + ')';
    };
    var window_hz = [o.display_hz[0], o.display_hz[1]];
    if (kind === 'cps') {
      var req = o.rms_max === null ? null : o.rms_max * o.rms_max;
      var top = Math.max(o.total_cps[o.total_cps.length - 1] || 0, req || 0) * 1.06 || 1;
      // Forward CPS, or by the box the reverse CPS: the variance from f to the top of the grid.
      var above = function (s) { var end = s[s.length - 1]; return s.map(function (v) { return end - v; }); };
      var forward = { raw: o.cps, total: o.total_cps, ylabel: 'CPS [' + o.variance_unit + ']' };
      var reverse = { raw: o.cps.map(above), total: above(o.total_cps), ylabel: 'reverse CPS [' + o.variance_unit + ']' };
      var cpsFig = { names: o.contributors, colours: o.colours, raw: forward.raw, total: forward.total,
                     rows: rows(o.f, forward.raw), ylabel: forward.ylabel, xText: hz, valueText: varianceText };
      var gc = draw(cpsFig, el, { stackedGraph: true, fillGraph: true, fillAlpha: 0.7, valueRange: [0, top],
                                  dateWindow: window_hz, underlayCallback: requirementLine(req) });
      graphs['cps' + i] = gc;
      var rlabel = document.createElement('label'), rbox = document.createElement('input');
      rbox.type = 'checkbox';
      rbox.className = 'reverse';
      rbox.addEventListener('change', function () {
        var v = rbox.checked ? reverse : forward;
        cpsFig.raw = v.raw;
        cpsFig.total = v.total;
        gc.updateOptions({ file: rows(o.f, v.raw), ylabel: esc(v.ylabel) });
      });
      rlabel.appendChild(rbox);
      rlabel.appendChild(document.createTextNode('reverse (variance above f)'));
      rlabel.style.marginLeft = '1.5rem';
      el.querySelector('.toggles').appendChild(rlabel);
    } else if (kind === 'psd' || kind === 'asd') {
      // PSD, or ASD = sqrt(PSD) by the box under the figure.
      var psd = o.psd.concat([o.total_psd]);
      var asd = psd.map(function (s) { return s.map(function (v) { return v === null ? null : Math.sqrt(v); }); });
      var units = { psd: o.variance_unit + '/Hz', asd: (/[/ ]/.test(o.unit) ? '(' + o.unit + ')' : o.unit) + '/√Hz' };
      var fig = { names: o.contributors.concat(['total']), colours: o.colours.concat(['#000000']), raw: psd,
                  rows: rows(o.f, psd), logY: true, ylabel: 'PSD [' + units.psd + ']', xText: hz,
                  valueText: function (v) { return num(v) + ' ' + units[fig.raw === psd ? 'psd' : 'asd']; } };
      var g = draw(fig, el, { dateWindow: window_hz });
      graphs['psd' + i] = g;
      var label = document.createElement('label'), box = document.createElement('input');
      box.type = 'checkbox';
      box.className = 'asd';
      box.addEventListener('change', function () {
        fig.raw = box.checked ? asd : psd;
        g.updateOptions({ file: rows(o.f, fig.raw),
                          ylabel: esc(box.checked ? 'ASD [' + units.asd + ']' : 'PSD [' + units.psd + ']') });
      });
      label.appendChild(box);
      label.appendChild(document.createTextNode('amplitude (ASD = √PSD)'));
      label.style.marginLeft = '1.5rem';
      el.querySelector('.toggles').appendChild(label);
      if (kind === 'asd') box.click();  // the report was asked for amplitudes (--asd)
    } else if (kind === 'bands') {
      var names = o.contributors, raw = names.map(function (n, k) {
        return o.band_variance.map(function (b) { return b[k]; });
      });
      var totals = o.band_variance.map(function (b) { return b.reduce(function (a, v) { return a + v; }, 0); });
      var bandRows = o.bands.map(function (b, j) { return [j].concat(raw.map(function (r) { return r[j]; })); });
      var bandText = function (x) { return o.bands[Math.round(x)] ? o.bands[Math.round(x)] + ' Hz' : ''; };
      draw({ names: names, colours: o.colours, raw: raw, total: totals, rows: bandRows, logX: false,
             xlabel: 'frequency band [Hz]', ylabel: 'variance [' + o.variance_unit + ']', xText: bandText,
             valueText: varianceText },
           el, { stackedGraph: true, plotter: barPlotter, dateWindow: [-0.5, o.bands.length - 0.5],
                 axes: { x: { logscale: false, axisLabelWidth: 110, ticker: function () {
                   return o.bands.map(function (b, j) { return { v: j, label: esc(b) }; });
                 } }, y: { axisLabelWidth: 60 } } });
    }
  });
  // An output's CPS and PSD zoom together and show the same frequency on hover.
  data.outputs.forEach(function (o, i) {
    if (graphs['cps' + i] && graphs['psd' + i])
      Dygraph.synchronize([graphs['cps' + i], graphs['psd' + i]], { zoom: true, selection: true, range: false });
  });
  document.documentElement.setAttribute('data-figures', 'drawn');
})();
)deb_js";

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
  // `keep` (indices into f_hz) thinned at `tolerance`: PlotPoints over the
  // points kept so far, for log and linear series, united.
  const auto thin = [&](const std::vector<std::size_t>& keep, double tolerance) {
    std::vector<double> f(keep.size());
    for (std::size_t k = 0; k < keep.size(); ++k) f[k] = f_hz[keep[k]];
    const auto pass = [&](const std::vector<const std::vector<double>*>& series, PlotScale scale) {
      std::vector<std::vector<double>> values(series.size(), std::vector<double>(keep.size()));
      std::vector<const std::vector<double>*> view;
      for (std::size_t c = 0; c < series.size(); ++c) {
        for (std::size_t k = 0; k < keep.size(); ++k) values[c][k] = (*series[c])[keep[k]];
        view.push_back(&values[c]);
      }
      return series.empty() ? std::vector<std::size_t>{} : PlotPoints(f, view, f.front(), f.back(), scale, tolerance);
    };
    const std::vector<std::size_t> a = pass(log_series, PlotScale::kLog), b = pass(linear_series, PlotScale::kLinear);
    std::vector<std::size_t> both, out;
    std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
    for (std::size_t k : both) out.push_back(keep[k]);
    return out;
  };
  std::vector<std::size_t> keep(f_hz.size());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = i;
  if (keep.empty()) return keep;
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

std::string FigureDataJson(const Budget& budget, const BudgetResult& result, int threads) {
  // Thinning a dense grid takes tens of ms per figure: one job per output
  // and per contributor's paths.
  std::vector<json> outputs(result.outputs.size());
  ParallelForEach(outputs.size(), [&](std::size_t o) { outputs[o] = OutputData(budget, result, result.outputs[o]); },
                  threads);
  std::vector<json> paths(budget.contributors.size(), json::array());
  ParallelForEach(paths.size(), [&](std::size_t c) {
    const std::vector<PathResponse> responses = ComputePathResponses(budget, result, c, result.grid.f_hz(), 1);
    for (std::size_t o = 0; o < responses.size(); ++o) paths[c].push_back(PathData(budget, result, c, o, responses[o]));
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
  return std::string("<script>\n") + kDygraphsLicence + DygraphsJs() + "\n</script>\n<script type=\"application/json\" id=\"deb-figure-data\">" +
         data_json + "</script>\n<script>" + kScript + "</script>\n";
}

std::string FigureCss() { return std::string(DygraphsCss()) + kCss; }

}  // namespace deb::report
