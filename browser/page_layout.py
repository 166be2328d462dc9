"""How the page sits in the window, read from the back of a room: sizes, text, legends and keys.

vpython 7.6.5 draws a fixed-size 3-D canvas, its caption under it and each graph under the last,
so at 1280 × 800 the graphs started below the fold. This module's CSS and a short script (sent
once with the page's title; jQuery runs scripts in the HTML it inserts) lay the page out in the
browser, where the window's size is known, and again whenever the window is resized:

* the 3-D view at the top left, as wide as the window leaves it (its shape stays
  scene3d.CANVAS_SIZE's, so the camera framing worked out in Python still holds), the controls
  under it, and the graphs in a column on the right: at 1280 × 800 the view and the position
  graph are both on screen, and at 1024 × 768 nothing scrolls sideways; in a window too narrow
  for both (1280 × 800 at 200 % zoom: 640 CSS px) the graphs go under the controls;
* text at least BODY_PX (18 px) — body, buttons, menus, axis ticks, legends, graph titles — and in
  projector mode (the page's Projector button, key P, or `--projector`) at least PROJECTOR_PX
  (22 px), with every graph line LINE_FACTOR times thicker and black on white;
* each graph's legend in a line of its own above the graph, never over its data, each colour box
  kept on one line with its label (a legend that wraps breaks between entries);
* the 3-D view's labels grow with projector mode as the page's text does, their offsets from
  their masses follow the canvas's size, and each is drawn wholly inside the canvas (moved in from
  an edge it would cross: 18 px text in the 538 × 263 px canvas of a 1024 × 768 window);
* the keys are export/page_keys.py's, heard by export/page_access.js (browser/access.py puts it on
  the page); every control is reached with Tab and shows a thick outline when it has the focus;
* the energy bars (browser/energy_bars.py), when chosen, in the graph place under the graphs.

The graphs keep the height browser/graphs.py gives them (flot's tick spacing depends on it, and
browser/axes.py picks round ticks for that height); only their widths follow the window.
"""
from __future__ import annotations

import json

from .scene3d import CANVAS_SIZE

BODY_PX = 18             # px: the smallest text on the page
PROJECTOR_PX = 22        # px: the smallest text in projector mode
LINE_FACTOR = 1.6        # graph lines this much thicker in projector mode
GRAPH_WIDTH = (420, 760)  # px: the graph column's narrowest and widest
GRAPH_SHARE = 0.45       # of the window's width, for the graph column, within GRAPH_WIDTH
GAP = 16                 # px: between the view's column and the graphs'
NOTE_MARK = " ¶ "         # in a graph's title: what follows is a line to show under the graph
TICK_ROOM = 1.6          # em: room right of the graphs for half their last time tick (`30`, `1000`)

