"""Graph tick labels in plain decimals, for every page that draws graphs with flot.

vpython's graphs (the local page) and GlowScript 3.2's (the offline page, export/offline_page.py)
both draw with flot through jQuery's $.plot, and flot may choose a tick spacing of 2.5 × 10ⁿ and
print it rounded (`0.3, 0.5, 0.8` for ticks 0.25 apart), or in e-notation (`4e-2`). The script
here wraps $.plot once so that every axis prints its ticks with the decimals its spacing needs.
browser/axes.py chooses round axis ends as well; tests/test_tick_labels.py runs the script in
Chromium's flot from 10⁻⁶ to 10⁶.
"""
from __future__ import annotations

# vpython's graphs hand flot their own tick formatter, which writes a small axis in e-notation
# (format_number in glow.min.js: ticks 0.02 apart below 0.1 read 2e-2, 4e-2). Every graph is drawn
# by a call to jQuery's $.plot, so the page wraps that call once and gives every axis this one:
# the tick value with as many decimals as the spacing needs (0.0005 → 4, 2.5 → 1, 200 → 0), "0"
# at zero, never an exponent (toFixed writes plain digits below 10²¹).
#
# clear_outside: vpython's graphs never clear the canvas outside the plotting area (it keeps its
# titles there, and the local page writes them in a line above each graph instead), so the local
# page clears it after every drawing. GlowScript's offline graphs draw their title and axis labels
# there, and keep them.
_SCRIPT = """<script>(function () {
  var CLEAR = %(clear)s;
  var jq = window.jQuery; if (!jq || !jq.plot || jq.plot.plainTicks) return;
  function plain(value, axis) {
    var step = Math.abs(axis.tickSize) || Math.abs(value) || 1;
    var decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    while (decimals < 20 && Math.abs(Math.round(step * Math.pow(10, decimals)) - step * Math.pow(10, decimals)) > 1e-6) decimals++;
    if (Math.abs(value) < step / 2) return "0";
    return value.toFixed(decimals);
  }
  // vpython's graphs never clear the canvas outside the plotting area (it keeps its titles there),
  // so where a thick curve once touched the frame (an axis about to widen), half its width stayed
  // above the frame for good (resonance's position graph, from t = 16 s). After every drawing,
  // everything outside the frame is cleared: the titles are in the line above each graph.
  function clearOutside(plot, ctx) {
    var o = plot.getPlotOffset(), w = plot.width(), h = plot.height();
    var holder = plot.getPlaceholder(), W = holder.width(), H = holder.height();
    var border = plot.getOptions().grid.borderWidth, edge = 1 + (typeof border === "number" ? border :
        Math.max(border.top || 0, border.right || 0, border.bottom || 0, border.left || 0));
    ctx.save();
    ctx.clearRect(0, 0, W, Math.max(0, o.top - edge));
    ctx.clearRect(0, o.top + h + edge, W, H);
    ctx.clearRect(0, 0, Math.max(0, o.left - edge), H);
    ctx.clearRect(o.left + w + edge, 0, W, H);
    ctx.restore();
  }
  var original = jq.plot;
  jq.plot = function (placeholder, data, options) {
    options = options || {};
    ["xaxis", "yaxis"].forEach(function (name) { options[name] = options[name] || {}; options[name].tickFormatter = plain; });
    options.hooks = options.hooks || {};
    var draw = options.hooks.draw || [];
    if (CLEAR && draw.indexOf(clearOutside) < 0) options.hooks.draw = draw.concat([clearOutside]);
    return original(placeholder, data, options);
  };
  for (var key in original) jq.plot[key] = original[key];
  jq.plot.plainTicks = plain;
})();</script>"""


def plain_ticks(*, clear_outside: bool) -> str:
    """The <script> element that makes every flot graph on the page print plain tick labels."""
    return _SCRIPT % {"clear": "true" if clear_outside else "false"}
