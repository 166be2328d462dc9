/* The offline page's own script: it runs the handed-out Web VPython program in GlowScript 3.2 and
   puts the page's controls around it. export/offline_page.py writes it into the page, with the
   data it reads (#offline-data): the program for each integrator, the constants this file may
   change and over what range, the sliders, the arrows and the Step read-out's layout.

   The physics is the program's, and only the program's: this script never steps anything. It
   owns the timing (the program waits at rate() while paused; Step lets one step through), starts
   the program again for Reset or a new set-up (the constants written into its constants block),
   shows and hides the arrows the program drew, and writes out a Step with the numbers the
   program reports (export/program_page.py), in export/step_update.py's layout and digits.

   A set-up can come from the address: vertical.html#k=60&dt=0.05&integrator=rk4, `--set`'s
   grammar. Each value is read as a plain decimal number, checked against its constant's declared
   range and the range this file can run; nothing in the address is ever run as code. Any problem
   is one line on the page, and the file's own set-up runs. */
// The compiled program, evaluated where its free names rate, GSprint (its print) and offline_page
// are the run's own (a script of its own, not in strict mode, as GlowScript's own page runs it).
window.offlineProgram = function (compiled, rate, GSprint, offline_page, canvas, graph) {
  return eval(compiled + "\n;__main__");
};

