/* The offline page's judgement of a set-up, as the command line judges it (export/offline_judge.py
   says where each part comes from). A set-up is a link's (`vertical.html#m=1&k=120&dt=0.5`), a
   slider's or a preset's; what is refused is one line on the page, in `--set`'s words.

   - A value from the address is read as --set reads it (scenes/_constants.py parse_value and
     check_value), against its constant's declaration (DATA.constants: range, unit, the words of
     the range); only a constant's own name is taken, and a name given twice is named.
   - The forces' rules and rates come from the program itself: its check section (before it draws
     anything) refuses a rule it breaks in the rule's own sentence, and reports each mass's k, b/m
     and drag rate (each force's PROGRAM_RATES, export/program_page.py).
   - Whether Δt is stable is read off physics/stability.py's own table of each method's largest
     stable Δt (DATA.judge), in its own sentences (CAUSES, PAST_LIMIT, EVERY_DT), which this fills.
   Nothing here steps or works out any physics. */
(function () {
  "use strict";
  var DATA = JSON.parse(document.getElementById("offline-data").textContent);
  var OWN = Object.prototype.hasOwnProperty;
  var page = window.OfflinePage = window.OfflinePage || {};
  var pyG = function (x, digits) { return page.numbers.pyG(x, digits); };

  // ---- a value from the address, read as --set reads it ----

  // What Python's float() reads (--set reads a value with it): a decimal with an exponent, digits
  // grouped by _, or inf, infinity and nan in any case, with a sign.
  var DIGITS = "\\d+(?:_\\d+)*";
  var DECIMAL = new RegExp("^[+-]?(?:(?:" + DIGITS + "(?:\\.(?:" + DIGITS + ")?)?|\\.(?:" + DIGITS + "))" +
                           "(?:[eE][+-]?" + DIGITS + ")?|inf|infinity|nan)$", "i");

  function shownNumber(value) {                   // format_value's digits: inf and nan as Python writes them
    if (isNaN(value)) return "nan";
    if (!isFinite(value)) return value < 0 ? "-inf" : "inf";
    return pyG(value, 6);
  }
  function describe(value, unit) { return shownNumber(value) + (unit && unit !== "1" ? " " + unit : ""); }

  function command(name, text) {
    return "python main.py " + DATA.scene + " --html " + DATA.scene + ".html --set " + name + "=" + text;
  }

  // A constant's value from the address, or the one-line reason it cannot be used (as --set says it).
  function checked(name, text) {
    if (!OWN.call(DATA.constants, name)) {
      if (DATA.all_constants.indexOf(name) >= 0)
        return {problem: name + " cannot be set from the address in this file; write a file with it: " + command(name, text)};
      return {problem: "unknown constant '" + name + "' in the address (known: " + DATA.all_constants.join(", ") + ")"};
    }
    var declared = DATA.constants[name];
    text = text.trim();
    if (!DECIMAL.test(text)) return {problem: name + " needs a number (got '" + text + "')"};
    var word = text.replace(/^[+-]/, "").toLowerCase();
    var value = word === "nan" ? NaN : word.indexOf("inf") === 0 ? (text[0] === "-" ? -Infinity : Infinity) :
      Number(text.replace(/_/g, ""));
    var mantissa = text.toLowerCase().split("e")[0];
    if (value === 0 && /[1-9]/.test(mantissa))
      return {problem: name + " = " + text + " is too small for the computer to tell from 0; write 0 to switch it off, " +
                       "or give at least " + DATA.smallest_text + " in size"};
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

  // The set-up in the address (`#k=60&dt=0.05&integrator=rk4`): {values, integrator} or {problem}.
  function fromAddress(hash) {
    var values = {}, integrator = DATA.integrator, seen = {};
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
      if (OWN.call(seen, name))
        return {problem: name + " is given twice in the address (" + name + "=" + seen[name] + " and " + name + "=" +
                         value + "): give it once"};
      seen[name] = value;
      if (name === "integrator") {
        if (DATA.fixed_methods)
          return {problem: "scene '" + DATA.scene + "' steps its masses with " + DATA.fixed_methods.join(", ") +
                           ", one each, so integrator=" + value + " would do nothing; leave it out"};
        if (!OWN.call(DATA.programs, value))
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

  // ---- whether Δt is stable: physics/stability.py's verdict, from its table and its sentences ----

  var J = DATA.judge;

  // L(θ): the method's largest stable Δt·√(ω² + γ²), θ = atan2(γ, ω), between the table's points;
  // where one of two points is 0 (no stable Δt) or inf (any), the nearer point's value.
  function scaledLimit(method, theta) {
    var table = J.methods[method].limit, x = theta / (Math.PI / 2) * (J.angles - 1);
    var i = Math.min(Math.floor(x), J.angles - 2), f = x - i;
    var a = table[i] === null ? Infinity : table[i], b = table[i + 1] === null ? Infinity : table[i + 1];
    if (!isFinite(a) || !isFinite(b) || a === 0 || b === 0) return f < 0.5 ? a : b;
    return a * (1 - f) + b * f;
  }

  function largestStable(method, omega, rate) {     // s: physics/stability.py's largest_stable_dt
    var size = Math.sqrt(omega * omega + rate * rate);
    if (size === 0) return Infinity;
    var limit = scaledLimit(method, Math.atan2(rate, omega));
    return limit === 0 ? 0 : limit / size;
  }

  function growth(method, omegaDt) {              // ρ − 1 per step of a method that grows at every Δt
    var table = J.methods[method].growth, decades = J.growth_decades;
    var x = (Math.log10(omegaDt) - decades[0]) * J.growth_per_decade;
    var i = Math.max(0, Math.min(Math.floor(x), table.length - 2)), f = Math.max(0, Math.min(1, x - i));
    return Math.exp(Math.log(table[i]) * (1 - f) + Math.log(table[i + 1]) * f);
  }

  function fill(text, slots) { return text.replace(/\{(\w+)\}/g, function (all, name) { return slots[name]; }); }

  // Which rate alone makes (within 1 %) the limit all of them together make (stability.py's _cause).
  function cause(method, mass, limit) {
    if (limit === 0) return "spring";
    var alone = {spring: largestStable(method, mass.omega, 0), damping: largestStable(method, 0, mass.damping),
                 drag: largestStable(method, 0, mass.drag)};
    var close = ["spring", "damping", "drag"].filter(function (name) {   // math.isclose(..., rel_tol=0.01)
      return isFinite(alone[name]) && Math.abs(alone[name] - limit) <= 0.01 * Math.max(Math.abs(alone[name]), Math.abs(limit));
    });
    if (close.length) return close[0];
    return [["spring", mass.omega], ["damping", mass.damping], ["drag", mass.drag]]
      .filter(function (pair) { return pair[1] > 0; }).map(function (pair) { return pair[0]; }).join(" and ");
  }

  function sentence(method, mass, dt, limit) {    // stability.py's _message, from its own templates
    var numbers = {omega: pyG(mass.omega, 4), damping: pyG(mass.damping, 4), drag: pyG(mass.drag, 4),
                   speed: pyG(mass.speed, 4)};
    var what = {};
    Object.keys(J.causes).forEach(function (part) { what[part] = fill(J.causes[part], numbers); });
    if (limit === 0)
      return fill(J.every_dt, {dt: pyG(dt, 6), method: method, spring: what.spring,
                               growth: pyG(100 * growth(method, mass.omega * dt), 3)});
    var why = cause(method, mass, limit);
    var shown = pyG(limit, 4), digits = 6;
    while (Number(pyG(dt, digits)) !== dt && Number(pyG(dt, digits)) <= Number(shown) && digits < 17) digits += 1;
    return fill(J.past_limit, {dt: pyG(dt, digits), verb: why.indexOf(" and ") < 0 ? "makes" : "make", limit: shown,
                               method: method, rule: J.methods[method].rules[why] || "",
                               named: why.split(" and ").map(function (part) { return what[part]; }).join(" and ")});
  }

  // One verdict over the masses judged (stability.py's judge): the worst mass decides.
  function verdict(masses, methods, dt) {
    var worst = null;
    masses.forEach(function (mass) {
      var method = methods[mass.i], limit = largestStable(method, mass.omega, mass.damping + mass.drag);
      var past = limit === 0 ? Infinity : dt / limit;
      if (dt > limit * (1 + 1e-12) && (worst === null || past > worst.past))
        worst = {mass: mass, method: method, limit: limit, past: past};
    });
    if (worst === null) return null;
    return {past_limit: worst.limit > 0, message: sentence(worst.method, worst.mass, dt, worst.limit)};
  }

  // The command line's judgement before a run (reports/headless.py stability_warning): a refusal
  // past a method's limit ({refused}), a warning where the motion grows at every Δt ({warning}),
  // or null. The masses a scene expects to run away (each mass with its own method, the ones whose
  // method grows at this Δt: Model.expected_runaways) are judged on their own.
  function judgeRun(reports, methods, dt) {
    var masses = reports.map(function (report, i) {
      return {i: i, omega: Math.sqrt(report.stiffness / report.m), damping: report.damping, drag: report.drag,
              speed: report.speed};
    });
    var runaway = function (mass) {
      return DATA.fixed_methods !== null && dt > largestStable(methods[mass.i], mass.omega, mass.damping + mass.drag);
    };
    var groups = [masses.filter(function (mass) { return !runaway(mass); })];
    if (DATA.fixed_methods !== null) groups.push(masses.filter(runaway));
    for (var g = 0; g < groups.length; g++) {
      var found = verdict(groups[g], methods, dt);
      if (found && found.past_limit) return {refused: J.refused + ": " + found.message};
      if (found) return {warning: "warning: expect the motion to grow: " + found.message};
    }
    return null;
  }

  page.judge = {checked: checked, fromAddress: fromAddress, judgeRun: judgeRun, describe: describe};
})();
