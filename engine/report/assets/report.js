// dampbench report: draws the JSON document embedded in the page (engine/report/html_report.cpp) with D3 v3
// into SVG. Every number is computed by dampbench; this script only lays out and draws. Figures are drawn in
// small batches (setTimeout) so long reports stay responsive; <body data-rendered="N"> marks the end.
(function () {
  'use strict';
  var errors = [];
  window.addEventListener('error', function (e) {
    errors.push(String(e.message));
    var box = document.getElementById('report-errors');
    if (box) { box.textContent = 'Drawing errors: ' + errors.join('; '); box.style.display = 'block'; }
  });

  var data = JSON.parse(document.getElementById('dampbench-data').textContent);
  var root = d3.select('#report');
  var palette = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f'];
  var colorIndex = {};
  function colorOf(key) {
    if (!(key in colorIndex)) colorIndex[key] = Object.keys(colorIndex).length;
    return palette[colorIndex[key] % palette.length];
  }
  var queue = [], figures = 0;
  function later(draw) { queue.push(draw); }
  // A collapsed condition (reports of more than 12) is drawn when it is first opened.
  function whenOpen(box, draw) {
    if (box.property('open')) { draw(); return; }
    var drawn = false;
    box.on('toggle', function () {
      if (drawn || !box.property('open')) return;
      drawn = true;
      draw();
      setTimeout(drain, 0);
    });
  }
  function drain() {
    var start = Date.now();
    while (queue.length && Date.now() - start < 30) queue.shift()();
    if (queue.length) setTimeout(drain, 0);
    else document.body.setAttribute('data-rendered', String(figures));
  }
  function fmt(v) { return v === null || v === undefined ? '–' : (Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(3) : +v.toPrecision(4)); }
  function finite(v) { return v !== null && v !== undefined && isFinite(v); }

  // One chart: series of {label, color, x, y, kind: line|step|points|band (y0, y1), dashed, faint, title}.
  function chart(parent, o) {
    figures += 1;
    var fig = parent.append('figure').attr('class', 'fig').attr('data-kind', o.kind);
    fig.append('figcaption').text(o.title);
    var W = o.width || 360, H = o.height || 260, m = {top: 8, right: 12, bottom: 40, left: 72};
    var w = W - m.left - m.right, h = H - m.top - m.bottom;
    var xs = [], ys = [];
    o.series.forEach(function (s) {
      var n = s.x.length;
      for (var i = 0; i < n; i++) {
        if (!finite(s.x[i])) continue;
        if (s.kind === 'band') { if (finite(s.y0[i]) && finite(s.y1[i])) { xs.push(s.x[i]); ys.push(s.y0[i], s.y1[i]); } }
        else if (finite(s.y[i])) { xs.push(s.x[i]); ys.push(s.y[i]); }
      }
    });
    function positive(v) { return v.filter(function (x) { return x > 0; }); }
    var xLog = o.xLog && positive(xs).length > 0, yLog = o.yLog && positive(ys).length > 0;
    if (xLog) xs = positive(xs);
    if (yLog) ys = positive(ys);
    var x = (xLog ? d3.scale.log() : d3.scale.linear()).range([0, w]);
    var y = (yLog ? d3.scale.log() : d3.scale.linear()).range([h, 0]);
    x.domain(xs.length ? d3.extent(xs) : [0, 1]);
    y.domain(o.yDomain || (ys.length ? d3.extent(ys) : [0, 1]));
    if (x.domain()[0] === x.domain()[1]) x.domain(xLog ? [x.domain()[0] / 2, x.domain()[0] * 2] : [x.domain()[0] - 1, x.domain()[0] + 1]);
    if (y.domain()[0] === y.domain()[1]) y.domain(yLog ? [y.domain()[0] / 2, y.domain()[0] * 2] : [y.domain()[0] - 1, y.domain()[0] + 1]);
    if (!xLog) x.nice();
    if (!yLog && !o.yDomain) y.nice();
    var svg = fig.append('svg').attr('width', W).attr('height', H).attr('viewBox', '0 0 ' + W + ' ' + H);
    var g = svg.append('g').attr('transform', 'translate(' + m.left + ',' + m.top + ')');
    var xAxis = d3.svg.axis().scale(x).orient('bottom').ticks(5);
    var yAxis = d3.svg.axis().scale(y).orient('left').ticks(5);
    if (xLog) logTicks(xAxis, x, d3.format('.2s'));
    if (yLog) logTicks(yAxis, y, d3.format('.3g'));
    g.append('g').attr('class', 'axis').attr('transform', 'translate(0,' + h + ')').call(xAxis);
    g.append('g').attr('class', 'axis').call(yAxis);
    g.append('text').attr('class', 'label').attr('x', w / 2).attr('y', h + 34).attr('text-anchor', 'middle').text(o.xLabel);
    g.append('text').attr('class', 'label').attr('transform', 'rotate(-90)').attr('x', -h / 2).attr('y', -60)
      .attr('text-anchor', 'middle').text(o.yLabel);
    var plot = g.append('g');
    function px(v) { return Math.round(v * 10) / 10; }  // 0.1 px: shorter paths, same picture
    function ok(v, log) { return finite(v) && (!log || v > 0); }
    o.series.forEach(function (s) {
      var idx = d3.range(s.x.length);
      if (s.kind === 'band') {
        var area = d3.svg.area().defined(function (i) { return ok(s.x[i], xLog) && ok(s.y0[i], yLog) && ok(s.y1[i], yLog); })
          .x(function (i) { return px(x(s.x[i])); }).y0(function (i) { return px(y(s.y0[i])); })
          .y1(function (i) { return px(y(s.y1[i])); });
        plot.append('path').attr('class', 'series band').attr('d', area(idx)).style('fill', s.color).style('opacity', 0.18);
      } else if (s.kind === 'points') {
        plot.selectAll('circle.none').data(idx.filter(function (i) { return ok(s.x[i], xLog) && ok(s.y[i], yLog); })).enter()
          .append('circle').attr('class', 'point').attr('r', s.radius || 3.5)
          .attr('cx', function (i) { return x(s.x[i]); }).attr('cy', function (i) { return y(s.y[i]); })
          .style('fill', function (i) { return s.hollow && s.hollow[i] ? 'white' : s.color; }).style('stroke', s.color)
          .append('title').text(function (i) { return (s.titles ? s.titles[i] + ': ' : '') + fmt(s.y[i]); });
      } else {
        var line = d3.svg.line().defined(function (i) { return ok(s.x[i], xLog) && ok(s.y[i], yLog); })
          .x(function (i) { return px(x(s.x[i])); }).y(function (i) { return px(y(s.y[i])); })
          .interpolate(s.kind === 'step' ? 'step-after' : 'linear');
        plot.append('path').attr('class', 'series line').attr('d', line(idx)).style('stroke', s.color)
          .style('stroke-width', s.faint ? 0.8 : 1.6).style('opacity', s.faint ? 0.35 : 1)
          .style('stroke-dasharray', s.dashed ? '5,3' : null).append('title').text(s.label);
      }
    });
    var legend = fig.append('div').attr('class', 'legend');
    o.series.forEach(function (s) {
      if (!s.label || s.noLegend) return;
      var item = legend.append('span').attr('class', 'item');
      item.append('span').attr('class', 'swatch').style('background', s.color);
      item.append('span').text(s.label);
    });
    return fig;
  }

  // At most 6 labelled ticks on a log axis, whatever its range (D3's own choice labels none within a decade).
  function logTicks(axis, scale, format) {
    var d = scale.domain();
    var all = d[1] / d[0] < 10 ? d3.scale.linear().domain(d).ticks(4) : scale.ticks(), step = Math.ceil(all.length / 6);
    var values = all.length ? all.filter(function (_, i) { return i % step === 0; }) : scale.domain();
    axis.tickValues(values).tickFormat(format);
  }

  function el(parent, tag, text, cls) {
    var e = parent.append(tag);
    if (text !== undefined) e.text(text);
    if (cls) e.attr('class', cls);
    return e;
  }

  // Header: title, notes, fingerprint, contents.
  el(root, 'h1', data.title);
  el(root, 'div', '', 'errors').attr('id', 'report-errors').style('display', 'none');
  data.notes.forEach(function (n) { el(root, 'p', n, 'note'); });
  var sections = [
    ['loops', 'Hysteresis loops', data.conditions.length > 0],
    ['held-out', 'Held-out predictions', data.held_out.length > 0],
    ['convergence', 'Convergence', data.conditions.length > 0],
    ['runs', 'Run distributions', data.distributions.length > 0],
    ['ecdf', 'Fixed-target runtime', data.ecdfs.length > 0 || data.runtimes.length > 0],
    ['laws', 'Parameters against operating variables', data.laws.length > 0],
    ['tables', 'Tables', data.tables.length > 0],
    ['fingerprint', 'Fingerprint', true]];
  var toc = el(root, 'nav', '', 'toc');
  sections.forEach(function (s) { if (s[2]) toc.append('a').attr('href', '#' + s[0]).text(s[1]); });

  function conditionTitle(c) {
    var parts = [];
    if (c.part) parts.push(c.part);
    if (c.split) parts.push('split ' + c.split);
    parts.push(c.condition);
    return parts.join(' · ');
  }
  var collapsed = data.conditions.length > 12;

  // Loops: per condition and record, F–x, F–v and residual over time, measured against each model's best fit.
  if (data.conditions.length) {
    el(root, 'h2', 'Hysteresis loops').attr('id', 'loops');
    el(root, 'p', 'Measured force (black) against the force of each model\'s best run, simulated by dampbench from ' +
      'its stored parameters. Residual = model − measured. Records longer than the drawing limit are drawn at ' +
      'every k-th sample (the caption says which).' + (collapsed ? ' Open a condition to draw its figures.' : ''), 'help');
    data.conditions.forEach(function (c) {
      var box = el(root, 'details', undefined, 'condition');
      if (!collapsed) box.attr('open', '');
      el(box, 'summary', conditionTitle(c));
      c.records.forEach(function (rf) { recordFigures(box, rf); });
    });
  }

  // One record's figures in a condition's (or fold's) box: F–x, F–v and residual over time, measured against each
  // model's force (dashed where the record was predicted, not fitted). rf.title, when given, heads the captions.
  function recordFigures(box, rf) {
    var rec = data.records[rf.record];
    var head = rf.title || (rf.role === 'predicted' ? 'predicted: ' : '') + rec.name + (rec.label ? ' (' + rec.label + ')' : '');
    if (rec.unavailable) { el(box, 'p', head + ': not drawn, ' + rec.unavailable, 'note'); return; }
    var row = el(box, 'div', undefined, 'row');
    var every = rec.stride > 1 ? ', every ' + rec.stride + 'th of ' + rec.samples + ' samples' : '';
    whenOpen(box, function () { later(function () {
      var measured = {label: 'measured', color: '#000', kind: 'line'};
      function loop(xKey, kind, xLabel) {
        var series = [Object.assign({}, measured, {x: rec[xKey], y: rec.F})];
        rf.models.forEach(function (m) {
          series.push({label: m.model + ' (' + m.optimizer + ', ' + m.metric + ' ' + fmt(m.value) + ')',
                       color: colorOf(m.model), kind: 'line', dashed: rf.role === 'predicted', x: rec[xKey], y: m.F});
        });
        chart(row, {kind: kind, title: head + ': force against ' + xLabel + every, xLabel: xLabel, yLabel: 'F [N or N·m]', series: series});
      }
      loop('x', 'loop-displacement', 'x [m or rad]');
      loop('v', 'loop-velocity', 'v [m/s or rad/s]');
      var residuals = rf.models.map(function (m) {
        return {label: m.model, color: colorOf(m.model), kind: 'line', x: rec.t,
                y: m.F.map(function (f, i) { return finite(f) && finite(rec.F[i]) ? f - rec.F[i] : null; })};
      });
      chart(row, {kind: 'residual', title: head + ': residual over time' + every, xLabel: 't [s]', yLabel: 'F model − measured', series: residuals});
    }); });
  }

  // Held-out records: per fold, each record it predicts measured against the fold's prediction (the same figures).
  if (data.held_out.length) {
    el(root, 'h2', 'Held-out predictions').attr('id', 'held-out');
    el(root, 'p', 'Each held-out record (black) against the force predicted for it (dashed) by the model and best ' +
      'parameters of the fold that left it out; fold "all" is the fit on every fitted record, predicting the --predict ' +
      'records. Captions give the record\'s metric and, with --reference per-file, its ratio to the record\'s own ' +
      'per-file fit; the held-out tables list them all.', 'help');
    data.held_out.forEach(function (f) {
      var box = el(root, 'details', undefined, 'condition fold').attr('open', '');
      el(box, 'summary', 'fold ' + f.fold + (f.fitted_on ? ' — fitted on ' + f.fitted_on : ''));
      f.records.forEach(function (rf) { recordFigures(box, rf); });
    });
  }

  // Convergence: best-so-far against evaluations, each run faint, median and interquartile band per optimizer.
  if (data.conditions.length) {
    el(root, 'h2', 'Convergence').attr('id', 'convergence');
    el(root, 'p', 'Best-so-far metric against evaluations: every run (thin steps), the median over runs (thick) and ' +
      'the band between the 25 % and 75 % quantiles, per optimizer. "not converged" repeats the tables\' † verdict.', 'help');
    data.conditions.forEach(function (c) {
      var box = el(root, 'details', undefined, 'condition');
      if (!collapsed) box.attr('open', '');
      el(box, 'summary', conditionTitle(c));
      var row = el(box, 'div', undefined, 'row');
      c.convergence.forEach(function (mc) {
        var stored = mc.optimizers.some(function (o) { return o.runs.some(function (r) { return r.length > 0; }); });
        if (!stored) {  // a store written without best-so-far traces
          el(row, 'p', mc.model + ': no convergence history in this store', 'note');
          return;
        }
        whenOpen(box, function () { later(function () {
          var series = [];
          mc.optimizers.forEach(function (o) {
            var col = colorOf('opt:' + o.optimizer);
            o.runs.forEach(function (run) {
              series.push({kind: 'step', faint: true, color: col, noLegend: true, label: o.optimizer + ' run',
                           x: run.map(function (p) { return p[0]; }), y: run.map(function (p) { return p[1]; })});
            });
            series.push({kind: 'band', color: col, noLegend: true, x: o.band.evaluations, y0: o.band.q25, y1: o.band.q75});
            series.push({kind: 'line', color: col, label: o.optimizer + ' median of ' + o.runs.length + ' runs' +
                         (o.converged ? '' : ' — not converged (' + o.verdict + ')'), x: o.band.evaluations, y: o.band.median});
          });
          chart(row, {kind: 'convergence', title: mc.model, xLabel: 'evaluations', yLabel: 'best-so-far ' + mc.optimizers[0].metric,
                      xLog: true, yLog: true, series: series});
        }); });
      });
    });
  }

  // Run distributions: the final metric of every run, per condition and optimizer (box: quartiles, whiskers: range).
  if (data.distributions.length) {
    el(root, 'h2', 'Run distributions').attr('id', 'runs');
    el(root, 'p', 'Final metric of every run per condition: box from the 25 % to the 75 % quantile with the median, ' +
      'whiskers to the best and worst run, one dot per run. Runs that agree to better than 1e-3 are drawn relative to ' +
      'the best run (axis: run / best − 1), runs that agree to 1e-9 as one line, "all runs equal".', 'help');
    data.distributions.forEach(function (d) {
      var slot = el(root, 'div', undefined, 'row');  // the figure's place, filled when its turn comes
      later(function () { distribution(slot, d); });
    });
  }

  // The run-distribution axis. Runs that agree to more digits than a tick label holds are drawn relative to the
  // best run (the label says so, the caption gives the best), and runs that agree to rounding (1e-9 of the best)
  // are drawn on one line read as "all runs equal": a linear axis over such a spread would label its ticks with
  // a dozen digits that say nothing and do not fit beside the figure.
  function runAxis(ext, count) {
    var best = ext[0], size = Math.max(Math.abs(ext[0]), Math.abs(ext[1])), spread = ext[1] - ext[0];
    var value = {mode: 'value', label: '', caption: '', shown: function (v) { return v; }};
    if (!count || !(size > 0) || !isFinite(spread)) return value;
    if (spread <= 1e-9 * size)
      return {mode: 'equal', label: '', caption: 'all runs equal: ' + fmt(best), shown: function () { return 0; }};
    if (spread >= 1e-3 * size || best === 0) return value;
    return {mode: 'relative', label: ' / best − 1', caption: 'relative to the best run, ' + fmt(best),
            shown: function (v) { return (v - best) / Math.abs(best); }};
  }

  function distribution(parent, d) {
    figures += 1;
    var title = [d.part, d.split ? 'split ' + d.split : '', d.model, d.metric].filter(function (s) { return s; }).join(' · ');
    var fig = parent.append('figure').attr('class', 'fig wide').attr('data-kind', 'runs');
    fig.append('figcaption').text(title);
    var m = {top: 8, right: 12, bottom: 90, left: 64};
    var W = Math.max(360, Math.min(1400, 70 + d.conditions.length * (24 + 14 * d.optimizers.length))), H = 300;
    var w = W - m.left - m.right, h = H - m.top - m.bottom;
    var all = [];
    d.values.forEach(function (row) { row.forEach(function (runs) { runs.forEach(function (v) { if (finite(v)) all.push(v); }); }); });
    var ext = all.length ? d3.extent(all) : [0, 1];
    var axis = runAxis(ext, all.length);
    var shown = axis.shown;
    var log = axis.mode === 'value' && ext[0] > 0 && ext[1] / ext[0] > 20;
    var y = (log ? d3.scale.log() : d3.scale.linear()).range([h, 0]);
    if (axis.mode === 'equal') y.domain([-1, 1]);
    else if (axis.mode === 'relative') y.domain([0, shown(ext[1])]).nice();
    else y.domain(ext[0] === ext[1] ? [ext[0] * 0.9, ext[1] * 1.1 + 1e-300] : ext);
    if (axis.mode === 'value' && !log) y.nice();
    if (axis.caption) fig.select('figcaption').text(title + ' — ' + axis.caption);
    var x = d3.scale.ordinal().domain(d3.range(d.conditions.length)).rangeBands([0, w], 0.2);
    var inner = d3.scale.ordinal().domain(d3.range(d.optimizers.length)).rangeBands([0, x.rangeBand()], 0.15);
    var svg = fig.append('svg').attr('width', W).attr('height', H);
    var g = svg.append('g').attr('transform', 'translate(' + m.left + ',' + m.top + ')');
    var yAxis = d3.svg.axis().scale(y).orient('left').ticks(5, log || axis.mode === 'relative' ? '.1e' : undefined);
    if (axis.mode === 'equal') yAxis.tickValues([0]).tickFormat(function () { return fmt(ext[0]); });
    g.append('g').attr('class', 'axis').call(yAxis);
    if (axis.mode === 'equal')
      g.append('text').attr('class', 'label equal-runs').attr('x', w / 2).attr('y', h / 4).attr('text-anchor', 'middle')
        .text('all ' + all.length + ' runs equal (spread ≤ 1e-9 of the best)');
    g.append('g').attr('class', 'axis').attr('transform', 'translate(0,' + h + ')')
      .call(d3.svg.axis().scale(x).orient('bottom').tickFormat(function (i) { return d.conditions[i]; }))
      .selectAll('text').attr('transform', 'rotate(-35)').style('text-anchor', 'end');
    g.append('text').attr('class', 'label').attr('transform', 'rotate(-90)').attr('x', -h / 2).attr('y', -50)
      .attr('text-anchor', 'middle').text('final ' + d.metric + axis.label);
    d.optimizers.forEach(function (opt, oi) {
      var col = colorOf('opt:' + opt);
      d.conditions.forEach(function (cond, ci) {
        var v = d.values[oi][ci].filter(finite).sort(d3.ascending);
        if (!v.length) return;
        var x0 = x(ci) + inner(oi), bw = inner.rangeBand(), mid = x0 + bw / 2;
        var q1 = d3.quantile(v, 0.25), q2 = d3.quantile(v, 0.5), q3 = d3.quantile(v, 0.75);
        g.append('path').attr('class', 'series whisker').attr('d', 'M' + mid + ',' + y(shown(v[0])) + 'V' + y(shown(v[v.length - 1])))
          .style('stroke', col);
        g.append('rect').attr('class', 'box').attr('x', x0).attr('width', bw).attr('y', y(shown(q3)))
          .attr('height', Math.max(1, y(shown(q1)) - y(shown(q3)))).style('stroke', col).style('fill', col).style('fill-opacity', 0.15);
        g.append('path').attr('class', 'series median').attr('d', 'M' + x0 + ',' + y(shown(q2)) + 'H' + (x0 + bw)).style('stroke', col)
          .style('stroke-width', 2);
        v.forEach(function (val, k) {  // deterministic spread across the box
          g.append('circle').attr('class', 'point').attr('r', 1.8)
            .attr('cx', x0 + bw * (0.15 + 0.7 * ((k * 0.618034) % 1))).attr('cy', y(shown(val))).style('fill', col).style('opacity', 0.6)
            .append('title').text(opt + ', ' + cond + ': ' + fmt(val));
        });
      });
    });
    var legend = fig.append('div').attr('class', 'legend');
    d.optimizers.forEach(function (opt) {
      var item = legend.append('span').attr('class', 'item');
      item.append('span').attr('class', 'swatch').style('background', colorOf('opt:' + opt));
      item.append('span').text(opt);
    });
  }

  // A table with its title, paper and note; `open` shows it unfolded.
  function drawTable(parent, t, open) {
    var box = el(parent, 'details', undefined, 'table');
    if (open) box.attr('open', '');
    el(box, 'summary', t.title + (t.paper ? ' — ' + t.paper : ''));
    var table = box.append('table').attr('data-id', t.id);
    var tr = table.append('thead').append('tr');
    t.columns.forEach(function (c) { el(tr, 'th', c); });
    var body = table.append('tbody');
    t.rows.forEach(function (r) { var row = body.append('tr'); r.forEach(function (c) { el(row, 'td', c); }); });
    if (t.note) el(box, 'p', t.note, 'note');
  }

  // Fixed-target runtime (COCO / IOHprofiler style): the ECDFs, then the ERT tables they come from.
  if (data.ecdfs.length || data.runtimes.length) {
    el(root, 'h2', 'Fixed-target runtime').attr('id', 'ecdf');
    el(root, 'p', 'Share of (condition, run) pairs whose best-so-far reached the target (each title gives it) within ' +
      'the evaluations on the x axis; the runtime tables below give success, ERT (evaluations, restarts included, ' +
      'per success) and ERT in seconds of this machine.', 'help');
    var erow = el(root, 'div', undefined, 'row');
    data.ecdfs.forEach(function (e) {
      later(function () {
        chart(erow, {kind: 'ecdf', title: e.title, xLabel: 'evaluations', yLabel: 'share of runs at target', xLog: true,
                     yDomain: [0, 1], series: e.series.map(function (s) {
                       return {kind: 'step', label: s.label, color: colorOf('opt:' + s.label), x: e.budgets, y: s.fraction};
                     })});
      });
    });
    data.runtimes.forEach(function (t) { drawTable(root, t, true); });
  }

  // Identified parameters against the operating variable of their law, with the fitted law.
  if (data.laws.length) {
    el(root, 'h2', 'Parameters against operating variables').attr('id', 'laws');
    el(root, 'p', 'Best-run parameter per condition (dots; hollow: not identifiable from that record, ‡ in the tables) ' +
      'and the least-squares law through them (line), one per value of the law\'s other variables. SI units.', 'help');
    var lrow = el(root, 'div', undefined, 'row');
    data.laws.forEach(function (l) {
      later(function () {
        var series = [];
        l.groups.forEach(function (gr, k) {
          var col = palette[k % palette.length];
          series.push({kind: 'line', color: col, label: gr.label || l.law, x: gr.curve.x, y: gr.curve.y});
          series.push({kind: 'points', color: col, noLegend: true, x: gr.points.map(function (p) { return p.x; }),
                       y: gr.points.map(function (p) { return p.y; }), titles: gr.points.map(function (p) { return p.condition; }),
                       hollow: gr.points.map(function (p) { return p.undetermined; })});
        });
        chart(lrow, {kind: 'law', title: l.title + ' = ' + l.law + ' (R² ' + fmt(l.r2) + ')', xLabel: l.variable, yLabel: l.parameter, series: series});
      });
    });
  }

  // Tables: the same cells as `dampbench table --kind sweep`.
  if (data.tables.length) {
    el(root, 'h2', 'Tables').attr('id', 'tables');
    data.tables.forEach(function (t) { drawTable(root, t, false); });
  }

  el(root, 'h2', 'Fingerprint').attr('id', 'fingerprint');
  var ft = root.append('table').attr('class', 'fingerprint').append('tbody');
  data.fingerprint.forEach(function (f) { var r = ft.append('tr'); el(r, 'th', f[0]); el(r, 'td', f[1]); });

  setTimeout(drain, 0);
})();