STYLE = """
body { font-size: %(body)dpx; }
button, select, input { font-size: %(body)dpx !important; }
input[type=checkbox] { width: 1em !important; height: 1em !important; vertical-align: middle; }
button { padding: 2px 10px; }
#glowscript > div { white-space: pre-wrap !important; }
#glowscript .glowscript-canvas-wrapper { margin-bottom: 4px; }
#sm-graphs { position: absolute; top: 8px; overflow-x: hidden; }
#sm-graphs .glowscript-graph { float: none !important; display: block; margin: 0 0 6px 0 !important; }
.glowscript-graph .tickLabels, .glowscript-graph .tickLabel { font-size: %(body)dpx !important; color: #000 !important; }
.sm-note { font-size: %(body)dpx; margin: 0 0 10px 0; max-width: 760px; }
.sm-legend { font-size: %(body)dpx; min-height: 4px; line-height: 1.25; }
.sm-legend table { font-size: %(body)dpx !important; color: #000; border-collapse: collapse; }
.sm-key { display: flex; flex-wrap: wrap; align-items: center; }
.sm-key table, .sm-key tbody, .sm-key tr { display: contents; }
.sm-key td { display: inline-block; }
.sm-key .sm-entry { display: inline-flex; align-items: center; white-space: nowrap; }
.sm-legend td.legendLabel { padding: 0 14px 0 4px; white-space: nowrap; }
.sm-legend td.legendColorBox > div { border: none !important; }
.sm-legend td.legendColorBox > div > div { border-width: 8px !important; }
#sm-projector { margin-left: 16px; font-size: %(body)dpx; }
.sm-measure { border: 2px solid #0072b2; border-radius: 6px; padding: 4px 10px; margin: 4px 0 2px 0; background: #fff;
              line-height: 1.6; }
.sm-read { font-size: %(body)dpx; margin: 0 0 8px 0; max-width: 760px; }
.sm-bars { font-size: %(body)dpx; margin: 4px 0 10px 0; }
.sm-bars-table { border-collapse: collapse; width: 100%%; font-size: inherit !important; }
.sm-bars-table td { font-size: inherit !important; }
.sm-bars-table td { padding: 3px 0; }
.sm-bar-label { padding-right: 10px !important; }   /* wraps: '−W_nc (damping, friction)' in a narrow column */
.sm-bar-cell { position: relative; width: 55%%; min-width: 80px; background: #fff; border: 1px solid #999; }
.sm-bar { position: absolute; top: 3px; bottom: 3px; }
.sm-bar-zero { position: absolute; top: 0; bottom: 0; border-left: 2px solid #000; }
.sm-bar-value { white-space: nowrap; text-align: right; padding-left: 10px !important; }
.sm-bars-scale { color: #333; }
button:focus-visible, select:focus-visible, .ui-slider-handle:focus, #sm-projector:focus-visible
  { outline: 4px solid #0072b2 !important; outline-offset: 2px; }
body.sm-projector, body.sm-projector button, body.sm-projector select, body.sm-projector input,
body.sm-projector .sm-legend, body.sm-projector .sm-legend table, body.sm-projector .sm-note,
body.sm-projector .sm-read, body.sm-projector .sm-bars,
body.sm-projector .glowscript-graph .tickLabels, body.sm-projector .glowscript-graph .tickLabel
  { font-size: %(projector)dpx !important; }
body.sm-projector { background: #fff; color: #000; font-weight: 600; }
body.sm-projector button, body.sm-projector select { border: 2px solid #000; color: #000; background: #fff; }
"""