(function () {
  "use strict";
  var DATA = JSON.parse(document.getElementById("offline-data").textContent);
  var byId = function (id) { return document.getElementById(id); };

  // ---- numbers, written as the command line writes them (export/step_update.py) ----

  // Python's format(x, '.<digits>g') for a finite x: toExponential rounds correctly except at an
  // exact tie, which it rounds away from zero where Python rounds to the even digit.
  function pyG(x, digits) {
    if (x === 0) return Object.is(x, -0) ? "-0" : "0";
    var size = Math.abs(x);
    var parts = size.toExponential(digits - 1).split("e");
    var exact = size.toPrecision(100).replace(".", "").replace(/e.*$/, "").replace(/^0+/, "");
    var tail = exact.slice(digits);
    if (/^50*$/.test(tail) && "02468".indexOf(exact[digits - 1]) >= 0) {   // a tie: keep the even digit
      var power = Number(size.toExponential(digits + 20).split("e")[1]);
      parts = [exact[0] + (digits > 1 ? "." + exact.slice(1, digits) : ""), String(power)];
    }
    var mantissa = parts[0], exponent = Number(parts[1]);
    var text;
    if (exponent < -4 || exponent >= digits) {
      mantissa = mantissa.indexOf(".") >= 0 ? mantissa.replace(/0+$/, "").replace(/\.$/, "") : mantissa;
      text = mantissa + "e" + (exponent < 0 ? "-" : "+") + (Math.abs(exponent) < 10 ? "0" : "") + Math.abs(exponent);
    } else {
      var all = mantissa.replace(".", "");
      if (exponent < 0) text = "0." + "0".repeat(-1 - exponent) + all;
      else text = all.slice(0, exponent + 1) + (all.length > exponent + 1 ? "." + all.slice(exponent + 1) : "");
      if (text.indexOf(".") >= 0) text = text.replace(/0+$/, "").replace(/\.$/, "");
    }
    return (x < 0 ? "-" : "") + text;
  }

  var NO_VALUE = "(no value)";
  function number(x) {                       // step_update.number: 6 digits, no '-0'
    if (!isFinite(x)) return NO_VALUE;
    var text = pyG(x, 6);
    return text === "-0" ? "0" : text;
  }
  function clean(x) { return isFinite(x) ? Number(pyG(x, 15)) : x; }   // export/numbers.py's clean
  function vectorText(v, unit) {             // step_update.vector
    var size = Math.max.apply(null, v.map(Math.abs));
    var text = "< " + v.map(function (c) { return number(Math.abs(c) < 1e-12 * size ? 0 : c); }).join(", ") + " >";
    return unit ? text + " " + unit : text;
  }
  function shown(v, unit) { return vectorText(v.map(clean), unit); }   // step_update.shown
  function timeDecimals(dt) {                // export/numbers.py
    var text = pyG(dt, 15);
    if (text.indexOf("e") >= 0) {
      var parts = text.split("e");
      return Math.max(0, (parts[0].split(".")[1] || "").length - Number(parts[1]));
    }
    return (text.split(".")[1] || "").length;
  }
  function cleanTime(t, dt) { return clean(Number(t.toFixed(Math.min(100, timeDecimals(dt))))); }
  window.offlineNumbers = {pyG: pyG, number: number, vectorText: vectorText, shown: shown,
                           timeDecimals: timeDecimals, cleanTime: cleanTime};   // for the tests

  // ---- the set-up: the file's own, the address's, the sliders' ----

  var DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;

  function describe(value, unit) { return pyG(value, 6) + (unit && unit !== "1" ? " " + unit : ""); }

  // A constant's value from the address, or the one-line reason it cannot be used (as --set says it).
  function checked(name, text) {
    var declared = DATA.constants[name];
    if (declared === undefined) {
      if (DATA.all_constants.indexOf(name) >= 0)
        return {problem: name + " cannot be set from the address in this file; write a file with it: " + command(name, text)};
      return {problem: "unknown constant '" + name + "' in the address (known: " + DATA.all_constants.join(", ") + ")"};
    }
    text = text.trim();
    if (!DECIMAL.test(text)) return {problem: name + " needs a number (got '" + text + "')"};
    var value = Number(text);
    var mantissa = text.toLowerCase().split("e")[0];
    if (value === 0 && /[1-9]/.test(mantissa))
      return {problem: name + " = " + text + " is too small for the computer to tell from 0; write 0 to switch it off"};
    var unit = declared.unit;
    var inside = (declared.above_low ? value > declared.low : value >= declared.low) && value <= declared.high &&
                 (!declared.whole || value === Math.round(value));
    if (!isFinite(value) || !inside)
      return {problem: name + " must be " + declared.words + " (got " + describe(value, unit) + ")"};
    if (value !== 0 && Math.abs(value) < DATA.smallest)
      return {problem: name + " must be 0 or at least " + DATA.smallest + (unit && unit !== "1" ? " " + unit : "") +
                       " in size (got " + describe(value, unit) + ")"};
    if (value < declared.file_low || value > declared.file_high)
      return {problem: name + " = " + describe(value, unit) + " is outside what this file can run (" +
                       describe(declared.file_low, "") + " to " + describe(declared.file_high, unit) +
                       "); write a file for it: " + command(name, text)};
    return {value: value};
  }

  function command(name, text) {
    return "python main.py " + DATA.scene + " --html " + DATA.scene + ".html --set " + name + "=" + text;
  }

  // The set-up in the address (`#k=60&dt=0.05&integrator=rk4`): {values, integrator} or {problem}.
  function fromAddress(hash) {
    var values = {}, integrator = DATA.integrator;
    var text = hash.replace(/^#/, "");
    if (!text) return {values: values, integrator: integrator};
    var parts = text.split("&");
    for (var i = 0; i < parts.length; i++) {
      if (!parts[i]) continue;
      var part;
      try { part = decodeURIComponent(parts[i].replace(/\+/g, " ")); }
      catch (e) { return {problem: "the address's set-up cannot be read (a bad % code in '" + parts[i] + "')"}; }
      var at = part.indexOf("=");
      if (at <= 0) return {problem: "the address's set-up needs NAME=VALUE, like #k=25 (got '" + part + "')"};
      var name = part.slice(0, at).trim(), value = part.slice(at + 1);
      if (name === "integrator") {
        if (DATA.fixed_methods)
          return {problem: "scene '" + DATA.scene + "' steps its masses with " + DATA.fixed_methods.join(", ") +
                           ", one each, so integrator=" + value + " would do nothing; leave it out"};
        if (!Object.prototype.hasOwnProperty.call(DATA.programs, value))
          return {problem: "integrator must be one of " + Object.keys(DATA.programs).join(", ") + " (got '" + value + "')"};
        integrator = value;
        continue;
      }
      var read = checked(name, value);
      if (read.problem) return {problem: read.problem};
      values[name] = read.value;
    }
    return {values: values, integrator: integrator};
  }

  // The address's fragment for a set-up: what differs from the scene's defaults.
  function fragment(setup) {
    var parts = [];
    Object.keys(DATA.constants).forEach(function (name) {
      var value = setup.values[name];
      if (value !== DATA.constants[name].scene_default) parts.push(name + "=" + String(value));
    });
    if (setup.integrator !== DATA.scene_integrator) parts.push("integrator=" + setup.integrator);
    return parts.join("&");
  }

  // The program for a set-up: the file's program for its integrator, with each constant that
  // differs written into its line of the constants block (`k = 60   # N/m: ...`).
  function programFor(setup) {   // with the forces the Add a force box adds (export/force_box.js)
    var own = window.offlineForces ? window.offlineForces.program(setup.integrator) : DATA.programs[setup.integrator];
    return withConstants(own, setup);
  }
  function withConstants(text, setup) {
    var lines = text.split("\n");
    Object.keys(setup.values).forEach(function (name) {
      if (setup.values[name] === DATA.constants[name].written) return;
      var at = lines.findIndex(function (line) { return line.indexOf(name + " = ") === 0; });
      if (at < 0) throw new Error("the program has no line for " + name);
      var match = /^(\S+ = )(.*?)((\s+)# .*)?$/.exec(lines[at]);
      var literal = String(setup.values[name]);
      var room = match[2].length + (match[4] || " ").length - 1;
      lines[at] = match[1] + literal + (match[3] ? " ".repeat(Math.max(1, room - literal.length + 1)) +
                                        match[3].replace(/^\s+/, "") : "");
    });
    return lines.join("\n");
  }
  window.offlineProgramFor = programFor;   // for the tests

  // ---- one run of the program ----

  var current = null;              // the run now; a run replaced stops at its next rate()
  // with prefers-reduced-motion the page opens paused, its first frame drawn (Run starts it)
  var paused = !!(window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches), steps = 0, release = null, speed = 1;
  var jump = null, jumps = 0, jumpsDrawn = 0;   // the jump under way ({run, n}), jumps done, and drawn
  var compiled = {};               // program text -> GlowScript's JavaScript

  function holdUntilAsked() { return new Promise(function (resolve) { release = resolve; }); }
  function letGo() { if (release) { var r = release; release = null; r(); } }

  // What the program's rate(1/dt) is in one run: the page's clock. Simulated time runs at speed ×
  // wall time: a step not yet due waits; behind, the program steps on, letting the page draw every
  // YIELD_MS, or after as long as the last drawing took where that is longer, so the physics keeps
  // at least half the time (GlowScript's own rate waits for every drawing, so a slow graphics card
  // slowed the physics down with it); more than LAG_S behind (a tab the browser froze), the clock slips
  // instead of racing to catch up. Paused, it holds the program here until Run or Step; a replaced
  // run is held for good (its promise never settles, so that run ends here).
  var YIELD_MS = 30, LAG_S = 0.25;
  function wait(ms) { return new Promise(function (resolve) { setTimeout(resolve, ms); }); }

  // Jump to t: the run steps on to the jump's step without waiting and without drawing (rate()
  // returns at once), letting the page breathe every JUMP_YIELD_MS on a long jump; there it is
  // paused, and drawn once (browser/jump.py is the local page's).
  var JUMP_YIELD_MS = 1000;

  function rateFor(run) {
    return async function (perSecond) {
      for (;;) {                     // a jump asked while held goes on from the hold
        if (jump && jump.run === run && run === current) {
          if (run.n < jump.n) {
            if (performance.now() - jump.breathed > JUMP_YIELD_MS) { await wait(0); jump.breathed = performance.now(); }
            return;
          }
          jumped(run);
        }
        if (!(run === current && paused && steps === 0)) break;
        if (run.stepped) { showStep(run); run.stepped = false; }
        run.clock = null;
        await holdUntilAsked();
      }
      if (run !== current) return new Promise(function () {});
      if (paused) {                  // Step: this one step, then back to the hold above
        steps -= 1;
        run.stepped = true;
        return;
      }
      var now = performance.now(), rate = perSecond * speed;
      var clock = run.clock || (run.clock = {wall: now, steps: 0, drawn: now});
      clock.steps += 1;
      var due = (now - clock.wall) / 1000 * rate;
      if (due < clock.steps - 1) await wait((clock.steps - 1 - due) / rate * 1000);
      else if (now - clock.drawn > Math.max(YIELD_MS, clock.drawing || 0)) {
        var asked = performance.now();
        await wait(0);                 // the page draws: as long as it takes, the physics gets as long
        clock.drawing = performance.now() - asked;
      } else return;
      clock.drawn = performance.now();
      if ((clock.drawn - clock.wall) / 1000 * rate - clock.steps > LAG_S * rate)
        clock.wall = clock.drawn - clock.steps / rate * 1000;
      if (run !== current) return new Promise(function () {});
    };
  }

  function printFor(run) {        // the program's print(): its answer, into the page's answer box
    return function () {
      if (run !== current) return;
      var text = Array.prototype.slice.call(arguments).map(String).join(" ");
      run.printed.push(text);
      byId("answer").textContent = run.printed.join("\n");
    };
  }

  function vec(v) { return [v.x, v.y, v.z]; }
  function flat(list) {
    return Array.isArray(list) ? list.reduce(function (all, x) { return all.concat(flat(x)); }, []) : [list];
  }

  function pageFor(run) {          // the object the program asks for: `page = offline_page()`
    var scene = run.scene = window.canvas.selected, camera = DATA.camera, centre = camera.centre;
    scene.autoscale = false;         // the local page's framing (export/framing.py), not GlowScript's zoom to fit
    scene.fov = camera.fov;
    scene.forward = window.vector(0, -camera.pitch, -1);
    scene.center = window.vector(centre[0], centre[1], centre[2]);
    scene.range = camera.range;
    return {
      drawn: function (balls, pos, p, arrows) {
        if (run !== current) return;
        run.balls = flat(balls);
        run.arrows = {};   // a Python dict in the program: RapydScript's, with its items in .jsmap
        DATA.arrows.kinds.forEach(function (kind) {
          var objects = arrows.jsmap ? arrows.jsmap.get(kind) : arrows[kind];
          if (objects !== undefined) run.arrows[kind] = flat(objects);
        });
        run.last = pos.map(function (r, i) { return {r: vec(r), p: vec(p[i])}; });
        run.graph = window.graph.get_selected();
        showArrows(run);
        drawEquilibrium(run);
        showMeasured(run);
        if (window.offlineForces) window.offlineForces.drawn(run);
      },
      stepped: function (i, n, m, F, p, r, terms) {
        if (run !== current) return;
        var before = run.last[i];
        run.steps[i] = {n: n, m: m, F: vec(F), p_i: before.p, r_i: before.r, p_f: vec(p), r_f: vec(r),
                        terms: (terms || []).map(vec)};
        run.last[i] = {r: run.steps[i].r_f, p: run.steps[i].p_f};
        if (i === 0) run.n = n;
        if (window.offlineForces) window.offlineForces.stepped(run, run.steps[i]);
      }
    };
  }

  function start(setup) {
    var text = programFor(setup);
    if (!compiled[text]) compiled[text] = compile(text);
    var old = current;
    var run = {setup: setup, printed: [], steps: [], n: 0, stepped: false, dt: setup.values.dt};
    current = run;
    steps = 0;
    letGo();                        // a held run sees it was replaced, and stops
    if (old) retire(old);
    byId("answer").textContent = "";
    byId("step").textContent = "";
    byId("program-text").textContent = text;
    var box = document.createElement("div");
    box.className = "glowscript";
    byId("view").appendChild(box);
    run.box = box;
    window.__context = {glowscript_container: $(box)};
    // the compiled program's free names rate, GSprint (its print) and offline_page are this run's
    var sizes = viewSizes();
    var main = window.offlineProgram(compiled[text], rateFor(run), printFor(run), function () { return pageFor(run); },
                                     sized(window.canvas, sizes.canvas), sized(window.graph, sizes.graph));
    main().then(function () {
      run.ended = true;
      if (jump && jump.run === run) jumped(run);   // the program ended before the jump's t
    }, function (error) {
      if (run === current) say("The program stopped: " + String(error).split("\n")[0]);
    });
    showLink(setup);
  }

  // GlowScript's compiler (RScompiler, kept as text in #compiler) compiles one program per run of
  // its file, as GlowScript's own editor loads the file again for each run: run it, then compile.
  function compile(text) {
    var script = document.createElement("script");
    script.textContent = byId("compiler").textContent;
    document.head.appendChild(script);
    script.remove();
    return window.glowscript_compile(text, {lang: "vpython", version: "3.2"});
  }

  function retire(run) {           // the replaced run's canvas stops drawing and leaves the page
    try { if (run.scene) { run.scene.visible = false; run.scene.remove(); } } catch (e) { /* already gone */ }
    if (run.box) run.box.remove();
  }

  // ---- the equilibrium and the period: the file's own set-up's, from the physics the local page
  // uses (export/offline_page.py's measured), shown while that set-up runs ----

  function ownSetUp(run) {
    return run.setup.integrator === DATA.integrator && Object.keys(DATA.constants).every(function (name) {
      return run.setup.values[name] === DATA.constants[name].written;
    });
  }

  function drawEquilibrium(run) {   // a thin line across each mass's equilibrium, the first one named
    var lesson = DATA.measured, centres = lesson.equilibrium;
    run.equilibrium = [];
    if (!centres || !ownSetUp(run)) return;
    var r = lesson.radius, across = lesson.axis === 1 ? [1, 0, 0] : [0, 1, 0];
    centres.slice(0, DATA.step.masses).forEach(function (c, i) {
      var size = across.map(function (a) { return a ? 5 * r : 0.08 * r; });
      var at = window.vector(c[0], c[1], c[2]);
      run.equilibrium.push(window.box({pos: at, size: window.vector(size[0], size[1], 0.08 * r),
                                       color: window.vector(0.8, 0.8, 0.8)}));
      if (i === 0) run.equilibrium.push(window.label({pos: at.add(window.vector(2.5 * r * across[0], 2.5 * r * across[1], 0)),
        text: "equilibrium", height: 18, color: window.vector(0.8, 0.8, 0.8), box: false, line: false,
        xoffset: 12, yoffset: 0, align: "left"}));
    });
    showMeasured(run);
  }

  function showMeasured(run) {
    var own = ownSetUp(run), lines = DATA.measured.period;
    var equilibriumOn = byId("show-equilibrium").checked, periodOn = byId("show-period").checked;
    (run.equilibrium || []).forEach(function (object) { object.visible = equilibriumOn && own; });
    byId("period").hidden = !(periodOn && own);
    byId("period").textContent = "measured over the first " + pyG(DATA.measured.window, 6) + " s:\n" + lines.join("\n") +
      (DATA.measured.formula_note ? "\nno formula: " + DATA.measured.formula_note : "");
    byId("measure-note").textContent = (equilibriumOn || periodOn) && !own ?
      "shown for the file's own set-up only; write a file with these constants (Copy link, or --set) to see them" : "";
  }

  // ---- the Step read-out: export/step_update.py's layout, filled with the program's numbers ----

  function showStep(run) {
    var blocks = [];
    var count = Math.min(run.steps.length, DATA.step.masses);
    for (var i = 0; i < count; i++) {
      var s = run.steps[i];
      if (!s) continue;
      var method = DATA.fixed_methods ? DATA.fixed_methods[i] : run.setup.integrator;
      var layout = DATA.step.layouts[method], dt = run.setup.values.dt;
      var F = DATA.step.kicks_once[method] ? s.F : s.p_f.map(function (pf, k) { return (pf - s.p_i[k]) / dt; });
      var velocity = {v_f: s.p_f.map(function (c) { return c / s.m; }), v_i: s.p_i.map(function (c) { return c / s.m; })};
      var values = {t: number(cleanTime(s.n * dt, dt)), F_net: shown(F), p_i: shown(s.p_i),
                    impulse: shown(F.map(function (c) { return c * dt; })), p_f: shown(s.p_f),
                    v_f: shown(velocity.v_f), r_i: shown(s.r_i),
                    drift: shown(velocity[layout.drift].map(function (c) { return c * dt; })), r_f: shown(s.r_f)};
      var lines = layout.lines.map(function (line) {
        return line.replace(/\{(\w+)\}/g, function (all, slot) { return values[slot]; });
      });
      blocks.push((run.last.length > 1 ? DATA.step.labels[i] + "\n" : "") + lines.join("\n"));
    }
    var more = run.last.length > count ? "\n(and " + (run.last.length - count) + " more masses)" : "";
    byId("step").textContent = blocks.join("\n") + more;
    sayMotion(run);
  }

  // ---- the motion in words: export/description.py's template, filled with the program's numbers ----

  function sayMotion(run) {
    var D = DATA.describe, dt = run.setup.values.dt, n = run.n || 0;
    var t = (n * dt).toFixed(Math.min(100, Math.max(2, timeDecimals(dt))));
    var centres = ownSetUp(run) ? DATA.measured.equilibrium : null;
    var masses = (run.last || []).map(function (now, i) {
      var s = run.steps[i] && run.steps[i].n === n ? run.steps[i] : null;
      var m = s ? s.m : (run.setup.values.m !== undefined ? run.setup.values.m : D.m[i]);
      var method = DATA.fixed_methods ? DATA.fixed_methods[i] : run.setup.integrator;
      var step = null;
      if (s) {
        var once = DATA.step.kicks_once[method];
        step = {average: !once, parts: once ? s.terms.map(function (F, k) { return [D.labels[k], F]; }) : [],
                F_net: once ? s.F : s.p_f.map(function (pf, k) { return (pf - s.p_i[k]) / dt; })};
      }
      return {who: run.last.length > 1 ? D.template.many.replace("{label}", DATA.step.labels[i]) : D.template.one,
              r: now.r, v: now.p.map(function (c) { return c / m; }), centre: centres ? centres[i] : null, step: step,
              position: "< " + now.r.map(function (c) { return pyG(c, D.digits); }).join(", ") + " >"};
    });
    byId("description").textContent = window.smAccess.sentences(D, t, masses, masses.length, pyG);
  }

  // ---- the controls ----

  var setup = null;

  function say(text) { byId("status").textContent = text; }

  function showRunButton() { byId("run").textContent = paused ? "Run" : "Pause"; }

  function toggle() { paused = !paused; showRunButton(); if (current) current.clock = null; if (!paused) letGo(); }
  function step() {
    if (!paused) { paused = true; showRunButton(); return; }
    steps += 1;
    letGo();
  }
  function reset() { start(setup); }

  // The time typed in the box, s ("2.5", "2.5 s"), or the one-line reason it cannot be one.
  function jumpTime(text) {
    var found = /^\s*([+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?)\s*s?\s*$/.exec(text);
    if (!found) return {problem: "jump to t: '" + text.trim().slice(0, 40) + "' is not a time in seconds; type a number such as 2.5"};
    var t = Number(found[1]);
    if (!isFinite(t)) return {problem: "jump to t: " + found[1] + " s is not a time the run can reach; type a number such as 2.5"};
    if (t < 0) return {problem: "jump to t: the run starts at t = 0 s, so it cannot show t = " + pyG(t, 6) + " s"};
    return {t: t};
  }

  // Jump to the box's t: the first step at or after it (as --headless and the program's n_until
  // count), from t = 0 again if that is before now; paused there.
  function jumpTo(text) {
    var asked = jumpTime(text);
    if (asked.problem) { say(asked.problem); return; }
    var dt = setup.values.dt, n = Math.max(0, Math.ceil(asked.t / dt - 1e-9));
    if (!current || n < current.n) start(setup);
    paused = true;
    steps = 0;
    showRunButton();
    byId("step").textContent = "";
    jump = {run: current, n: n, breathed: performance.now()};
    if (current.ended) jumped(current);
    else letGo();
  }

  function jumped(run) {           // the jump is over: paused where it ended, then drawn once
    var asked = jump.n;
    jump = null;
    jumps += 1;
    var done = jumps;
    run.clock = null;
    if (run.n < asked) say("jump to t: the program stops at t = " + (run.n * run.dt).toFixed(Math.max(2, timeDecimals(run.dt))) +
                           " s (its t_end), so the page shows that");
    else say("");
    window.requestAnimationFrame(function () {           // this frame draws the run where it is,
      window.requestAnimationFrame(function () { jumpsDrawn = Math.max(jumpsDrawn, done); });   // and it has
    });
  }

  function showArrows(run) {
    var any = false;
    DATA.arrows.kinds.forEach(function (kind) {
      var on = byId("arrow-" + kind).checked;
      any = any || on;
      (run.arrows && run.arrows[kind] || []).forEach(function (object) { object.visible = on; });
    });
    (run.balls || []).forEach(function (ball) { ball.opacity = any ? DATA.arrows.see_through : 1; });
  }

  // The 3-D view and the graph under it fill the left of the window: the view takes what the panel
  // leaves of the width and half the height below the title, the graph the rest.
  function viewSizes() {
    var width = Math.max(320, Math.min(window.innerWidth - byId("panel").offsetWidth - 48, 1200));
    var below = window.innerHeight - byId("view").getBoundingClientRect().top - 12;
    var height = Math.max(200, Math.round(below * 0.52));
    return {canvas: {width: width, height: height}, graph: {width: width, height: Math.max(200, below - height - 30)}};
  }

  // GlowScript's canvas() or graph(), made at the page's size unless the program gives one.
  function sized(make, size) {
    var made = function (options) { return make(Object.assign({}, size, options || {})); };
    Object.setPrototypeOf(made, make);
    return made;
  }

  function sizeView(run) {         // after a resize: the 3-D view follows (the graph keeps its size)
    var size = viewSizes().canvas;
    if (run.scene) { run.scene.width = size.width; run.scene.height = size.height; }
  }

  function showTime() {
    if (current) {
      var dt = current.setup.values.dt;
      var t = current.n * dt;
      byId("time").textContent = "t = " + t.toFixed(Math.min(100, Math.max(2, timeDecimals(dt)))) + " s";
    }
    window.requestAnimationFrame(showTime);
  }

  function showLink(setup) {
    var text = fragment(setup);
    byId("link").value = text ? "#" + text : "(the file's own set-up: no fragment)";
    try { history.replaceState(null, "", text ? "#" + text : location.pathname + location.search); }
    catch (e) { /* some browsers refuse it on file://: the address keeps what it had */ }
  }

  function showSlider(name) {
    var spec = DATA.sliders[name], value = setup.values[name];
    byId("slider-" + name + "-value").textContent = DATA.constants[name].symbol + " = " + describe(value, DATA.constants[name].unit);
    byId("slider-" + name).setAttribute("aria-valuetext", byId("slider-" + name + "-value").textContent);
  }

  function buildControls() {
    byId("run").addEventListener("click", function (e) { toggle(); e.target.blur(); });
    byId("step-button").addEventListener("click", function (e) { step(); e.target.blur(); });
    byId("reset").addEventListener("click", function (e) { reset(); e.target.blur(); });
    byId("jump").addEventListener("click", function (e) { jumpTo(byId("jump-t").value); e.target.blur(); });
    byId("jump-t").addEventListener("keydown", function (e) {
      if (e.key === "Enter") { e.preventDefault(); jumpTo(byId("jump-t").value); }
    });
    DATA.arrows.kinds.forEach(function (kind) {
      byId("arrow-" + kind).addEventListener("change", function () { if (current) showArrows(current); });
    });
    Object.keys(DATA.sliders).forEach(function (name) {
      var spec = DATA.sliders[name], input = byId("slider-" + name);
      function valueAt() { return spec.values ? spec.values[Number(input.value)] : Number(input.value); }
      input.addEventListener("input", function () {
        var value = valueAt();
        byId("slider-" + name + "-value").textContent = DATA.constants[name].symbol + " = " + describe(value, DATA.constants[name].unit);
        input.setAttribute("aria-valuetext", byId("slider-" + name + "-value").textContent);   // said with its unit
      });
      input.addEventListener("change", function () {   // released: the run starts again with the new value
        var values = Object.assign({}, setup.values);
        values[name] = valueAt();
        setup = {values: values, integrator: setup.integrator};
        say("");
        start(setup);
      });
    });
    byId("speed").addEventListener("change", function (e) { setSpeed(DATA.speeds[e.target.value]); e.target.blur(); });
    ["show-equilibrium", "show-period"].forEach(function (id) {
      byId(id).addEventListener("change", function () { if (current) showMeasured(current); });
    });
    byId("projector").addEventListener("change", function (e) {
      document.body.classList.toggle("projector", e.target.checked);
      if (current) sizeView(current);
    });
    window.addEventListener("resize", function () { if (current) sizeView(current); });
    byId("describe").addEventListener("click", function () { if (current) sayMotion(current); });
    // the keys are export/page_access.js's (export/page_keys.py), as on the local page
  }

  function setSpeed(value) { speed = value; if (current) current.clock = null; }

  function placeSliders() {
    Object.keys(DATA.sliders).forEach(function (name) {
      var spec = DATA.sliders[name], input = byId("slider-" + name), value = setup.values[name];
      input.value = spec.values ? String(Math.max(0, spec.values.indexOf(value))) : String(value);
      showSlider(name);
    });
  }

  // What the page shows now, for a look from outside (the tests): the step reached, whether it is
  // paused, the set-up, which kinds of arrow are drawn, the jumps made and drawn, and each mass's
  // r and p as the program last reported them.
  window.offlineState = function () {
    var run = current || {};
    var drawn = {};
    Object.keys(run.arrows || {}).forEach(function (kind) {
      drawn[kind] = run.arrows[kind].length > 0 && run.arrows[kind].every(function (o) { return o.visible; });
    });
    return {n: run.n, paused: paused, speed: speed, integrator: setup.integrator, values: setup.values,
            arrows: drawn, opacity: (run.balls || []).map(function (ball) { return ball.opacity; }),
            jumping: jump !== null, jumps: jumps, jumpsDrawn: jumpsDrawn, last: run.last};
  };

  // what the Add a force box (export/force_box.js) asks of the page
  window.offlinePage = {setup: function () { return setup; }, withConstants: withConstants,
                        restart: function () { start(setup); }};

  // ---- start ----

  var asked = fromAddress(location.hash);
  var own = {};
  Object.keys(DATA.constants).forEach(function (name) { own[name] = DATA.constants[name].written; });
  if (asked.problem) {
    say(asked.problem + "; running the file's own set-up instead.");
    setup = {values: own, integrator: DATA.integrator};
  } else {
    setup = {values: Object.assign(own, asked.values), integrator: asked.integrator};
  }
  buildControls();
  placeSliders();
  showRunButton();
  start(setup);
  window.requestAnimationFrame(showTime);
})();
