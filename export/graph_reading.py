"""Reading a graph by clicking it, as a student reads a period or two amplitudes off a printout.

A click on any graph picks the point of its lines nearest the mouse (on the screen, among every
curve's own points: numbers the engine gave, never a value in between) and writes it in a line
under the graph, with the axes' units (from the graph's titles, `t (s)`, `y (m)`):

    y (simulation): t = 2.35 s, y = −1.932 m

A second click adds the second point and the difference, the way a period or a ratio of
amplitudes is read:

    … then t = 5.5 s, y = −1.93 m: Δt = 3.15 s, Δy = 0.002 m

and a third starts again. The axes' titles come from the graph itself, or in a notebook (where
the page's script cannot reach vpython's graphs) from window.smGraphTitles, which
browser/graphs.py writes, keyed by each graph's first curve's label. The points picked stay marked on the graph (flot's highlight, put back
each time vpython draws the graph anew) while they are on its axis.

All of it runs in the page (GRAPH_READING, a script the controls add once): every graph is drawn by
a call to jQuery's $.plot, which the script wraps, as browser/axes.py's does for the ticks. It works
in the browser and in a notebook alike, and asks nothing of Python. The offline page
(export/offline_page.py) holds the same script: GlowScript 3.2 draws its graphs with flot too, and
the page names each curve's axes in window.smGraphTitles, as a notebook does.
"""
from __future__ import annotations

GRAPH_READING = """<script>(function () {
  var jq = window.jQuery; if (!jq || !jq.plot || jq.plot.smReading) return;
  function part(title, which) {  // 'y (m)' -> name 'y', unit 'm'
    var m = (title || '').match(/^(.*?)\\s*\\(([^()]*)\\)\\s*$/);
    return m ? (which === 'unit' ? m[2] : m[1]) : (which === 'unit' ? '' : (title || ''));
  }
  function number(v) {
    var text = Number(v.toPrecision(4)).toString();
    if (text.indexOf('e') >= 0) text = v.toPrecision(4);
    return text.replace('-', '\\u2212');
  }
  function graphOf(el) {
    if (typeof glowObjs === 'undefined') return null;
    for (var i = 0; i < glowObjs.length; i++) {
      var g = glowObjs[i];
      if (g && g.graph_options && g.container && g.container[0] === el) return g;
    }
    return null;
  }
  function nearest(plot, pos) {  // the lines' own point nearest the click, on the screen
    var best = null;
    plot.getData().forEach(function (s, index) {
      var d = s.datapoints, ps = d.pointsize, xa = s.xaxis, ya = s.yaxis;
      var cx = xa.p2c(pos.x), cy = ya.p2c(pos.y);
      for (var j = 0; j + 1 < d.points.length; j += ps) {
        var x = d.points[j], y = d.points[j + 1];
        if (x == null || y == null || x < xa.min || x > xa.max || y < ya.min || y > ya.max) continue;
        var dx = xa.p2c(x) - cx, dy = ya.p2c(y) - cy, far = dx * dx + dy * dy;
        if (best === null || far < best.far) best = {far: far, x: x, y: y, index: index, label: s.label || ''};
      }
    });
    return best;
  }
  function line(el) {
    var read = el.nextElementSibling;
    while (read && read.classList.contains('sm-note')) read = read.nextElementSibling;
    if (!read || !read.classList.contains('sm-read')) {
      read = document.createElement('div'); read.className = 'sm-read';
      var after = el; while (after.nextElementSibling && after.nextElementSibling.classList.contains('sm-note')) after = after.nextElementSibling;
      after.parentNode.insertBefore(read, after.nextSibling);
    }
    return read;
  }
  function titles(el) {  // [xtitle, ytitle]: from the graph, or where Python wrote them (a notebook)
    var g = graphOf(el);
    if (g) return [g.xtitle, g.ytitle];
    var plot = jq(el).data('plot'), data = plot ? plot.getData() : [];
    var known = window.smGraphTitles || {};
    for (var i = 0; i < data.length; i++) if (known[data[i].label]) return known[data[i].label];
    return ['', ''];
  }
  function show(el) {
    var picks = el.__smPicks || [], named = titles(el);
    var xname = part(named[0], 'name'), xunit = part(named[0], 'unit');
    var yname = part(named[1], 'name'), yunit = part(named[1], 'unit');
    var u = function (unit) { return unit ? '\\u00a0' + unit : ''; };
    var text = '';
    picks.forEach(function (p, n) {
      var said = xname + ' = ' + number(p.x) + u(xunit) + ', ' + (p.label || yname) + ' = ' + number(p.y) + u(yunit);
      text += n === 0 ? '<b>Read:</b> ' + said : '; then ' + said;
    });
    if (picks.length === 2) {
      var a = picks[0], b = picks[1];
      text += ': <b>\\u0394' + xname + ' = ' + number(b.x - a.x) + u(xunit) + ', \\u0394' + (yname || 'value') +
              ' = ' + number(b.y - a.y) + u(yunit) + '</b>';
    }
    var read = line(el);
    read.innerHTML = text;
    read.dataset.picks = JSON.stringify(picks.map(function (p) { return [p.x, p.y, p.label]; }));
  }
  function mark(plot, el) {  // put the picked points back on a graph vpython has drawn anew
    (el.__smPicks || []).forEach(function (p) {
      var data = plot.getData();
      for (var i = 0; i < data.length; i++) if ((data[i].label || '') === p.label) { plot.highlight(i, [p.x, p.y]); return; }
    });
  }
  var original = jq.plot;
  jq.plot = function (placeholder, data, options) {
    options = options || {};
    options.grid = options.grid || {};
    options.grid.clickable = true;
    var plot = original(placeholder, data, options);
    var el = jq(placeholder)[0];
    if (el && !el.__smReading) {
      el.__smReading = true;
      el.style.cursor = 'crosshair';
      jq(el).bind('plotclick', function (event, pos) {
        var now = jq(el).data('plot'), pick = now && nearest(now, pos);
        if (!pick) return;
        var picks = el.__smPicks || [];
        if (picks.length >= 2) picks = [];
        picks.push({x: pick.x, y: pick.y, label: pick.label});
        el.__smPicks = picks;
        now.unhighlight();
        mark(now, el);
        show(el);
      });
    }
    if (el) mark(plot, el);
    return plot;
  };
  for (var key in original) jq.plot[key] = original[key];
  jq.plot.smReading = true;
})();</script>"""
