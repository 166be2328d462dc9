/* The offline page's tools, as on the local page: how the page sits in the window, the legend
   beside each graph, the energy graph (or phase space, or energy bars, in the graph place under
   the position graph), the error read-out, the Step drawn as vector addition, and the Measure
   panel (stopwatch, period, lines, marker, reading a graph).

   Every number shown is the program's (export/program_page.py: its K, each force's U and W_nc,
   the exact curve's value, p and r after each step) or the file's own set-up's worked out by the
   physics in Python when the file was written (the period, the equilibrium: DATA.measured).
   This script only samples, sums, draws and writes them. */
(function () {
  "use strict";
  var page = window.OfflinePage, DATA = page.DATA, byId = page.byId;
  var TOOLS = DATA.tools;

  function vector(a) { return window.vector(a[0], a[1], a[2]); }
  function rgb(c) { return "rgb(" + c.map(function (x) { return Math.round(255 * x); }).join(",") + ")"; }

  // ---- how the page sits in the window: the view and the controls on the left, the graphs in a
  // column on the right; both grow with the window (a projector's 1920 × 1080 as well) ----

  var layout = page.layout = {};
  layout.sizes = function () {
    var width = document.documentElement.clientWidth, height = window.innerHeight;
    var wide = width >= TOOLS.two_columns_from;
    var left = wide ? Math.round((width - 40) * TOOLS.view_share) : width - 28;
    var right = wide ? width - left - 52 : width - 28;
    var top = byId("main").getBoundingClientRect().top + window.scrollY;
    var below = Math.max(360, height - top - 12);
    var viewHeight = Math.max(220, Math.round(below * (wide ? 0.62 : 0.5)));
    var graphHeight = Math.max(200, Math.round(wide ? (below - 2 * TOOLS.legend_px) / 2 - 24 : below * 0.42));
    // the graph leaves room at its right for half of its last tick label, which flot centres on the axis's end
    return {canvas: {width: left, height: viewHeight}, graph: {width: right - TOOLS.tick_room, height: graphHeight},
            wide: wide, left: left, right: right};
  };
  // The camera's range for a canvas of this size: what export/framing.py's camera_range gives for
  // the picture the local page frames (its width and height, m, with a tenth to spare), at this
  // canvas's own width and height, widened as much as the arrows' scales widened it there.
  // (GlowScript's range is half the picture's smaller side: its height, unless it is taller than wide.)
  layout.range = function (width, height) {
    var camera = DATA.camera, box = camera.box;
    var half = width >= height ? Math.max(box[1], box[0] * height / width) : Math.max(box[0], box[1] * width / height);
    return camera.grow * 0.55 * Math.max(half, 1e-3);
  };
  layout.resized = function () {
    var sizes = layout.sizes(), run = page.current();
    document.body.classList.toggle("narrow", !sizes.wide);
    byId("left").style.width = sizes.left + "px";
    byId("graphs").style.width = sizes.right + "px";
    if (!run) return;
    if (run.scene) {
      run.scene.width = sizes.canvas.width; run.scene.height = sizes.canvas.height;
      run.scene.range = layout.range(sizes.canvas.width, sizes.canvas.height);
    }
    [run.graph, tools.place.graph].forEach(function (g) {   // a graph GlowScript has put on the page
      if (g && g.container && document.body.contains(g.container[0])) {
        g.width = sizes.graph.width; g.height = sizes.graph.height;
      }
    });
  };

  // Each flot graph's legend in a line above it, not on its curves: flot puts it where it is told
  // (legend.container), and the page gives it the element before the graph (as browser/graph_reading.py
  // and export/plain_ticks.py, a wrapper of $.plot).
  (function () {
    var jq = window.jQuery, original = jq.plot;
    jq.plot = function (placeholder, data, options) {
      options = options || {};
      var el = jq(placeholder)[0], holder = el && el.closest(".glowscript-graph, .graph-place") || el;
      if (holder) {
        var legend = holder.previousElementSibling;
        if (!legend || !legend.classList.contains("graph-legend")) {
          legend = document.createElement("div");
          legend.className = "graph-legend";
          holder.parentNode.insertBefore(legend, holder);
        }
        options.legend = Object.assign({}, options.legend || {}, {container: jq(legend), noColumns: 8});
      }
      return original(placeholder, data, options);
    };
    for (var key in original) jq.plot[key] = original[key];
  })();

  // ---- what the tools keep of a run ----

  var tools = {place: {}, samples: [], next: 0, start: null};

  page.hooks.started.push(function (run) {
    tools.samples = [];
    tools.next = 0;
    tools.start = null;
    tools.place = {};
    tools.energy = [];
    tools.exact = [];
    stopwatch.restarted(run);
    hideStep();
  });

  // GlowScript puts each graph under the 3-D canvas when its first point is drawn: the page moves
  // it into the column on the right, the program's position graph above the graph place.
  function placeGraphs(run) {
    var graphs = byId("graphs");
    graphs.textContent = "";
    var slot = document.createElement("div");
    slot.className = "position-slot";
    graphs.appendChild(slot);
    new MutationObserver(function () {
      Array.prototype.slice.call(run.box.querySelectorAll(".glowscript-graph")).forEach(function (el) {
        var place = tools.place.graph && tools.place.graph.container && tools.place.graph.container[0] === el;
        var legend = el.previousElementSibling, into = place ? tools.place.holder : slot;
        if (legend && legend.classList.contains("graph-legend")) into.appendChild(legend);
        into.appendChild(el);
      });
    }).observe(run.box, {childList: true, subtree: true});
  }

  page.hooks.drawn.push(function (run) {
    placeGraphs(run);
    window.smGraphTitles = window.smGraphTitles || {};
    (run.labels.length > 1 ? run.labels : [TOOLS.axis_name]).forEach(function (label) {
      window.smGraphTitles[label] = ["t (s)", TOOLS.axis_name + " (m)"];
    });
    buildPlace(run);
    drawLines(run);
    showMeasured(run);
    layout.resized();
  });

  // Each mass's energy at the start and after each step (the program's K, each force's U, W_nc),
  // and a sample for the graphs every SAMPLE_EVERY s of simulated time once every mass has reported.
  page.hooks.energy.push(function (run, i, n, report) {
    tools.energy[i] = report;
    if (!run.last || i !== run.last.length - 1) return;
    var t = n * run.dt;
    if (t + 1e-9 * run.dt < tools.next) return;
    tools.next = t + TOOLS.sample_every;
    sample(run, t);
  });

  page.hooks.frame.push(function (run) {
    stopwatch.show(run);
    showError(run);
    if (tools.place.kind === "bars") drawBars(run);
  });

  page.hooks.paused.push(function (run) { drawStep(run); });
  page.hooks.resumed.push(function () { hideStep(); });

  // ---- the energy: the program's numbers, summed over the masses ----

  function parts(run) {             // K, each force's U and W_nc, summed over the masses now
    var out = {K: 0, U: {}, W: 0, masses: []};
    tools.energy.forEach(function (e, i) {
      if (!e) return;
      var K = e.K, U = 0;
      out.K += K;
      Object.keys(e.U).forEach(function (force) { out.U[force] = (out.U[force] || 0) + e.U[force]; U += e.U[force]; });
      out.W += e.W;
      out.masses[i] = K + U;
    });
    return out;
  }

  function sample(run, t) {
    var now = parts(run);
    if (tools.start === null) tools.start = now;
    var U = 0;
    Object.keys(now.U).forEach(function (force) { U += now.U[force]; });
    var rest = TOOLS.energy.from_rest ? sum(tools.start.U) : 0;
    var energy = {K: now.K, U: U - rest, E: now.K + U - rest, E_minus_W_nc: now.K + U - rest - now.W};
    var place = tools.place;
    if (place.kind === "energy" && place.curves) {
      if (TOOLS.energy.per_mass) place.curves.forEach(function (curve, i) { curve.plot(t, now.masses[i]); });
      else TOOLS.energy.keys.forEach(function (key, k) { place.curves[k].plot(t, energy[key]); });
    } else if (place.kind === "phase" && place.curves) {
      run.last.forEach(function (state, i) {
        if (place.curves[i]) place.curves[i].plot(state.r[TOOLS.axis], state.p[TOOLS.axis]);
      });
    }
    tools.samples.push({t: t, energy: energy});
  }

  function sum(dict) { return Object.keys(dict).reduce(function (s, key) { return s + dict[key]; }, 0); }

  // ---- the graph place under the position graph: energy graph, phase space or energy bars ----

  function buildPlace(run) {
    var kind = byId("graph-place").value, sizes = layout.sizes().graph;
    var holder = document.createElement("div");
    holder.className = "graph-place";
    byId("graphs").appendChild(holder);
    tools.place = {kind: kind, holder: holder};
    if (kind === "bars") { holder.classList.add("bars"); drawBars(run); return; }
    var titles = kind === "energy" ? ["Energy", "t (s)", "energy (J)"] :
      ["Phase space", TOOLS.axis_name + " (m)", "p" + TOOLS.axis_name + " (kg·m/s)"];
    var g = window.graph({title: titles[0], xtitle: titles[1], ytitle: titles[2], width: sizes.width,
                          height: sizes.height});
    tools.place.graph = g;
    var curves = [];
    if (kind === "energy" && TOOLS.energy.per_mass) {
      run.last.forEach(function (state, i) {
        curves.push(window.gcurve({graph: g, color: vector(TOOLS.colours[i]), width: 3,
                                   label: (run.labels || [])[i] || "mass"}));
      });
    } else if (kind === "energy") {
      TOOLS.energy.keys.forEach(function (key) {
        curves.push(window.gcurve({graph: g, color: vector(TOOLS.energy.colours[key]), width: 3,
                                   label: TOOLS.energy.labels[key]}));
      });
    } else {
      run.last.forEach(function (state, i) {
        curves.push(window.gcurve({graph: g, color: vector(TOOLS.colours[i]), width: 3,
                                   label: (run.labels || [])[i] || "mass"}));
      });
    }
    tools.place.curves = curves;
    window.smGraphTitles = window.smGraphTitles || {};
    curves.forEach(function (curve, k) { window.smGraphTitles[curve.label] = [titles[1], titles[2]]; });
    if (kind === "energy") tools.samples.forEach(function (s) {
      if (TOOLS.energy.per_mass) return;
      TOOLS.energy.keys.forEach(function (key, k) { curves[k].plot(s.t, s.energy[key]); });
    });
  }

  // PhET's bars (browser/energy_bars.py): K, each force's U from the start of the run, what the
  // forces that are not conservative took (−W_nc), and the total, level where energy is kept.
  function drawBars(run) {
    var holder = tools.place.holder;
    if (!holder || !tools.energy.length) return;
    var now = parts(run), start = tools.start || now;
    var bars = [["K", now.K, TOOLS.bars.K]];
    Object.keys(now.U).forEach(function (force, k) {
      bars.push(["U " + force, now.U[force] - (start.U[force] || 0), TOOLS.bars.U[k % TOOLS.bars.U.length]]);
    });
    bars.push(["−W_nc (" + TOOLS.bars.taken_by + ")", -now.W, TOOLS.bars.taken]);
    var total = bars.reduce(function (s, bar) { return s + bar[1]; }, 0);
    bars.push(["total", total, TOOLS.bars.total]);
    var size = Math.max.apply(null, bars.map(function (bar) { return Math.abs(bar[1]); }).concat([tools.barScale || 1e-12]));
    tools.barScale = size;
    holder.innerHTML = "<div class='bars-title'>Energy bars: U from the start of the run (J)</div>" +
      bars.map(function (bar) {
        var share = Math.abs(bar[1]) / size * 50;
        return "<div class='bar'><span class='bar-name'>" + bar[0] + "</span><span class='bar-track'>" +
          "<span class='bar-fill' style='background:" + rgb(bar[2]) + ";width:" + share.toFixed(2) + "%;" +
          (bar[1] < 0 ? "right:50%" : "left:50%") + "'></span></span><span class='bar-value'>" +
          page.numbers.pyG(bar[1], 4).replace("-", "−") + "&nbsp;J</span></div>";
      }).join("");
  }

  byId("graph-place").addEventListener("change", function (e) {
    e.target.blur();
    var run = page.current();
    if (!run) return;
    if (tools.place.holder) tools.place.holder.remove();
    if (tools.place.graph) tools.place.graph.remove && tools.place.graph.remove();
    buildPlace(run);
    layout.resized();
  });

  // ---- the error read-out: the simulation against the program's own exact curve ----

  // A small length as the local page writes it (browser/readout.py length_text): three digits, in
  // the largest of m, mm, µm, nm and pm that keeps it at 1 or more.
  function lengthText(metres, signed) {
    if (!isFinite(metres)) return "not a number";
    var size = Math.abs(metres);
    if (size === 0) return "0\u00a0m";
    var units = [["m", 1], ["mm", 1e-3], ["µm", 1e-6], ["nm", 1e-9], ["pm", 1e-12]], unit = units[0];
    if (size < 0.1) {
      unit = null;
      for (var k = 1; k < units.length; k++) {
        if (Number((size / units[k][1]).toPrecision(3)) >= 1) { unit = units[k]; break; }
      }
      if (!unit) return "less than 1\u00a0pm (round-off)";
    }
    var value = Number((size / unit[1]).toPrecision(3));
    if (value >= 1000 && unit[0] !== "m") { unit = units[units.indexOf(unit) - 1]; value = Number((size / unit[1]).toPrecision(3)); }
    var decimals = Math.max(0, 2 - Math.floor(Math.log10(value)));
    return (metres < 0 ? "−" : signed ? "+" : "") + value.toFixed(decimals) + "\u00a0" + unit[0];
  }
  page.lengthText = lengthText;

  function showError(run) {
    var out = byId("error");
    if (!TOOLS.exact || !run.exact) { out.textContent = ""; return; }
    var errors = [];
    run.last.forEach(function (state, i) {
      var exact = run.exact[i];
      if (exact !== undefined && isFinite(exact)) errors.push(state.r[TOOLS.axis] - exact);
    });
    if (!errors.length) { out.textContent = ""; return; }
    var name = TOOLS.axis_name;
    if (run.last.length === 1)
      out.innerHTML = "error " + name + " − " + name + "<sub>exact</sub> = " + lengthText(errors[0], true);
    else
      out.textContent = "largest |error| against the exact solutions = " +
        lengthText(Math.max.apply(null, errors.map(Math.abs)), false);
  }

  // ---- a Step drawn as vector addition beside each mass (browser/arrows3d.py's show_step) ----

  function hideStep() { (tools.stepArrows || []).forEach(function (a) { a.visible = false; }); }

  function drawStep(run) {
    hideStep();
    if (!run.scene) return;
    tools.stepArrows = [];
    var radius = DATA.measured.radius, scale = 1 / TOOLS.step.p_unit;
    for (var i = 0; i < Math.min(run.steps.length, DATA.step.masses); i++) {
      var found = page.stepNumbers(run, i);
      if (!found) continue;
      var s = found.step;
      var a_i = s.p_i.map(function (c) { return c * scale; }), a_dp = found.impulse.map(function (c) { return c * scale; });
      var a_f = s.p_f.map(function (c) { return c * scale; });
      var across = Math.abs(a_f[0]) > Math.abs(a_f[1]) ? [0, 1, 0] : [1, 0, 0];
      var at = s.r_f.map(function (c, k) { return c + TOOLS.step.aside * radius * across[k]; });
      var tip = at.map(function (c, k) { return c + a_i[k]; });
      var beside = at.map(function (c, k) { return c + TOOLS.step.apart * radius * across[k]; });
      [["p_i", at, a_i], ["F_net", tip, a_dp], ["p", beside, a_f]].forEach(function (made) {
        tools.stepArrows.push(window.arrow({canvas: run.scene, pos: vector(made[1]), axis: vector(made[2]),
                                            color: vector(TOOLS.step.colours[made[0]]),
                                            shaftwidth: 0.2 * radius}));
      });
    }
  }

  // ---- the Measure panel ----

  // A stopwatch on simulated time (browser/stopwatch.py's rule): reading = held + (t − started)
  // while running; Lap notes the reading; a run that restarts keeps what was counted.
  var stopwatch = {running: false, held: 0, started: 0, laps: [], t: 0};
  stopwatch.now = function (run) { return run ? run.n * run.dt : 0; };
  stopwatch.reading = function (t) { return stopwatch.held + (stopwatch.running ? t - stopwatch.started : 0); };
  stopwatch.press = function () {
    var t = stopwatch.now(page.current());
    if (stopwatch.running) stopwatch.held = stopwatch.reading(t); else stopwatch.started = t;
    stopwatch.running = !stopwatch.running;
    byId("stopwatch-start").textContent = stopwatch.running ? "Stop (S)" : "Start (S)";
  };
  stopwatch.lap = function () {
    if (stopwatch.running) stopwatch.laps.push(stopwatch.reading(stopwatch.now(page.current())));
  };
  stopwatch.clear = function () {
    stopwatch.running = false; stopwatch.held = 0; stopwatch.started = 0; stopwatch.laps = [];
    byId("stopwatch-start").textContent = "Start (S)";
  };
  stopwatch.restarted = function () {
    if (stopwatch.running) { stopwatch.held = stopwatch.reading(stopwatch.t); stopwatch.started = 0; }
  };
  stopwatch.show = function (run) {
    var t = stopwatch.now(run), decimals = Math.max(2, page.numbers.timeDecimals(run.dt));
    stopwatch.t = t;
    var text = stopwatch.reading(t).toFixed(decimals) + "\u00a0s";
    if (stopwatch.laps.length) {
      var shown = stopwatch.laps.slice(-4), first = stopwatch.laps.length - shown.length + 1;
      text += "   laps: " + shown.map(function (lap, k) { return (first + k) + ": " + lap.toFixed(decimals) + "\u00a0s"; }).join(", ");
    }
    if (byId("stopwatch").textContent !== text) byId("stopwatch").textContent = text;
  };
  page.stopwatch = stopwatch;

  // What the tools show now, for a look from outside (the tests): the Step's arrows and the lines drawn.
  page.toolsState = function () {
    var run = page.current() || {}, lines = {};
    ["natural", "equilibrium", "marker"].forEach(function (kind) {
      lines[kind] = (run.lines && run.lines[kind] || []).filter(function (o) { return o.visible; }).length;
    });
    return {stepArrows: (tools.stepArrows || []).filter(function (a) { return a.visible; }).length, lines: lines,
            place: tools.place.kind};
  };

  function ownSetUp(run) {
    return run.setup.integrator === DATA.integrator && Object.keys(DATA.constants).every(function (name) {
      return run.setup.values[name] === DATA.constants[name].own;
    });
  }

  // The natural-length, equilibrium and marker lines across the motion's axis (browser/reference_lines.py):
  // the natural length where each spring would rest without a load (its anchor, L0 towards the
  // mass), the equilibrium where the forces balance (physics/equilibrium.py, the file's own set-up),
  // and a marker a click in the picture moves.
  function drawLines(run) {
    run.lines = {natural: [], equilibrium: [], marker: []};
    var r = DATA.measured.radius, axis = TOOLS.axis, across = axis === 1 ? [1, 0, 0] : [0, 1, 0];
    function line(kind, at, text) {
      var size = across.map(function (a) { return a ? 2 * TOOLS.lines.half_length * r : 0.06 * r; });
      var made = [window.box({canvas: run.scene, pos: vector(at), size: window.vector(size[0], size[1], 0.06 * r),
                              color: vector(TOOLS.lines.colours[kind])})];
      if (text) made.push(window.label({canvas: run.scene, pos: vector(at.map(function (c, k) {
        return c + TOOLS.lines.half_length * r * across[k]; })), text: text, height: 18, box: false, line: false,
        color: vector(TOOLS.lines.colours[kind]), xoffset: 10, yoffset: 0, align: "left", opacity: 0}));
      run.lines[kind] = run.lines[kind].concat(made);
    }
    var natural = TOOLS.lines.natural, centres = DATA.measured.equilibrium;
    if (natural && run.ran.L0 !== undefined) natural.forEach(function (mass, i) {
      if (i >= DATA.step.masses) return;
      var at = mass.anchor.map(function (c, k) { return c + run.ran.L0 * mass.direction[k]; });
      line("natural", at, i === 0 ? "natural length" : "");
    });
    if (centres && ownSetUp(run)) centres.slice(0, DATA.step.masses).forEach(function (c, i) {
      line("equilibrium", c, i === 0 ? "equilibrium" : "");
    });
    tools.marker = null;
    run.scene.bind("click", function () {
      if (!byId("line-marker").checked) return;
      var at = run.scene.mouse.pos, where = [at.x, at.y, at.z];
      run.lines.marker.forEach(function (o) { o.visible = false; });
      run.lines.marker = [];
      var place = DATA.measured.equilibrium ? DATA.measured.equilibrium[0].slice() : run.last[0].r.slice();
      place[axis] = where[axis];
      line("marker", place, TOOLS.axis_name + " = " + page.numbers.pyG(where[axis], 4) + " m");
      tools.marker = where[axis];
      showLines(run);
    });
    showLines(run);
  }

  function showLines(run) {
    ["natural", "equilibrium", "marker"].forEach(function (kind) {
      var on = byId("line-" + kind).checked;
      (run.lines && run.lines[kind] || []).forEach(function (o) { o.visible = on; });
    });
    var note = byId("line-equilibrium").checked && !ownSetUp(run) ?
      "the equilibrium is drawn for the file's own set-up only (write a file with these constants to see it)" : "";
    byId("lines-note").textContent = note;
  }

  function showMeasured(run) {
    var own = ownSetUp(run), on = byId("show-period").checked;
    byId("period").hidden = !on;
    byId("period").textContent = !own ? "the period is measured for the file's own set-up only (Reset to its " +
      "values, or write a file with these constants: Copy link, or --set)" :
      "measured over the first " + page.numbers.pyG(DATA.measured.window, 6) + " s:\n" + DATA.measured.period.join("\n") +
      (DATA.measured.formula_note ? "\nno formula: " + DATA.measured.formula_note : "");
  }

  byId("measure-toggle").addEventListener("click", function (e) {
    var box = byId("measure"), open = box.hidden;
    box.hidden = !open;
    e.target.textContent = open ? "Measure ▾" : "Measure ▸";
    e.target.setAttribute("aria-expanded", open ? "true" : "false");
    e.target.blur();
  });
  byId("stopwatch-start").addEventListener("click", function (e) { stopwatch.press(); e.target.blur(); });
  byId("stopwatch-lap").addEventListener("click", function (e) { stopwatch.lap(); e.target.blur(); });
  byId("stopwatch-clear").addEventListener("click", function (e) { stopwatch.clear(); e.target.blur(); });
  byId("show-period").addEventListener("change", function () { var run = page.current(); if (run) showMeasured(run); });
  ["natural", "equilibrium", "marker"].forEach(function (kind) {
    byId("line-" + kind).addEventListener("change", function () { var run = page.current(); if (run) showLines(run); });
  });

  // S, L and C press the stopwatch's buttons (export/page_access.js, export/page_keys.py).
  page.ownSetUp = ownSetUp;

})();
