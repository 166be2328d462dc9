/* The offline page's "Add a force" box: the student writes a force as a vector expression of the
   program's names, and the page runs the program with it (export/offline_forces.py writes the data
   this reads, #offline-data's "forces").

   Safe by construction: the text is read by the grammar physics/expression.py declares (its data,
   "grammar"), in the same three passes (tokens, syntax, the tree's nodes, names and kinds), and
   only the tree it reads is written into the program, spelled as the program writer spells it
   (programText, as expression.program_text). Nothing the student writes is ever run by this
   script; the program GlowScript compiles holds only what the grammar allows. A link never
   carries a force (the address's set-up is the constants' alone).

   The program with the forces is the writer's own program with a place held for forces
   (offline_forces.py's SlotForce): each force goes in the place's line, its term in each sum, its
   name and arrow among the forces' arrows. The last set of forces that ran well is kept: a force
   that cannot be read changes nothing, and a run that blows up goes back to it. */
(function () {
  "use strict";
  var DATA = JSON.parse(document.getElementById("offline-data").textContent);
  var BOX = DATA.forces;
  if (!BOX) return;
  var G = BOX.grammar, SLOT = BOX.slot;
  var byId = function (id) { return document.getElementById(id); };

  // ---- reading a force: physics/expression.py's parse, pass by pass ----

  function Refused(message) { this.message = message; }
  function refuse(message) { throw new Refused(message); }

  var ALIASES = {};
  Object.keys(G.names).forEach(function (name) {
    ALIASES[name] = name;
    G.names[name].aliases.forEach(function (alias) { ALIASES[alias] = name; });
  });
  var NAME_LIST = Object.keys(G.names).join(", ");
  var FUNCTION_LIST = Object.keys(G.functions).join(", ");
  var has = function (object, key) { return Object.prototype.hasOwnProperty.call(object, key); };

  function tokens(text) {           // expression.tokens: [kind, text, start]
    var found = [], at = 0;
    var patterns = Object.keys(G.tokens).map(function (kind) { return [kind, new RegExp(G.tokens[kind], "y")]; });
    while (at < text.length) {
      if (/\s/.test(text[at])) { at += 1; continue; }
      var matched = false;
      for (var i = 0; i < patterns.length && !matched; i++) {
        patterns[i][1].lastIndex = at;
        var match = patterns[i][1].exec(text);
        if (match) { found.push([patterns[i][0], match[0], at]); at += match[0].length; matched = true; }
      }
      if (matched) continue;
      var operator = null;
      for (var j = 0; j < G.python_operators.length; j++) {
        if (text.startsWith(G.python_operators[j], at)) { operator = G.python_operators[j]; break; }
      }
      if (operator) { found.push(["operator", operator, at]); at += operator.length; }
      else { var c = String.fromCodePoint(text.codePointAt(at)); found.push(["other", c, at]); at += c.length; }
    }
    return found;
  }

  function checkTokens(list) {      // pass 1
    var number = new RegExp("^(?:" + G.number + ")$");
    list.forEach(function (token) {
      var kind = token[0], word = token[1];
      if (kind === "number" && !number.test(word))
        refuse(word + " is not a number this can read: write numbers like 2, 0.5 or 1e-3");
      if (kind === "name" && G.keywords.indexOf(word) >= 0)
        refuse("the word " + word + " is not allowed: write one force, like vector(2, 0, 0)");
      if (kind === "quote") refuse("text in quotes is not allowed: write one force, like vector(2, 0, 0)");
      if ((kind === "operator" || kind === "other") && G.allowed_operators.indexOf(word) < 0)
        refuse(word + " is not allowed: " + (has(G.hints, word) ? G.hints[word] : "use + - * / ** and ( )"));
    });
  }

  // Pass 2: Python's expression grammar over the tokens pass 1 lets through. Each node has its own
  // span (start, end) as Python's ast gives it, and `outer`, its span with the brackets around it.
  function syntax(what) { refuse("cannot read the force: " + what); }
  var WORDS = G.syntax_words;
  function parseSyntax(text, list) {
    var at = 0;
    function peek(word) { return at < list.length && list[at][0] !== "number" && list[at][0] !== "name" && list[at][1] === word; }
    function take() { return list[at++]; }
    function expect(word) {
      if (peek(word)) return take();
      if (word === ")") syntax(WORDS["'(' was never closed"]);
      syntax(G.syntax_default);
    }
    function outer(node) { return node.outer || [node.start, node.end]; }
    function starredOrSum(allowStar) {
      if (allowStar && peek("*")) {
        var star = take(), value = sum();
        return {type: "starred", value: value, start: star[2], end: outer(value)[1]};
      }
      return sum();
    }
    function tupleOrOne(close) {   // expressions [',' ...]; close: the bracket that ends them (null: the end)
      var first = starredOrSum(true), items = [first], comma = false;
      while (peek(",")) {
        take(); comma = true;
        if (close ? peek(close) : at >= list.length) break;
        items.push(starredOrSum(true));
      }
      if (!comma) {
        if (first.type === "starred") syntax(G.syntax_default);
        if (at < list.length && !(close && peek(close)) && close && startsValue()) syntax(WORDS["Perhaps you forgot a comma?"]);
        return first;
      }
      var last = list[at - 1];
      return {type: "tuple", items: items, start: outer(first)[0], end: last[2] + last[1].length};
    }
    function startsValue() {
      if (at >= list.length) return false;
      var kind = list[at][0];
      return kind === "number" || kind === "name" || peek("(") || peek("-") || peek("+");
    }
    function sum() {
      var node = term();
      while (peek("+") || peek("-")) {
        var op = take()[1], right = term();
        node = {type: "binary", op: op, left: node, right: right, start: outer(node)[0], end: outer(right)[1]};
      }
      return node;
    }
    function term() {
      var node = factor();
      while (peek("*") || peek("/")) {
        var op = take()[1], right = factor();
        node = {type: "binary", op: op, left: node, right: right, start: outer(node)[0], end: outer(right)[1]};
      }
      return node;
    }
    function factor() {
      if (peek("-") || peek("+")) {
        var sign = take(), operand = factor();
        return {type: "unary", op: sign[1], operand: operand, start: sign[2], end: outer(operand)[1]};
      }
      return power();
    }
    function power() {
      var base = primary();
      if (peek("**")) {
        take();
        var exponent = factor();
        return {type: "binary", op: "**", left: base, right: exponent, start: outer(base)[0], end: outer(exponent)[1]};
      }
      return base;
    }
    function primary() {
      var node = atom();
      for (;;) {
        if (peek("(")) {
          take();
          var args = [], keywords = [];
          while (!peek(")")) {
            if (at >= list.length) syntax(WORDS["'(' was never closed"]);
            if (peek("**")) {
              var stars = take(), value = sum();
              keywords.push({start: stars[2], end: outer(value)[1]});
            } else {
              if (keywords.length) syntax(G.syntax_default);
              args.push(starredOrSum(true));
            }
            if (peek(",")) take();
            else if (!peek(")")) {
              if (at >= list.length) syntax(WORDS["'(' was never closed"]);
              syntax(startsValue() ? WORDS["Perhaps you forgot a comma?"] : G.syntax_default);
            }
          }
          var close = take();
          node = {type: "call", func: node, args: args, keywords: keywords, start: outer(node)[0], end: close[2] + 1};
        } else if (peek(".")) {
          take();
          if (at >= list.length || list[at][0] !== "name") syntax(G.syntax_default);
          var attribute = take();
          node = {type: "attribute", value: node, attr: attribute[1], start: outer(node)[0],
                  end: attribute[2] + attribute[1].length};
        } else return node;
      }
    }
    function atom() {
      if (at >= list.length) syntax(G.syntax_default);
      var token = list[at];
      if (token[0] === "number") { take(); return {type: "number", text: token[1], start: token[2], end: token[2] + token[1].length}; }
      if (token[0] === "name") { take(); return {type: "name", id: token[1], start: token[2], end: token[2] + token[1].length}; }
      if (peek("(")) {
        var open = take();
        if (peek(")")) { var shut = take(); return {type: "tuple", items: [], start: open[2], end: shut[2] + 1}; }
        var inner = tupleOrOne(")");
        var closing = expect(")");
        if (inner.type === "tuple" && !inner.bracketed) {
          inner.start = open[2]; inner.end = closing[2] + 1; inner.bracketed = true;
        } else if (inner.type === "starred") syntax(G.syntax_default);
        else inner.outer = [open[2], closing[2] + 1];
        return inner;
      }
      if (peek(")")) syntax(WORDS["unmatched ')'"]);
      syntax(G.syntax_default);
    }
    if (!list.length) syntax(G.syntax_default);
    var tree = tupleOrOne(null);
    if (at < list.length) syntax(peek(")") ? WORDS["unmatched ')'"] : G.syntax_default);
    return tree;
  }

  function segment(text, node) { return text.slice(node.start, node.end); }
  function dotted(node) {
    if (node.type === "name") return node.id;
    if (node.type === "attribute") { var head = dotted(node.value); return head === null ? null : head + "." + node.attr; }
    return null;
  }

  function refusals(text, node, found) {      // pass 3a, as expression._refusals
    var start = node.start;
    if (node.type === "name" || node.type === "attribute") {
      var name = dotted(node);
      if (name === null) { found.push([start, segment(text, node) + " is not allowed: a force may use the names " + NAME_LIST]); return; }
      if (has(ALIASES, name)) return;
      if (has(G.functions, name)) found.push([start, name + " is a function: write it with what it works on, like " + name + "(v)"]);
      else if (name.indexOf(".") >= 0) {
        var cut = name.lastIndexOf("."), head = name.slice(0, cut), part = name.slice(cut + 1);
        var hint = has(ALIASES, head) && "xyz".indexOf(part) >= 0 && part.length === 1 ?
          "for " + name + " write dot(" + head + ", vector(" + "xyz".split("").map(function (axis) { return axis === part ? "1" : "0"; }).join(", ") + "))" :
          "a force may use the names " + NAME_LIST;
        found.push([start, name + " is not allowed: " + hint]);
      } else found.push([start, "unknown name " + name + ": a force may use the names " + NAME_LIST]);
      return;
    }
    if (node.type === "call") {
      var called = dotted(node.func);
      if (called === null || !has(G.functions, called)) {
        var what = called !== null && has(ALIASES, called) ? called + " is not a function" :
          called !== null ? "unknown function " + called : segment(text, node.func) + " cannot be called";
        found.push([start, what + ": a force may use the functions " + FUNCTION_LIST]);
        return;
      }
      node.args.forEach(function (arg) { refusals(text, arg, found); });
      node.keywords.forEach(function (keyword) { found.push([keyword.start, segment(text, keyword) + " is not allowed: give each value on its own"]); });
      return;
    }
    if (node.type === "starred") { found.push([start, segment(text, node) + " is not allowed: give each value on its own"]); return; }
    if (node.type === "tuple") { found.push([start, (segment(text, node) || "()") + " is a list of values, not a force: write vector(x, y, z)"]); return; }
    if (node.type === "binary") { refusals(text, node.left, found); refusals(text, node.right, found); return; }
    if (node.type === "unary") { refusals(text, node.operand, found); }
  }

  function a(kind) { return "a " + kind; }
  function kindMessage(op, left, right, seg) {     // expression.kind_message
    if (op === "**") return "cannot " + G.binary_words[op] + " with a vector in " + seg + ": ** takes numbers (write mag(r)**3, not r**3)";
    if (op === "/" && right === G.vector) return "cannot divide by a vector in " + seg + ": divide by a number, like mag(r)";
    if (op === "*") return "cannot multiply two vectors in " + seg + ": use dot(a, b) or cross(a, b)";
    return "cannot " + G.binary_words[op] + " " + a(left) + " and " + a(right) + " in " + seg + ": both must be vectors, or both numbers";
  }

  function kinds(text, node) {                  // pass 3b, as expression._tree
    if (node.type === "number") return {type: "number", text: node.text, kind: G.scalar};
    if (node.type === "name" || node.type === "attribute") {
      var name = ALIASES[dotted(node)];
      return {type: "name", name: name, kind: G.names[name].kind};
    }
    if (node.type === "unary") {
      var operand = kinds(text, node.operand);
      if (node.op === "+") return operand;
      return {type: "unary", op: "-", operand: operand, kind: G.unary["-"][operand.kind]};
    }
    if (node.type === "binary") {
      var left = kinds(text, node.left), right = kinds(text, node.right);
      var kind = G.binary[node.op][left.kind + " " + right.kind];
      if (!kind) refuse(kindMessage(node.op, left.kind, right.kind, segment(text, node)));
      return {type: "binary", op: node.op, left: left, right: right, kind: kind};
    }
    var name = dotted(node.func), takes = G.functions[name].takes;
    var args = node.args.map(function (arg) { return kinds(text, arg); });
    if (args.length !== takes.length)
      refuse(name + " takes " + takes.length + " value" + (takes.length !== 1 ? "s" : "") + " (" + takes.join(", ") +
             "), and " + segment(text, node) + " gives it " + args.length);
    args.forEach(function (arg, i) {
      if (arg.kind !== takes[i]) refuse(name + " needs " + a(takes[i]) + ", and " + segment(text, node.args[i]) + " is " + a(arg.kind));
    });
    return {type: "call", "function": name, args: args, kind: G.functions[name].gives};
  }

  function parse(text) {                        // expression.parse: {text, tree}, or Refused
    text = String(text).split(/\s+/).filter(Boolean).join(" ");
    if (!text) refuse("write a force, like vector(2, 0, 0)");
    if (text.length > G.max_length) refuse("a force of at most " + G.max_length + " characters, please (this one has " + text.length + ")");
    var list = tokens(text);
    checkTokens(list);
    var node = parseSyntax(text, list);
    var found = [];
    refusals(text, node, found);
    if (found.length) {
      var first = found[0];
      found.forEach(function (item) { if (item[0] < first[0]) first = item; });
      refuse(first[1]);
    }
    var tree = kinds(text, node);
    if (tree.kind !== G.vector)
      refuse(text + " is a number, but a force is a vector: give it a direction, like (" + text + ")*vector(0, 1, 0) or (" + text + ")*hat(v)");
    return {text: text, tree: tree};
  }

  function checkName(name, taken) {            // expression.check_force_name
    name = String(name).trim();
    if (!new RegExp("^(?:" + G.force_name + ")$").test(name))
      refuse("a force's name is a word of letters, digits and _ that starts with a letter, at most 20 long, like push (got '" + name + "')");
    if (taken.indexOf(name) >= 0) refuse("the name " + name + " is taken: call the force something else, like my" + name);
    return name;
  }

  function namesIn(node, into) {
    into = into || {};
    if (node.type === "name") into[node.name] = true;
    else if (node.type === "unary") namesIn(node.operand, into);
    else if (node.type === "binary") { namesIn(node.left, into); namesIn(node.right, into); }
    else if (node.type === "call") node.args.forEach(function (arg) { namesIn(arg, into); });
    return into;
  }

  // ---- writing it as the program's line: expression.program_text ----

  var PRECEDENCE = {"+": 1, "-": 1, "*": 2, "/": 2, unary: 3, "**": 4};
  function precedence(node) { return node.type === "binary" ? PRECEDENCE[node.op] : node.type === "unary" ? 3 : 5; }
  function programText(node, spelled) {
    if (node.type === "number") return node.text;
    if (node.type === "name") return spelled[node.name];
    if (node.type === "call") return node["function"] + "(" + node.args.map(function (arg) { return programText(arg, spelled); }).join(", ") + ")";
    if (node.type === "unary") {
      var inner = programText(node.operand, spelled);
      return node.operand.type === "binary" || node.operand.type === "unary" ? node.op + "(" + inner + ")" : node.op + inner;
    }
    var own = PRECEDENCE[node.op], left = programText(node.left, spelled), right = programText(node.right, spelled);
    if (precedence(node.left) < own || (node.op === "**" && precedence(node.left) <= own)) left = "(" + left + ")";
    if (node.right.type === "unary" || precedence(node.right) <= own) right = "(" + right + ")";
    return node.op === "+" || node.op === "-" ? left + " " + node.op + " " + right : left + node.op + right;
  }

  // ---- the force where the masses start: a number, or no value (the start's check) ----

  function evaluate(node, values) {            // vectors as [x, y, z], numbers as numbers
    var V = function (x) { return Array.isArray(x); };
    var mag = function (x) { return Math.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]); };
    if (node.type === "number") return Number(node.text);
    if (node.type === "name") return values[node.name];
    if (node.type === "unary") { var o = evaluate(node.operand, values); return V(o) ? o.map(function (c) { return -c; }) : -o; }
    if (node.type === "binary") {
      var l = evaluate(node.left, values), r = evaluate(node.right, values);
      var each = function (f) {
        if (V(l) && V(r)) return l.map(function (c, i) { return f(c, r[i]); });
        if (V(l)) return l.map(function (c) { return f(c, r); });
        if (V(r)) return r.map(function (c) { return f(l, c); });
        return f(l, r);
      };
      return each({"+": function (x, y) { return x + y; }, "-": function (x, y) { return x - y; },
                   "*": function (x, y) { return x * y; }, "/": function (x, y) { return x / y; },
                   "**": Math.pow}[node.op]);
    }
    var args = node.args.map(function (arg) { return evaluate(arg, values); });
    var hat = function (x) { var size = mag(x); return size > 0 ? x.map(function (c) { return c / size; }) : [0, 0, 0]; };
    return {
      vector: function (x, y, z) { return [x, y, z]; }, mag: mag, norm: hat, hat: hat,
      dot: function (x, y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; },
      cross: function (x, y) { return [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]]; },
      cos: Math.cos, sin: Math.sin, exp: Math.exp, sqrt: Math.sqrt
    }[node["function"]].apply(null, args);
  }

  function startProblem(force, values) {       // scenes/_written.py's _check_start
    var state = BOX.state;
    for (var i = 0; i < state.r.length; i++) {
      var m = values.m !== undefined ? values.m : state.m[i];
      var named = Object.assign({}, state.values, values, {r: state.r[i], v: state.v[i], t: state.t, m: m, pi: Math.PI,
                                p: state.v[i].map(function (c) { return m * c; })});
      var F = evaluate(force.law.tree, named);
      if (!F.every(isFinite))
        return "the force " + force.name + " has no value at t = 0 " + (state.r.length === 1 ? "where the mass starts" :
          "where the masses start") + " (it divides by zero or grows past any number there): change it, or start the mass elsewhere";
    }
    return "";
  }

  // ---- the program with the forces: the writer's program with its place filled ----

  function pad(code, comment) {                // export/lines.py's align_comments
    if (!comment) return code;
    var width = SLOT.column - 1;
    return (code.length < width ? code + " ".repeat(width - code.length) : code) + " # " + comment;
  }
  function split(line) {                       // (code, comment) of a line the writer aligned
    var at = line.indexOf(" # ");
    return at < 0 ? [line, ""] : [line.slice(0, at).replace(/\s+$/, ""), line.slice(at + 3)];
  }
  function escaped(text) { return text.replace(/[.*+?^${}()|[\]\\]/g, "\\$&"); }
  var TERM = "F_" + SLOT.name;

  function headerOf(text) {                    // the lines after the first up to the first blank one
    var lines = text.split("\n"), end = lines.indexOf("");
    return lines.slice(1, end);
  }

  function withForces(template, forces, optional, header, framing) {
    var terms = forces.map(function (force) { return "F_" + force.name; });
    var sites = new RegExp("^(\\s*)" + escaped(TERM) + " = " + ["t", "r", "v", "m"].map(function (name) {
      return escaped(SLOT.open) + name + "=(.*?)" + escaped(SLOT.close);
    }).join("") + "(\\s+# .*)?$");
    var used = {};
    forces.forEach(function (force) { Object.assign(used, namesIn(force.law.tree)); });
    var index = SLOT.index, lines = template.split("\n"), out = [];
    var blockLine = new RegExp("^\\s*force(arrows|labels)(\\[i\\])?\\[" + index + "\\]|^\\s*Ftail = Ftail \\+ Fscale\\*" + escaped(TERM) + "$");
    for (var n = 0; n < lines.length; n++) {
      var line = lines[n], match = sites.exec(line);
      var constant = /^(\w+) = /.exec(line);
      if (constant && optional.indexOf(constant[1]) >= 0 && !used[constant[1]]) continue;
      if (match) {
        var spelled = {t: match[2], r: match[3], v: match[4], m: match[5], pi: "pi", p: "(" + match[5] + "*" + match[4] + ")"};
        Object.keys(BOX.constants).forEach(function (name) { spelled[name] = name; });
        forces.forEach(function (force) {     // with its comment where the place has one (the laws written out)
          out.push(pad(match[1] + "F_" + force.name + " = " + programText(force.law.tree, spelled),
                       match[6] ? force.name + ", added: F = " + force.law.text : ""));
        });
        continue;
      }
      if (blockLine.test(line)) {               // the place's arrow: one block per force, numbered on
        var block = [];
        while (n < lines.length && blockLine.test(lines[n])) block.push(lines[n++]);
        n -= 1;
        forces.forEach(function (force, k) {
          block.forEach(function (each) {
            out.push(each.split("[" + index + "]").join("[" + (index + k) + "]").split(TERM).join("F_" + force.name));
          });
        });
        continue;
      }
      if (/^\s*forcenames = \[/.test(line)) {
        out.push(line.replace('"' + SLOT.name + '"', forces.map(function (force) { return '"' + force.name + '"'; }).join(", ")));
        continue;
      }
      var list = /^(\s*)force(xoffsets|aligns) = \[(.*)\]$/.exec(line);
      if (list) {
        var items = list[3].split(", ").slice(0, index);
        forces.forEach(function (force, k) {
          var odd = (index + k) % 2 === 1;
          items.push(list[2] === "xoffsets" ? String(odd ? -SLOT.xoffset : SLOT.xoffset) : odd ? '"right"' : '"left"');
        });
        out.push(list[1] + "force" + list[2] + " = [" + items.join(", ") + "]");
        continue;
      }
      var count = /^(\s*)for j in range\((\d+)\):$/.exec(line);
      if (count && Number(count[2]) === index + 1) { out.push(count[1] + "for j in range(" + (index + forces.length) + "):"); continue; }
      if (line.indexOf(TERM) >= 0 || line.indexOf(SLOT.name) >= 0) {   // a sum, or the arrows' comment
        var parts = split(line);
        var code = parts[0].split(TERM).join(terms.join(" + "));
        var comment = parts[1].split(SLOT.name).join(forces.map(function (force) { return force.name; }).join(", "));
        out.push(pad(code, comment));
        continue;
      }
      out.push(line);
    }
    out = keepFraming(out, framing);
    return [out[0]].concat(header, out.slice(1)).join("\n");
  }

  function keepFraming(lines, framing) {       // the file's own picture: its sphere, support and arrow scales
    var own = framing.split("\n");
    return lines.map(function (line) {
      var prefix = SLOT.framing.find(function (start) { return line.indexOf(start) === 0; });
      if (!prefix) return line;
      var kept = own.find(function (other) { return other.indexOf(prefix) === 0; });
      return kept === undefined ? line : kept;
    });
  }

  function commandWith(header, forces) {       // the header's command, with these forces (program_command.force_option)
    return header.map(function (line) {
      if (line.indexOf("# The same case on the simulator's page: ") !== 0) return line;
      return line.replace(/ --force "[^"]*"/g, "") + forces.map(function (force) {
        return ' --force "' + force.name + "=" + force.law.text + '"';
      }).join("");
    });
  }

  function sameAsFile(forces) {
    return forces.length === BOX.start.length && forces.every(function (force, i) {
      return force.name === BOX.start[i][0] && force.law.text === BOX.start[i][1];
    });
  }

  function program(integrator, forces, handout) {   // the program for these forces: the page's, or the handout
    var own = DATA.programs[integrator], made = BOX.programs[integrator];
    if ((!handout && sameAsFile(forces)) || !made) return own;
    var header = commandWith(headerOf(own), forces);
    var none = handout ? made.handout_none : made.page_none;
    if (!forces.length) return [none.split("\n")[0]].concat(header, none.split("\n").slice(1)).join("\n");
    var reads = forces.some(function (force) { var used = namesIn(force.law.tree); return used.v || used.p; });
    var kind = (handout ? "handout" : "page") + (reads && made[(handout ? "handout" : "page") + "_v"] ? "_v" : "");
    return withForces(made[kind], forces, made.optional[kind], header, handout ? made.handout_none : own);
  }

  // ---- the box ----

  var forces = [], good = [];                   // the forces the page runs, and the last set that ran well
  var lastRun = null, before = null;

  function read(name, text, taken) {
    var checkedName = checkName(name, taken);
    try { return {name: checkedName, law: parse(text)}; }
    catch (problem) {
      if (problem instanceof Refused) refuse("the force " + checkedName + ": " + problem.message);
      throw problem;
    }
  }

  BOX.start.forEach(function (pair) {
    forces.push(read(pair[0], pair[1], BOX.taken.concat(forces.map(function (f) { return f.name; }))));
  });
  good = forces.slice();

  function said(text, problem) {
    var line = byId("force-said");
    line.textContent = text;
    line.className = problem ? "force-said problem" : "force-said";
  }

  function netLine() {                         // the sum as the program writes it: Fnet = Fspring + Fgravity + F_push
    return "Fnet = " + BOX.terms.concat(forces.map(function (force) { return "F_" + force.name; })).join(" + ");
  }

  function showList() {
    var list = byId("force-list");
    list.textContent = "";
    forces.forEach(function (force) {
      var item = document.createElement("li");
      var words = document.createElement("span");
      words.textContent = force.name + ": F = " + force.law.text + " N ";
      var remove = document.createElement("button");
      remove.type = "button";
      remove.textContent = "Remove " + force.name;
      remove.addEventListener("click", function () {
        change(forces.filter(function (other) { return other !== force; }),
               force.name + " removed: the run starts again from t = 0, the run with it grey on the graph", "with " + force.name);
      });
      item.appendChild(words);
      item.appendChild(remove);
      list.appendChild(item);
    });
    byId("force-line").textContent = netLine();
    byId("force-reset").disabled = sameAsFile(forces);
  }

  function change(next, done, label) {          // run from t = 0 with these forces, the run before grey ("label")
    var values = window.offlinePage.setup().values, integrator = window.offlinePage.setup().integrator;
    if (!BOX.programs[integrator]) {             // the file holds the box's programs for its own integrator
      said("Add a force runs with this file's integrator, " + DATA.integrator + " (the address chose " + integrator +
           "): open the file without integrator= in its address, or write it with --integrator " + integrator, true);
      return false;
    }
    for (var i = 0; i < next.length; i++) {
      var problem = startProblem(next[i], values);
      if (problem) { said(problem + "; the run before is still on", true); return false; }
    }
    before = lastRun && lastRun.graph ? {curves: curvesOf(lastRun), label: label} : null;
    if (!(lastRun && lastRun.blown)) good = forces.slice();   // these ran well: a blow-up comes back to them
    forces = next;
    showList();
    if (next.length) {
      var box = byId("arrow-forces");
      if (box && !box.checked) { box.checked = true; box.dispatchEvent(new Event("change")); }
    }
    said(done, false);
    window.offlinePage.restart();
    return true;
  }

  function add() {
    var name = byId("force-name").value, text = byId("force-text").value;
    try {
      var force = read(name, text, BOX.taken.concat(forces.map(function (f) { return f.name; })));
      var missing = Object.keys(namesIn(force.law.tree)).filter(function (used) {
        return G.constants.indexOf(used) >= 0 && !has(BOX.constants, used);
      });
      if (missing.length) refuse("the force " + force.name + " reads " + missing.join(", ") + ", which this scene does not have");
      if (change(forces.concat([force]), force.name + " added: the run starts again from t = 0, " +
                 "the run before it grey on the graph", "without " + force.name)) {
        byId("force-name").value = nextName();
      }
    } catch (problem) {
      if (!(problem instanceof Refused)) throw problem;
      said(problem.message + "; the run before is still on", true);
    }
  }

  function nextName() {
    var base = "push", n = 2, taken = BOX.taken.concat(forces.map(function (f) { return f.name; }));
    var name = base;
    while (taken.indexOf(name) >= 0) name = base + n++;
    return name;
  }

  function curvesOf(run) {                      // the run's own curves (not the closed form's, not a dimmed one)
    return (run.graph.graph_series || []).filter(function (series) {
      return series.label !== "exact" && !series.__dimmed;
    }).map(function (series) { return series.data.slice(); });
  }

  function download() {
    var setup = window.offlinePage.setup();
    if (!BOX.programs[setup.integrator]) {
      said("Download my program writes this file's integrator, " + DATA.integrator + "; the address chose " +
           setup.integrator + ": write it with python main.py " + DATA.scene + " --webvpython FILE.py --integrator " +
           setup.integrator, true);
      return;
    }
    var text = window.offlinePage.withConstants(program(setup.integrator, forces, true), setup);
    var link = document.createElement("a");
    link.href = URL.createObjectURL(new Blob([text], {type: "text/x-python"}));
    link.download = DATA.scene + ".py";
    document.body.appendChild(link);
    link.click();
    link.remove();
    said("downloaded " + DATA.scene + ".py: the Web VPython program with " +
         (forces.length ? "your force" + (forces.length > 1 ? "s" : "") : "the file's forces") +
         " (glowscript.org or trinket run it)", false);
  }

  function build() {
    var menu = byId("force-example");
    G.examples.forEach(function (example, i) {
      var option = document.createElement("option");
      option.value = String(i);
      option.textContent = example.what + ": " + example.text;
      menu.appendChild(option);
    });
    menu.addEventListener("change", function () {
      var example = G.examples[Number(menu.value)];
      if (!example) return;
      byId("force-text").value = example.text;
      var taken = BOX.taken.concat(forces.map(function (f) { return f.name; }));
      byId("force-name").value = taken.indexOf(example.name) < 0 ? example.name : nextName();
    });
    byId("force-form").addEventListener("submit", function (e) { e.preventDefault(); add(); });
    byId("force-reset").addEventListener("click", function () {
      change(BOX.start.map(function (pair) { return read(pair[0], pair[1], BOX.taken); }),
             "back to the file's program: the run starts again from t = 0", "before");
    });
    byId("force-download").addEventListener("click", download);
    byId("force-name").value = nextName();
    showList();
  }

  window.offlineForces = {
    // the program the page runs for an integrator (export/offline_page.js asks before each start)
    program: function (integrator) { return program(integrator, forces, false); },
    drawn: function (run) {                     // a run drew its objects: the run before, dimmed beside it
      lastRun = run;
      if (!before || !run.graph) return;
      before.curves.forEach(function (data, i) {
        var curve = window.gcurve({graph: run.graph, data: data, color: window.vector(0.72, 0.72, 0.72), width: 2,
                                   label: i === 0 ? before.label : ""});
        curve.__dimmed = true;
      });
    },
    stepped: function (run, step) {             // each step: a run that blows up goes back to the last good forces
      if (run.blown) return;
      var finite = step.r_f.every(isFinite) && step.p_f.every(isFinite);
      var size = Math.max.apply(null, step.r_f.map(Math.abs));
      if (finite && size < 1e9) return;
      run.blown = true;
      var culprit = forces.filter(function (force) { return good.indexOf(force) < 0; }).map(function (force) { return force.name; });
      var t = pyNumber(step.n * run.dt);
      forces = good.slice();
      showList();
      said((culprit.length ? "the force " + culprit.join(" and ") + " makes" : "this makes") + " the run blow up at t = " + t +
           " s (the mass flies off): try a smaller force or a smaller Δt; back to the run before", true);
      setTimeout(function () { window.offlinePage.restart(); }, 0);
    },
    forTests: {parse: parse, programText: programText, checkName: checkName, withForces: withForces, program: program,
               forces: function () { return forces; }, read: read, Refused: Refused,
               lastGraph: function () { return lastRun && lastRun.graph; }}
  };
  function pyNumber(x) { return window.offlineNumbers ? window.offlineNumbers.number(x) : String(x); }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", build);
  else build();
})();