# The script: lays the page out (now, on every resize, and whenever vpython adds a graph), moves each
# graph's legend above it, makes lines thicker in projector mode, and listens to the keys.
SCRIPT = """
(function () {
  var MIN_VIEW = 300;   // px: the narrowest the 3-D view's column gets beside the graphs
  var ASPECT = %(aspect)s, CANVAS_HEIGHT = %(canvas_height)s, GRAPH_WIDTH = %(graph_width)s, SHARE = %(share)s, GAP = %(gap)s,
      FACTOR = %(factor)s, TITLE_PX = [%(body)d, %(projector)d], NOTE_MARK = %(note_mark)s,
      TICK_ROOM = %(tick_room)s;
  if (window.smProjector === undefined) window.smProjector = %(projector_on)s;
  // In a Jupyter notebook the scene is one cell's output: the notebook lays out its page and owns
  // its keys (Space, R and arrows move between cells), so only the text sizes apply there.
  var inNotebook = !!document.querySelector('.jp-Notebook, .jp-Cell, #notebook-container');
  function objects(test) {
    var found = [];
    if (typeof glowObjs === 'undefined') return found;
    for (var i = 0; i < glowObjs.length; i++) if (glowObjs[i] && test(glowObjs[i])) found.push(glowObjs[i]);
    return found;
  }
  function column() {
    var right = document.getElementById('sm-graphs');
    if (!right) { right = document.createElement('div'); right.id = 'sm-graphs'; document.body.appendChild(right); }
    return right;
  }
  // Each legend entry, colour box and label, in one span that never wraps, so that a long legend
  // breaks between entries, never between a box and its label.
  function pairUp(key) {
    key.querySelectorAll('td.legendColorBox').forEach(function (box) {
      if (box.parentNode.classList.contains('sm-entry')) return;
      var label = box.nextElementSibling, entry = document.createElement('span');
      entry.className = 'sm-entry';
      box.parentNode.insertBefore(entry, box);
      entry.appendChild(box);
      if (label && label.classList.contains('legendLabel')) entry.appendChild(label);
    });
  }
  function noteFor(el, text) {  // the line under a graph (a title's part after NOTE_MARK)
    var note = el.nextElementSibling;
    if (!note || !note.classList.contains('sm-note')) {
      if (!text) return;
      note = document.createElement('div'); note.className = 'sm-note';
      el.parentNode.insertBefore(note, el.nextSibling);
    }
    if (note.textContent !== text) note.textContent = text;
  }
  function headerFor(g) {
    var el = g.container && g.container[0];
    if (!el) return;
    var box = el.previousElementSibling;
    if (!box || !box.classList.contains('sm-legend')) {
      box = document.createElement('div'); box.className = 'sm-legend';
      box.innerHTML = '<div class="sm-title"></div><div class="sm-key"></div>';
      el.parentNode.insertBefore(box, el);
    }
    var parts = (g.title || '').split(NOTE_MARK);
    noteFor(el, parts[1] || '');
    var title = '<b>' + parts[0] + '</b>' +
        (g.ytitle ? ': ' + g.ytitle + (g.xtitle ? ' against ' + g.xtitle : '') : '');
    var heading = box.querySelector('.sm-title');
    if (heading.innerHTML !== title) heading.innerHTML = title;
    var key = box.querySelector('.sm-key');
    if (!key.__smObserved) {  // flot writes the legend anew at each redraw: pair it up each time
      key.__smObserved = true;
      new MutationObserver(function () { pairUp(key); }).observe(key, {childList: true, subtree: true});
    }
    pairUp(key);
    var legend = g.graph_options.legend || (g.graph_options.legend = {});
    if (legend.container !== key) { legend.container = key; legend.noColumns = 99; g.__changed = true; }
  }
  function thicken(g) {
    (g.graph_series || []).forEach(function (s) {
      if (s.__smWidth === undefined) s.__smWidth = s.width;
      var want = window.smProjector ? s.__smWidth * FACTOR : s.__smWidth;
      if (s.width !== want) s.width = want;
    });
  }
  function grow(o) {  // a 3-D label's text, as the page's text, TITLE_PX[1]/TITLE_PX[0] larger in projector mode
    if (o.__smHeight === undefined) o.__smHeight = o.height;
    var want = window.smProjector ? Math.round(o.__smHeight * TITLE_PX[1] / TITLE_PX[0]) : o.__smHeight;
    if (o.height !== want) o.height = want;
    // Its offset from the mass, set in Python for a canvas CANVAS_HEIGHT px tall, follows the
    // canvas as the picture does (the text does not shrink: it stays readable).
    if (o.__smOffsets === undefined) o.__smOffsets = [o.xoffset, o.yoffset];
    var scale = o.canvas && o.canvas.__height ? o.canvas.__height / CANVAS_HEIGHT : 1;
    var x = Math.round(o.__smOffsets[0] * scale), y = Math.round(o.__smOffsets[1] * scale);
    if (o.xoffset !== x) o.xoffset = x;
    if (o.yoffset !== y) o.yoffset = y;
    keepInside(Object.getPrototypeOf(o));
  }
  // Every 3-D label is drawn wholly inside its canvas: vpython's own drawing of it is tried first
  // on a spare 2-D canvas, and if its box (the rectangle vpython fills behind the text) would
  // cross an edge, the label is drawn moved in by just that much. Its text stays 18 px while a
  // small window shrinks the canvas, so near an edge it would otherwise be cut off.
  var SPARE = document.createElement('canvas').getContext('2d');
  function keepInside(proto) {
    if (proto.__smInside) return;
    proto.__smInside = true;
    var update = proto.__update;
    proto.__update = function (ctx, camera) {
      var box = null;
      SPARE.fillRect = function (x, y, w, h) { box = [x, y, w, h]; };
      try { update.call(this, SPARE, camera); } finally { delete SPARE.fillRect; }
      if (!box) return update.call(this, ctx, camera);
      var W = this.canvas.__width, H = this.canvas.__height, me = this;
      var dx = Math.max(-box[0], Math.min(0, W - box[0] - box[2]));
      var dy = Math.max(-box[1], Math.min(0, H - box[1] - box[3]));
      if (!dx && !dy) return update.call(this, ctx, camera);
      return shifted(ctx, dx, dy, function () { return update.call(me, ctx, camera); });
    };
  }
  // Draw with everything a label draws moved by (dx, dy) px: vpython resets the context's
  // transform after each piece of text, so a translate() would move only the first line.
  function shifted(ctx, dx, dy, draw) {
    var kept = {};
    [['fillRect', 0], ['moveTo', 0], ['lineTo', 0], ['fillText', 1]].forEach(function (pair) {
      var name = pair[0], at = pair[1], f = ctx[name];
      kept[name] = Object.prototype.hasOwnProperty.call(ctx, name) ? f : null;
      ctx[name] = function () {
        var a = Array.prototype.slice.call(arguments);
        a[at] += dx; a[at + 1] += dy;
        return f.apply(ctx, a);
      };
    });
    try { return draw(); } finally {
      Object.keys(kept).forEach(function (name) { if (kept[name]) ctx[name] = kept[name]; else delete ctx[name]; });
    }
  }
  // The graphs in the order Python made them (vpython places a graph when its first point
  // arrives, and a graph of errors gets none at t = 0, where every error is 0), each under its legend.
  function inOrder(right, graphs) {
    var want = graphs.map(function (g) { return g.container[0]; }).filter(function (el) {
      return el && el.parentNode === right;
    });
    var have = Array.prototype.filter.call(right.children, function (el) {
      return el.classList.contains('glowscript-graph');
    });
    if (want.every(function (el, i) { return have[i] === el; })) return;
    want.forEach(function (el) {
      var box = el.previousElementSibling, after = [];
      for (var next = el.nextElementSibling; next && (next.classList.contains('sm-note') ||
           next.classList.contains('sm-read')); next = next.nextElementSibling) after.push(next);
      if (box && box.classList.contains('sm-legend')) right.appendChild(box);
      right.appendChild(el);
      after.forEach(function (line) { right.appendChild(line); });
    });
  }
  function layout() {
    document.body.classList.toggle('sm-projector', !!window.smProjector);
    if (window.smGather) window.smGather();   // the Measure panel's block (browser/measure_panel.py)
    if (typeof fontsize !== 'undefined') fontsize = TITLE_PX[window.smProjector ? 1 : 0];
    var button = document.getElementById('sm-projector');
    if (button) button.textContent = window.smProjector ? 'Projector: on (P)' : 'Projector: off (P)';
    var labels = objects(function (o) { return o.constructor && o.constructor.name === 'label'; });
    if (inNotebook) {  // vpython writes the titles in the graphs there: without the line meant under one
      objects(function (o) { return o.graph_options && o.title && o.title.indexOf(NOTE_MARK) >= 0; })
        .forEach(function (g) { g.title = g.title.split(NOTE_MARK)[0]; });
      labels.forEach(grow);
      return;
    }
    // Always a vertical scrollbar: one that came and went would change the width, the layout the
    // height, and the scrollbar again, so the controls would jump about.
    document.documentElement.style.overflowY = 'scroll';
    // The window less the body's margins, and room for the graphs' last time tick, which flot
    // centres on the axis's end, half of it past the graph (it made every scene scroll sideways
    // by 14-28 px at 1280 x 800).
    var px = TITLE_PX[window.smProjector ? 1 : 0];
    var W = document.documentElement.clientWidth - 16 - Math.ceil(TICK_ROOM * px), H = window.innerHeight;
    var gw = Math.round(Math.min(GRAPH_WIDTH[1], Math.max(GRAPH_WIDTH[0], SHARE * W)));
    var left = Math.max(MIN_VIEW, W - gw - GAP);
    // Too narrow for two columns (a 1280 x 800 window at 200 %% zoom is 640 CSS px): one column, the
    // graphs under the controls, each as wide as the window, so none is cut off at the right.
    var stacked = W < MIN_VIEW + GAP + GRAPH_WIDTH[0];
    if (stacked) { left = W; gw = Math.min(GRAPH_WIDTH[1], W); }
    var cw = left, ch = Math.round(cw / ASPECT);
    if (ch > 0.6 * H) { ch = Math.round(0.6 * H); cw = Math.round(ch * ASPECT); }
    var main = document.getElementById('glowscript');
    if (main) main.style.width = left + 'px';
    objects(function (o) { return o.__canvas_element; }).forEach(function (c) {
      if (c.width !== cw) c.width = cw;
      if (c.height !== ch) c.height = ch;
    });
    labels.forEach(grow);  // after the canvas has its size: the labels' offsets follow it
    var right = column();
    right.style.position = stacked ? 'static' : '';
    right.style.left = stacked ? '' : (8 + left + GAP) + 'px';
    // Its own width and the room for the last tick, no more: the box flot gives a tick label is
    // wider than its text, and the last one's reached past the window (regimes, 1920 px)
    right.style.width = (gw + Math.ceil(TICK_ROOM * px)) + 'px';
    document.querySelectorAll('#glowscript > .glowscript-graph').forEach(function (el) {
      right.appendChild(el);
    });
    right.querySelectorAll('.sm-legend').forEach(function (box) {
      var next = box.nextElementSibling;
      if (!next || !next.classList.contains('glowscript-graph')) box.remove();
    });
    right.querySelectorAll('.sm-note, .sm-read').forEach(function (note) {
      var before = note.previousElementSibling;
      while (before && before.classList.contains('sm-note')) before = before.previousElementSibling;
      if (!before || !before.classList.contains('glowscript-graph')) note.remove();
    });
    var graphs = objects(function (o) { return o.graph_options && o.container && !o.__deleted; });
    graphs.forEach(function (g) {
      // vpython writes a graph's titles inside it when its first point arrives, until its width
      // changes; the legend line above says them. A graph whose first point came after the layout
      // had set its width (an error graph: every error is 0 at t = 0) is narrowed by a pixel once,
      // and widened back at the next layout, so it looks as the others do.
      // vpython redraws a graph whose width changes with no points at all; marked changed, it is
      // drawn again with its points (a paused graph, or one that gets no new points, stayed blank).
      if (g.__activated && !g.__smResized) { g.__smResized = true; g.width = gw - 1; g.__changed = true; }
      else if (g.width !== gw) { g.width = gw; g.__changed = true; }
      headerFor(g);
      thicken(g);
    });
    inOrder(right, graphs);
    // The energy bars (browser/energy_bars.py) take the graph place, under the other graphs.
    document.querySelectorAll('.sm-bars').forEach(function (bars) {
      var holder = bars.closest('span[id]') || bars;
      holder.style.display = 'block';
      holder.style.width = gw + 'px';
      if (holder.parentNode !== right || holder !== right.lastElementChild) right.appendChild(holder);
    });
  }
  window.smLayout = layout;
  if (!window.smInstalled && !inNotebook) {
    window.smInstalled = true;
    window.addEventListener('resize', layout);
    setInterval(layout, 700);
    // the keys are export/page_access.js's (export/page_keys.py), which both pages share
  }
  layout();
})();
"""

