/* What makes both pages usable by keyboard and by a screen reader: one script, written into the
   local page (browser/access.py) and the offline page (export/offline_page.py) alike.

   * the keys (export/page_keys.py declares them): each works wherever the focus is and presses the
     visible control whose label begins with the key's label; it never also activates the focused
     control (Space on a button runs or pauses, it does not press the button); Enter presses or
     ticks the focused control; on a slider the arrow keys move the slider; in a text box keys type;
     the "letter keys" box turns the single-character keys off (WCAG 2.1.4);
   * every graph gets a text alternative (what it plots, the range shown, its curves' last values)
     and, one click away, a table of the points it shows (a <details> under it);
   * the 3-D view gets a text alternative that points to the description in words;
   * the description (export/description.py) is read out from a live region;
   * with prefers-reduced-motion the page opens paused (each page says how: config.pause).

   It steps nothing and names no force: the numbers it writes are the graphs' own points. */
(function () {
  "use strict";
  var A = window.smAccess = window.smAccess || {};

  // ---- the keys ----

  var TEXT_TYPES = /^(text|search|number|email|url|tel|password|date|time|datetime-local|month|week)$/;
  var SLIDER_KEYS = /^(ArrowLeft|ArrowRight|ArrowUp|ArrowDown|Home|End|PageUp|PageDown)$/;
  var swallowed = {};                // keys whose keyup must not press the focused control either

  function typing(el) {              // a text box: its keys are its own
    if (!el) return false;
    if (el.isContentEditable || el.tagName === "TEXTAREA") return true;
    return el.tagName === "INPUT" && TEXT_TYPES.test(el.type || "text") && !el.readOnly;
  }
  function slider(el) {
    return !!el && ((el.tagName === "INPUT" && el.type === "range") || el.getAttribute("role") === "slider" ||
                    (el.classList && el.classList.contains("ui-slider-handle")));
  }
  function shown(el) { return !!el && el.offsetParent !== null && !el.disabled; }

  function labelOf(el) {             // the text a key's label is matched against
    if (el.tagName === "BUTTON") return el.textContent.trim();
    if (el.tagName === "INPUT" && el.type === "checkbox") {
      var label = el.closest("label") || (el.id && document.querySelector("label[for='" + el.id + "']"));
      return (label ? label.textContent : el.getAttribute("aria-label") || "").trim();
    }
    return "";
  }
  function controlFor(key) {
    var found = null;
    document.querySelectorAll("button, input[type=checkbox]").forEach(function (el) {
      if (found || !shown(el)) return;
      var text = labelOf(el).toLowerCase();
      if (key.labels.some(function (label) { return text.indexOf(label.toLowerCase()) === 0; })) found = el;
    });
    return found;
  }
  function menuFor(option) {
    var menus = document.querySelectorAll("select");
    for (var i = 0; i < menus.length; i++) {
      if (!shown(menus[i])) continue;
      for (var j = 0; j < menus[i].options.length; j++) if (menus[i].options[j].text === option) return menus[i];
    }
    return null;
  }
  function stepMenu(menu, by) {
    var n = Math.min(menu.options.length - 1, Math.max(0, menu.selectedIndex + by));
    if (n === menu.selectedIndex) return;
    menu.selectedIndex = n;
    menu.dispatchEvent(new Event("change", {bubbles: true}));
  }
  function lettersOn() {
    var box = document.querySelector(".sm-letter-keys");
    return !box || box.checked;
  }

  function act(key) {                // returns whether the page did something with it
    if (key.menu) {
      var menu = menuFor(key.menu);
      if (menu) stepMenu(menu, key.by);
      return !!menu;
    }
    var control = controlFor(key);
    if (!control) return false;
    control.click();
    return true;
  }

  // In a Jupyter notebook the scene is one cell's output and the notebook owns the keys (D D
  // deletes a cell, S saves): the page's keys work there only while the focus is in the scene.
  var IN_NOTEBOOK = !!document.querySelector(".jp-Notebook, .jp-Cell, #notebook-container");

  function onKeyDown(e) {
    if (e.ctrlKey || e.altKey || e.metaKey || e.defaultPrevented) return;
    var el = e.target;
    if (IN_NOTEBOOK && !(el.closest && el.closest(".glowscript"))) return;
    if (typing(el)) { if (e.key === "Escape") el.blur(); return; }
    if (slider(el) && SLIDER_KEYS.test(e.key)) return;
    if (el.tagName === "SELECT" && /^Arrow(Up|Down)$/.test(e.key)) return;   // ↑ ↓ choose in a menu
    if (el.tagName === "SELECT" && e.key === "ArrowLeft") { e.preventDefault(); return; }   // ← is nobody's
    if (e.key === "Enter" && el.tagName === "INPUT" && el.type === "checkbox") {
      el.click(); e.preventDefault(); return;         // Space is the page's: Enter ticks the box
    }
    var key = (A.keys || []).filter(function (k) { return k.keys.indexOf(e.key) >= 0; })[0];
    if (!key || (key.letter && !lettersOn())) return;
    if (act(key) || e.key === " ") {                  // Space never presses the focused control
      e.preventDefault();
      e.stopPropagation();
      swallowed[e.key] = true;
    }
  }
  function onKeyUp(e) {
    if (swallowed[e.key]) { delete swallowed[e.key]; e.preventDefault(); e.stopPropagation(); }
  }

  // Each control a key presses says so to a screen reader (aria-keyshortcuts).
  function markShortcuts() {
    (A.keys || []).forEach(function (key) {
      if (key.menu) {
        var menu = menuFor(key.menu);
        if (menu) menu.setAttribute("aria-keyshortcuts", "+ -");
        return;
      }
      var control = controlFor(key);
      var name = key.shown === "Space" ? "Space" : key.shown === "→" ? "ArrowRight" : key.shown;
      if (control && control.getAttribute("aria-keyshortcuts") !== name) control.setAttribute("aria-keyshortcuts", name);
    });
  }

  // ---- the graphs' line styles: no curve told from another by colour alone (export/palette.py) ----

  // Each line is drawn with its colour's dash pattern (A.lineStyles: LINE_DASHES, in units of the
  // line's width within A.dashUnit px), and each legend entry shows a sample of the line, its
  // dashes and width, beside its name. A flot plugin: every graph either page draws passes here.
  function styleOf(colour) {         // flot's 'rgb(193,127,0)' -> that colour's pattern, in units
    var m = /rgba?\(\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)/.exec(colour || "");
    if (!m) return [];
    var rgb = [+m[1], +m[2], +m[3]];
    for (var i = 0; i < (A.lineStyles || []).length; i++) {
      var want = A.lineStyles[i].rgb;
      if (Math.abs(want[0] - rgb[0]) <= 2 && Math.abs(want[1] - rgb[1]) <= 2 && Math.abs(want[2] - rgb[2]) <= 2)
        return A.lineStyles[i].dashes;
    }
    return [];
  }
  function dashes(series) {          // px, for setLineDash; a series of dots only is never dashed
    if (!series.lines || !series.lines.show) return [];
    var unit = Math.min(Math.max(series.lines.lineWidth || 1, A.dashUnit[0]), A.dashUnit[1]);
    return styleOf(series.color).map(function (n) { return n * unit; });
  }
  function sample(series) {          // the legend's picture of a line: its colour, width and dashes
    var shown = series.lines && series.lines.show, width = Math.min(Math.max(series.lines.lineWidth || 2, 2), 8);
    var svg = shown ? "<line x1='0' y1='8' x2='60' y2='8' stroke='" + series.color + "' stroke-width='" + width +
        "' stroke-dasharray='" + (dashes(series).join(" ") || "none") + "'/>"
      : "<circle cx='30' cy='8' r='5' fill='" + series.color + "'/>";
    return "<svg class='sm-sample' width='60' height='16' style='background:#fff' aria-hidden='true' focusable='false'>" + svg + "</svg>";
  }
  function legendSamples(plot) {
    var options = plot.getOptions(), where = options.legend && options.legend.container ?
      window.jQuery(options.legend.container)[0] : plot.getPlaceholder().find(".legend")[0];
    if (!where) return;
    var named = plot.getData().filter(function (s) { return s.label; });
    where.querySelectorAll("td.legendColorBox").forEach(function (box, i) {
      var s = named[i], want = s ? sample(s) : "";
      if (s && box.__smSample !== want) { box.innerHTML = want; box.__smSample = want; }
    });
  }
  var LINE_STYLES = {
    init: function (plot) {
      plot.hooks.drawSeries.push(function (plot, ctx, series) {
        if (ctx.setLineDash) ctx.setLineDash(A.lineStyles ? dashes(series) : []);
      });
      plot.hooks.draw.push(function (plot, ctx) {
        if (ctx.setLineDash) ctx.setLineDash([]);
        if (A.lineStyles) legendSamples(plot);
      });
    },
    name: "smLineStyles", version: "1"
  };

  // ---- the graphs: a text alternative and a table of the points shown ----

  function number(v) {               // as the graph reading writes a point (browser/graph_reading.py)
    var text = Number(v.toPrecision(4)).toString();
    if (text.indexOf("e") >= 0) text = v.toPrecision(4);
    return text.replace("-", "\u2212");
  }
  function graphObject(el) {         // vpython's graph objects, or GlowScript's graph chosen now (offline page)
    var all = typeof glowObjs !== "undefined" ? glowObjs :
      (window.graph && window.graph.get_selected ? [window.graph.get_selected()] : []);
    for (var i = 0; i < all.length; i++) {
      var g = all[i];
      if (g && g.graph_options && g.container && g.container[0] === el) return g;
    }
    return null;
  }
  function titles(el, plot) {        // {title, x, y}: from the graph object, or the words above it
    var g = graphObject(el) || {}, titlesBy = window.smGraphTitles || {};
    var first = (plot.getData()[0] || {}).label || "";
    var known = titlesBy[first] || {};
    var title = (g.title || known.title || "").split(" \u00b6 ")[0].replace(/<[^>]*>/g, "");
    if (!title) {
      var box = el.previousElementSibling;
      if (box && box.classList.contains("sm-legend")) title = box.querySelector(".sm-title").textContent;
    }
    return {title: title || "graph", x: (g.xtitle || known.xtitle || "x").replace(/<[^>]*>/g, ""),
            y: (g.ytitle || known.ytitle || "y").replace(/<[^>]*>/g, "")};
  }
  function curves(plot) {            // each curve's name and its points shown
    return plot.getData().map(function (s, i) {
      var points = (s.data || []).filter(function (p) { return p && p[0] != null && p[1] != null; });
      return {label: s.label || "curve " + (i + 1), points: points};
    }).filter(function (c) { return c.points.length; });
  }
  function part(title) {              // 'y (m)' -> {name: 'y', unit: ' m'}
    var m = /^(.*?)\s*\(([^()]*)\)\s*$/.exec(title || "");
    return m ? {name: m[1], unit: m[2] && m[2] !== "1" ? " " + m[2] : ""} : {name: title || "", unit: ""};
  }
  function words(el, plot) {
    var t = titles(el, plot), shown = curves(plot), xa = plot.getAxes().xaxis, ya = plot.getAxes().yaxis;
    var x = part(t.x), y = part(t.y);
    var head = t.title + ": " + t.y + " against " + t.x;
    if (!shown.length) return head + ", nothing plotted yet.";
    var last = shown.map(function (c) {
      var p = c.points[c.points.length - 1];
      return c.label + " " + number(p[1]) + y.unit + " at " + x.name + " = " + number(p[0]) + x.unit;
    });
    return head + ". Shown: " + x.name + " from " + number(xa.min) + " to " + number(xa.max) + x.unit + ", " +
           y.name + " from " + number(ya.min) + " to " + number(ya.max) + y.unit + ". Last values: " +
           last.join("; ") + ". The table under the graph lists the points shown.";
  }
  function tableHtml(el, plot) {
    var t = titles(el, plot), esc = function (s) {
      return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;");
    };
    return curves(plot).map(function (c) {
      return "<table class='sm-points'><caption>" + esc(t.title + ": " + c.label) + " (" + c.points.length +
             " points)</caption><thead><tr><th scope='col'>" + esc(t.x) + "</th><th scope='col'>" + esc(t.y) +
             "</th></tr></thead><tbody>" + c.points.map(function (p) {
               return "<tr><td>" + number(p[0]) + "</td><td>" + number(p[1]) + "</td></tr>";
             }).join("") + "</tbody></table>";
    }).join("");
  }
  // The <details> under a graph: after the lines other scripts put right under it (a note, a reading).
  function detailsFor(el) {
    var d = el.__smAlt;
    if (!d) {
      d = el.__smAlt = document.createElement("details");
      d.__smGraph = el;
      d.className = "sm-alt";
      d.innerHTML = "<summary>Table of the points shown</summary>" +
        // it scrolls when long: focusable, so its rows can be scrolled by keyboard (axe: scrollable-region-focusable)
        "<div class='sm-points-box' tabindex='0' role='region' aria-label='Table of the points shown'></div>";
      d.addEventListener("toggle", function () { if (d.open && el.__smPlot) fill(el); });
    }
    var after = el;
    while (after.nextElementSibling && after.nextElementSibling !== d &&
           /\bsm-(note|read)\b/.test(after.nextElementSibling.className)) after = after.nextElementSibling;
    if (el.parentNode && after.nextElementSibling !== d) el.parentNode.insertBefore(d, after.nextSibling);
    return d;
  }
  function fill(el) {
    var d = detailsFor(el), plot = el.__smPlot;
    var name = "Table of the points shown: " + titles(el, plot).title;
    d.querySelector("summary").textContent = name;
    d.querySelector(".sm-points-box").setAttribute("aria-label", name);
    d.querySelector(".sm-points-box").innerHTML = tableHtml(el, plot);
  }
  function described(el) {
    var plot = el.__smPlot;
    if (!plot || !el.isConnected) return;
    var text = words(el, plot);
    el.setAttribute("role", "img");
    if (el.getAttribute("aria-label") !== text) el.setAttribute("aria-label", text);
    var d = detailsFor(el);
    if (d.open || d.querySelector("summary").textContent.indexOf(":") < 0) fill(el);   // an open table follows the graph
  }
  function dropOrphans() {           // a graph taken down (another graph chosen, a new scene) takes its table along
    document.querySelectorAll("details.sm-alt").forEach(function (d) {
      var g = d.__smGraph;
      if (!g || !g.isConnected || g.offsetParent === null) d.remove();
      else detailsFor(g);
    });
  }
  function wrapPlot() {
    var jq = window.jQuery;
    if (!jq || !jq.plot || jq.plot.smAccess) return;
    var plot = jq.plot;
    jq.plot = function (placeholder) {
      var made = plot.apply(this, arguments);
      var el = jq(placeholder)[0];
      if (el) {
        el.__smPlot = made;
        if (!el.__smDue) {            // at most twice a second: a graph is redrawn every frame
          el.__smDue = true;
          setTimeout(function () { el.__smDue = false; described(el); }, 500);
        }
      }
      return made;
    };
    Object.keys(plot).forEach(function (name) { jq.plot[name] = plot[name]; });
    if (plot.plugins && plot.plugins.indexOf(LINE_STYLES) < 0) plot.plugins.push(LINE_STYLES);
    jq.plot.smAccess = true;
  }
  A.describeGraphs = function () {   // now, for a look from outside (the tests)
    document.querySelectorAll(".glowscript-graph").forEach(function (el) { described(el); });
  };

  // ---- the 3-D view, the live region, the sliders ----

  function markView() {
    document.querySelectorAll(".glowscript-canvas-wrapper").forEach(function (box) {
      if (box.getAttribute("role") === "img") return;
      box.setAttribute("role", "img");
      box.setAttribute("aria-label", A.viewLabel || "The 3-D view of the scene. Press D, or Describe, to hear " +
                       "where each mass is and how it moves.");
    });
  }
  function markLive() {              // the description's and the status line's holders read out what they are given
    document.querySelectorAll(".sm-description, .sm-status").forEach(function (text) {
      var holder = text.closest("span[id]") || text;
      if (holder.getAttribute("role") !== "status") {
        holder.setAttribute("role", "status");
        holder.setAttribute("aria-live", "polite");
        holder.setAttribute("aria-atomic", "true");
      }
    });
  }

  // A slider as a screen reader needs it: role, name, range and its value in words with its unit.
  // spec: {label, symbol, unit, texts (a round-value slider's words per place) or decimals}
  function sliderText(spec, value) {
    if (spec.texts) return spec.texts[Math.round(value)] || "";
    var text = Number(Number(value).toFixed(spec.decimals)).toString();
    return spec.symbol + " = " + text + (spec.unit && spec.unit !== "1" ? " " + spec.unit : "");
  }
  A.sliders = function (specs) {
    var all = Array.prototype.slice.call(document.querySelectorAll(".ui-slider")).slice(-specs.length);
    all.forEach(function (el, i) {
      var spec = specs[i], handle = el.querySelector(".ui-slider-handle"), $el = window.jQuery(el);
      if (!handle || el.__smSlider) return;
      el.__smSlider = true;
      var show = function (value) {
        handle.setAttribute("aria-valuenow", String(value));
        handle.setAttribute("aria-valuetext", sliderText(spec, value));
      };
      handle.setAttribute("role", "slider");
      handle.setAttribute("aria-label", spec.label);
      handle.setAttribute("aria-valuemin", String($el.slider("option", "min")));
      handle.setAttribute("aria-valuemax", String($el.slider("option", "max")));
      show($el.slider("option", "value"));
      $el.on("slide slidechange", function (e, ui) { show(ui.value); });
    });
  };

  // vpython's check boxes and menus carry no name: the words beside them are theirs.
  function nameWidgets() {
    document.querySelectorAll("#glowscript input[type=checkbox], #glowscript select, #glowscript input:not([type])")
      .forEach(function (el) {
        if (el.getAttribute("aria-label") || el.labels && el.labels.length) return;
        var text = "";
        if (el.type === "checkbox") {
          var next = el.nextElementSibling;
          text = next ? next.textContent : "";
        } else {
          for (var node = el.previousSibling; node && !text.trim(); node = node.previousSibling) {
            if (node.nodeType === 3) text = node.textContent;
            else break;
          }
        }
        text = text.replace(/\s+/g, " ").trim();
        if (text) el.setAttribute("aria-label", text);
      });
  }

  // Headings to move by (WCAG 1.3.1, 2.4.1, 2.4.6): each graph's title line (browser/page_layout.py)
  // is a level-2 heading; on a page that asks (config.headings: the local page, whose scene name is
  // its h1) so are the Measure panel's button, as an accordion's, and the controls, under a heading
  // heard, not seen.
  function heading(el, level) {
    if (el && el.getAttribute("role") !== "heading") { el.setAttribute("role", "heading"); el.setAttribute("aria-level", String(level)); }
  }
  function markHeadings() {
    document.querySelectorAll(".sm-legend .sm-title").forEach(function (title) { heading(title, 2); });
    if (!A.headings) return;
    var toggle = document.querySelector(".sm-measure-toggle");
    if (toggle && toggle.parentNode.tagName === "SPAN") heading(toggle.parentNode, 2);
    var first = Array.prototype.filter.call(document.querySelectorAll("#glowscript button"), function (b) {
      return /^(Run|Pause)$/.test(b.textContent.trim());
    })[0];
    if (first && !first.parentNode.querySelector(".sm-controls-heading")) {
      var h = document.createElement("h2");
      h.className = "sm-controls-heading sm-unseen";
      h.textContent = "Controls";
      first.parentNode.insertBefore(h, first);
    }
  }

  function tidy() {
    wrapPlot();
    markHeadings();
    dropOrphans();
    markView();
    markLive();
    markShortcuts();
    if (A.nameWidgets) nameWidgets();
  }

  // ---- install once per document; a page built again calls it again with its own config ----

  A.install = function (config) {
    A.keys = config.keys;
    A.viewLabel = config.viewLabel || A.viewLabel;
    A.nameWidgets = !!config.nameWidgets;
    A.headings = !!config.headings;
    A.lineStyles = config.lineStyles || A.lineStyles;
    A.dashUnit = config.dashUnit || A.dashUnit || [2, 4];
    if (config.title) document.title = config.title;
    if (!document.documentElement.getAttribute("lang")) document.documentElement.setAttribute("lang", "en");
    tidy();
    if (A.installed) return;
    A.installed = true;
    window.addEventListener("keydown", onKeyDown, true);   // the window's capture: before anything else on the page
    window.addEventListener("keyup", onKeyUp, true);
    setInterval(tidy, 700);
    var quiet = window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches;
    if (quiet && config.pause) config.pause();
  };

  // ---- the description, filled in the browser (the offline page) from export/description.py's template ----

  // data: description.template_data(); masses: [{who, r, v, centre, step}] (step: {F_net, average,
  // parts: [[label, F]]} or null); t: the clock's text; g: Python's 'g' format (pyG), as the numbers are written.
  A.sentences = function (data, t, masses, count, g) {
    var T = data.template;
    function fill(text, slots) { return text.replace(/\{(\w+)\}/g, function (all, name) { return slots[name]; }); }
    function size(v) { return Math.sqrt(v.reduce(function (s, c) { return s + c * c; }, 0)); }
    function rounded(x) { return g(Math.abs(x), data.digits); }
    function parts(v) {
      var n = size(v);
      if (!(n > data.still)) return [];
      return v.map(function (c, axis) { return [axis, c]; })
        .filter(function (p) { return Math.abs(p[1]) >= data.minor * n; })
        .sort(function (a, b) { return Math.abs(b[1]) - Math.abs(a[1]); });
    }
    function listed(words) {
      return words.length > 1 ? words.slice(0, -1).join(", ") + " and " + words[words.length - 1] : words.join("");
    }
    function offset(d) {
      return listed(parts(d).map(function (p) { return rounded(p[1]) + " m " + data.offset_words[p[0]][p[1] < 0 ? 1 : 0]; }));
    }
    function direction(v) {
      return listed(parts(v).map(function (p) { return data.direction_words[p[0]][p[1] < 0 ? 1 : 0]; }));
    }
    function force(slot, F, slots) {
      var d = direction(F);
      return fill(T[slot], Object.assign({size: rounded(size(F)), direction: d ? " " + d : ""}, slots));
    }
    var said = masses.slice(0, data.masses).map(function (m) {
      var where;
      if (!m.centre) where = fill(T.where_no_equilibrium, {who: m.who, position: m.position});
      else {
        var off = offset(m.r.map(function (c, k) { return c - m.centre[k]; }));
        where = off ? fill(T.where, {who: m.who, offset: off}) : fill(T.at_equilibrium, {who: m.who});
      }
      var d = direction(m.v);
      var text = where + " " + (d ? fill(T.moving, {direction: d, speed: rounded(size(m.v))}) : T.still);
      if (m.step) {
        var each = m.step.parts.filter(function (p) { return size(p[1]) > data.still; })
          .map(function (p) { return force("part", p[1], {label: p[0]}); });
        text += " " + force(m.step.average ? "average" : "step", m.step.F_net, {t: t}) +
                (each.length ? ": " + each.join(", ") : "") + ".";
      }
      return text;
    });
    var more = count > data.masses ? " " + fill(T.more, {count: count - data.masses}) : "";
    return fill(T.time, {t: t}) + " " + said.join(" ") + more;
  };
})();
