// index.html's figures (deb/report/budget/interactive_figures.h): draws every
// figure.chart of the page with dygraphs from the JSON in #deb-figure-data.
// User text reaches the page only through textContent or esc(). Built into
// deb (deb/CMakeLists.txt), not loaded from a file at view time.
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
  // The cumulative RMS on the right of a CPS, as its PNG: a label at the
  // variance r^2 of each round RMS value r. HTML over the chart (the canvas
  // callbacks draw inside the plot area only), placed again after each draw.
  function rmsAxis(o) {
    return function (g) {
      var div = g.graphDiv, area = g.getArea(), hi = g.yAxisRange()[1];
      Array.prototype.slice.call(div.querySelectorAll('.rms-axis')).forEach(function (e) { e.remove(); });
      if (!(hi > 0)) return;
      var top = Math.sqrt(hi), p = Math.pow(10, Math.floor(Math.log10(top / 6))), step = 10 * p;
      [1, 2, 2.5, 5].some(function (m) { if (m * p >= top / 6) { step = m * p; return true; } return false; });
      var label = function (text, x, y, cls) {
        var e = document.createElement('div');
        e.className = 'rms-axis' + (cls ? ' ' + cls : '');
        e.textContent = text;
        e.style.left = x + 'px';
        e.style.top = y + 'px';
        div.appendChild(e);
      };
      for (var k = 1; k * step * k * step <= hi * (1 + 1e-9); k++)
        label('– ' + String(Number((k * step).toPrecision(4))), area.x + area.w, g.toDomYCoord(k * step * k * step) - 7);
      label('RMS [' + o.unit + ']', area.x + area.w + 44, area.y + area.h / 2, 'title');
    };
  }
  // Where the cumulative RMS reaches the requirement (forward CPS only), as
  // the PNG marks it: a dashed vertical line, a dot on the limit and its
  // label left of the dot, above the limit, where the stack is still below it.
  function crossingMarker(o, shown) {
    return function (ctx, area, g) {
      if (o.crossing_hz === null || o.rms_max === null || !shown()) return;
      var x = area.x + g.toPercentXCoord(o.crossing_hz) * area.w, y = g.toDomYCoord(o.rms_max * o.rms_max);
      if (!(x >= area.x && x <= area.x + area.w)) return;
      ctx.save();
      ctx.strokeStyle = '#b2182b';
      ctx.fillStyle = '#b2182b';
      ctx.lineWidth = 1.5;
      ctx.setLineDash([4, 4]);
      ctx.beginPath();
      ctx.moveTo(x, area.y);
      ctx.lineTo(x, area.y + area.h);
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.beginPath();
      ctx.arc(x, y, 4, 0, 2 * Math.PI);
      ctx.fill();
      ctx.font = '12px sans-serif';
      ctx.textBaseline = 'bottom';
      var label = 'RMS reaches ' + num(o.rms_max) + ' ' + o.unit + ' at ' + num(o.crossing_hz) + ' Hz';
      var w = ctx.measureText(label).width;
      ctx.fillText(label, x - 8 - w >= area.x ? x - 8 - w : x + 8, Math.max(area.y + 14, y - 6));
      ctx.restore();
    };
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
  // Measured references over the stack: grey dashed, never summed (null where one covers nothing).
  function referenceLines(references, shown) {
    return function (ctx, area, g) {
      if (!shown()) return;
      references.forEach(function (r) {
        ctx.save();
        ctx.strokeStyle = '#707070';
        ctx.lineWidth = 2;
        ctx.setLineDash([8, 5]);
        ctx.beginPath();
        var drawing = false;
        r.cps.forEach(function (v, i) {
          if (v === null) { drawing = false; return; }
          var x = area.x + g.toPercentXCoord(r.f[i]) * area.w, y = g.toDomYCoord(v);  // toDomXCoord is linear
          if (drawing) ctx.lineTo(x, y); else ctx.moveTo(x, y);
          drawing = true;
        });
        ctx.stroke();
        ctx.restore();
      });
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
      var refs = (o.references || []).map(function (r) { return { name: r.name, rms: r.rms, cps: r.cps, f: o.f }; });
      refs.forEach(function (r) {
        top = Math.max(top, r.cps.reduce(function (a, v) { return v === null ? a : Math.max(a, v * 1.06); }, 0));
      });
      var forwardShown = function () { return cpsFig.raw === forward.raw; };
      var gc = draw(cpsFig, el, { stackedGraph: true, fillGraph: true, fillAlpha: 0.7, valueRange: [0, top],
                                  dateWindow: window_hz, rightGap: 64, underlayCallback: function (ctx, area, g) {
                                    requirementLine(req)(ctx, area, g);
                                    referenceLines(refs, forwardShown)(ctx, area, g);
                                    crossingMarker(o, forwardShown)(ctx, area, g);
                                  }, drawCallback: rmsAxis(o) });
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
      refs.forEach(function (r) {  // the reference's key: its RMS over what it covers
        var key = document.createElement('span');
        key.className = 'reference';
        key.style.marginLeft = '1.5rem';
        key.textContent = '- - ' + r.name + ' (reference, not summed): RMS ' + num(r.rms) + ' ' + o.unit;
        el.querySelector('.toggles').appendChild(key);
      });
    } else if (kind === 'psd' || kind === 'asd') {
      // PSD, or ASD = sqrt(PSD) by the box under the figure.
      var psd = o.psd.concat([o.total_psd]);
      var asd = psd.map(function (s) { return s.map(function (v) { return v === null ? null : Math.sqrt(v); }); });
      var units = { psd: o.variance_unit + '/Hz', asd: (/[/ ]/.test(o.unit) ? '(' + o.unit + ')' : o.unit) + '/√Hz' };
      var fig = { names: o.contributors.concat(['total']), colours: o.colours.concat(['#000000']), raw: psd,
                  rows: rows(o.f, psd), logY: true, ylabel: 'PSD [' + units.psd + ']', xText: hz,
                  valueText: function (v) { return num(v) + ' ' + units[fig.raw === psd ? 'psd' : 'asd']; } };
      // Contributors wide, the total a thin line over them: a contributor that is all of the total shows.
      var widths = {};
      fig.names.forEach(function (n, k) { widths['s' + k] = { strokeWidth: k < o.contributors.length ? 2.6 : 1.0 }; });
      // The y axis over the decades that hold the variance: at most 10 (PSD) or 5 (ASD) below the peak,
      // as the PNG (notches of a sinc^2 would otherwise stretch it to 1e-24).
      function decades(series, n) {
        var top = 0, bottom = Infinity;
        series.forEach(function (s) { s.forEach(function (v) { if (v > 0) { top = Math.max(top, v); bottom = Math.min(bottom, v); } }); });
        if (!(top > 0)) return null;
        var lo = Math.max(bottom, top * Math.pow(10, -n));
        return [Math.pow(10, Math.floor(Math.log10(lo))), Math.pow(10, Math.ceil(Math.log10(top * 1.5)))];
      }
      var ranges = { psd: decades(psd, 10), asd: decades(asd, 5) };
      var g = draw(fig, el, { dateWindow: window_hz, series: widths, valueRange: ranges.psd });
      graphs['psd' + i] = g;
      var label = document.createElement('label'), box = document.createElement('input');
      box.type = 'checkbox';
      box.className = 'asd';
      box.addEventListener('change', function () {
        fig.raw = box.checked ? asd : psd;
        g.updateOptions({ file: rows(o.f, fig.raw), valueRange: box.checked ? ranges.asd : ranges.psd,
                          ylabel: esc(box.checked ? 'ASD [' + units.asd + ']' : 'PSD [' + units.psd + ']') });
      });
      label.appendChild(box);
      label.appendChild(document.createTextNode('amplitude (ASD = √PSD)'));
      label.style.marginLeft = '1.5rem';
      el.querySelector('.toggles').appendChild(label);
      if (kind === 'asd') box.click();  // the report was asked for amplitudes (--asd)
    } else if (kind === 'bands') {
      var names = o.band_contributors, raw = names.map(function (n, k) {
        return o.band_variance.map(function (b) { return b[k]; });
      });
      var totals = o.band_variance.map(function (b) { return b.reduce(function (a, v) { return a + v; }, 0); });
      var bandRows = o.bands.map(function (b, j) { return [j].concat(raw.map(function (r) { return r[j]; })); });
      var bandText = function (x) { return o.bands[Math.round(x)] ? o.bands[Math.round(x)] + ' Hz' : ''; };
      draw({ names: names, colours: o.band_colours, raw: raw, total: totals, rows: bandRows, logX: false,
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