PROJECTOR_BUTTON = ("<button id='sm-projector' type='button' onclick='window.smProjector = !window.smProjector;"
                    " window.smLayout && window.smLayout()'>Projector (P)</button>")

KEYS_HINT = "Keys: Space run/pause, → step, R reset, J jump to t, + and − speed, P projector, Tab moves between controls."


def page_head(*, projector: bool = False) -> str:
    """The style and script the page's title carries: the layout above, starting in projector
    mode if asked (`--projector`); a page already shown keeps the mode its viewer chose."""
    numbers = {"body": BODY_PX, "projector": PROJECTOR_PX}
    script = SCRIPT % {**numbers, "aspect": json.dumps(CANVAS_SIZE[0] / CANVAS_SIZE[1]),
                       "canvas_height": json.dumps(CANVAS_SIZE[1]),
                       "graph_width": json.dumps(list(GRAPH_WIDTH)), "share": json.dumps(GRAPH_SHARE),
                       "gap": json.dumps(GAP), "factor": json.dumps(LINE_FACTOR),
                       "projector_on": json.dumps(bool(projector)), "note_mark": json.dumps(NOTE_MARK),
                       "tick_room": json.dumps(TICK_ROOM)}
    return f"<style>{STYLE % numbers}</style><script>{script}</script>"
