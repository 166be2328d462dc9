"""The local page's "Add a force" box: the student writes a force as a vector expression of the
program's names, and the run starts again with it in F_net.

The box is plain HTML in the caption (a menu of examples, the force's name, its expression, Add
and run, the one line that says what happened, the program's `Fnet = Fspring + Fgravity + F_push`,
each force added with its Remove button, Back to the file's program, Download my program), each
control labelled for a screen reader and worked from the keyboard (Enter in the expression adds
it). Its script sends what was asked as a small JSON text through one hidden vpython text box,
the only way vpython 7.6.5 lets a page send text; `message` turns it into one of browser/messages.py's
types, and the frame loop (browser/view.py) carries it out with physics/expression.py's grammar:
the text is read, never run (scenes/_written.py makes the force from the tree). The page is told
what to show by `show`, a call of the box's script with the state as JSON.

What the view does with a new set of forces (`try_forces`): builds the model (a force that cannot
be read, or has no value at t = 0, is one line and nothing else changes), runs it over the graph's
window to see that it does not blow up (the same), and works out the run before over that window,
which `Comparison` draws dimmed on the position graph beside the new one.
"""
from __future__ import annotations

import html
import json
import math
from dataclasses import dataclass


from physics.expression import CONSTANT_NAMES, EXAMPLES, FUNCTIONS, NAMES, ExpressionError, check_force_name, parse
from physics.recording import steps_to_reach
from physics.simulate import BlowUpError
from scenes._written import scene_constants

from .messages import AddForce, DownloadProgram, RemoveForce, ResetForces

MAX_PREFLIGHT_SECONDS = 5.0     # the most computing the check of a new force may take, by the engine's estimate
DIMMED = (0.72, 0.72, 0.72)     # the run before: light grey, under the new run's colour
MAX_COMPARED_MASSES = 4         # the run before is drawn for this many graphed masses at most
CHUNK_SECONDS = 0.5             # s of simulated time the check runs at a time: where a blow-up is told


def message(text: str):
    """What the box's script sent, as a message of browser/messages.py; None for anything else."""
    try:
        asked = json.loads(text)
    except (TypeError, ValueError):
        return None
    if not isinstance(asked, dict) or not all(isinstance(value, str) and len(value) <= 400 for value in asked.values()):
        return None
    kind = asked.get("do")
    if kind == "add" and set(asked) == {"do", "name", "text"}:
        return AddForce(asked["name"], asked["text"])
    if kind == "remove" and set(asked) == {"do", "name"}:
        return RemoveForce(asked["name"])
    if kind == "reset" and set(asked) == {"do"}:
        return ResetForces()
    if kind == "download" and set(asked) == {"do"}:
        return DownloadProgram()
    return None


@dataclass(frozen=True)
class Change:
    """The forces after a message of the box, what to say, and the grey curve's legend."""

    written: tuple
    said: str
    before: str


def written_after(written: tuple, asked, *, taken=(), start=()) -> Change:
    """The forces after a message: ((name, text), ...), a sentence and the name of the run before.
    Raises ExpressionError (one line) for a force that cannot be read or a name that is taken."""
    if isinstance(asked, AddForce):
        name = check_force_name(asked.name, taken=[*taken, *(other for other, _ in written)])
        try:
            text = parse(asked.text).text
        except ExpressionError as problem:
            raise ExpressionError(f"the force {name}: {problem}") from None
        return Change((*written, (name, text)), f"{name} added: the run starts again from t = 0, "
                      f"the run before it grey on the graph", f"without {name}")
    if isinstance(asked, RemoveForce):
        kept = tuple(pair for pair in written if pair[0] != asked.name)
        return Change(kept, f"{asked.name} removed: the run starts again from t = 0, the run with it grey on the graph",
                      f"with {asked.name}")
    return Change(tuple(start), "back to the file's program: the run starts again from t = 0", "before")


def net_line(model) -> str:
    """The program's sum, as it writes it: Fnet = Fspring + Fgravity + F_push."""
    return "Fnet = " + " + ".join(force.TERM for force in model.forces if getattr(force, "TERM", ""))


@dataclass
class Tried:
    """A set of forces that can run: the setup and model, and the run before it as graph points."""

    setup: object
    model: object
    before: list


def try_forces(setup, model_now, *, integrator: str, window: float, sample_every: float, graphed, axis: int) -> Tried:
    """The setup's model, checked (ExpressionError or ValueError, one line, for a force that cannot
    be read or has no value at t = 0; BlowUpError where the run blows up within the graph's window),
    and the run now (model_now) over that window: a list per graphed mass of (t, coordinate)."""
    model = setup.build()
    _run(model, integrator, window, sample_every, graphed, axis, check=True)
    before = _run(model_now, integrator, window, sample_every, graphed, axis, check=False)
    return Tried(setup, model, before)


def _run(model, integrator, window, sample_every, graphed, axis, *, check: bool) -> list:
    """The model's run over the window (as far as MAX_PREFLIGHT_SECONDS of computing reaches):
    each graphed mass's (t, coordinate) points from t0; a blow-up raises where `check`, else ends
    the points there."""
    from physics.simulate import every

    engine = model.simulation(integrator)
    masses = list(graphed)[:MAX_COMPARED_MASSES]
    points = [[[float(model.state.t), float(model.state.r[i, axis])]] for i in masses]
    steps = steps_to_reach(window, model.dt)
    affordable = int(MAX_PREFLIGHT_SECONDS / max(engine.seconds_per_step(), 1e-9))
    stride = max(1, round(sample_every / model.dt))
    chunk = stride * max(1, round(CHUNK_SECONDS / sample_every))   # a blow-up is found by the end of its chunk
    total = min(steps, affordable)
    try:
        while engine.steps < total:
            samples = engine.advance(min(chunk, total - engine.steps), record=every(stride), final=False)
            for line, i in zip(points, masses):
                line += [[float(t), float(x)] for t, x in zip(samples.t, samples.r[:, i, axis]) if math.isfinite(x)]
    except BlowUpError:
        if check:
            raise
    return points


def blown_up_sentence(names, problem: BlowUpError) -> str:
    """A run that blew up, naming the forces just added."""
    when = f" by t = {problem.t:.3g} s" if math.isfinite(getattr(problem, "t", math.nan)) else ""
    who = f"the force {' and '.join(names)} makes" if names else "this makes"
    return f"{who} the run blow up{when} (the mass flies off): try a smaller force, or a smaller Δt"


def change_forces(view, asked, batch) -> None:
    """Carry out a message of the box on the page's view (browser/view.py): the new forces run from
    t = 0 with the run before dimmed beside them, or one line says why not and nothing else changes."""
    box, live = view.controls.force_box, view.live
    own = [force.LABEL for force in view.setup.with_written(()).build().forces]
    try:
        change = written_after(view.setup.written, asked, taken=own, start=box.start)
        written = change.written
        setup = view.setup.with_values(**batch.changes).with_written(written)
        graphs = view.graphs
        tried = try_forces(setup, live.model, integrator=view.integrator, window=graphs.span,
                           sample_every=graphs.spacing, graphed=graphs.graphed, axis=graphs.axes[0])
    except BlowUpError as problem:
        added = [name for name, _ in written if name not in {old for old, _ in view.setup.written}]
        box.show(setup=view.setup, model=live.model, said=blown_up_sentence(added, problem) + "; the run before is still on",
                 problem=True)
        return
    except ValueError as problem:
        box.show(setup=view.setup, model=live.model, said=f"{problem}; the run before is still on", problem=True)
        return
    changes, batch.changes = batch.changes, {}
    view.rebuild_with(tried.setup, tried.model, changes=changes, integrator=batch.integrator or view.integrator)
    batch.integrator = None
    view.comparison.show(view.graphs, tried.before, label=change.before)
    if written and "forces" not in view.arrows.shown:   # each force's arrow, the new one's with its name
        view.arrows.set_shown("forces", True)
        view.controls.arrow_boxes["forces"].checked = True
    box.show(setup=tried.setup, model=tried.model, said=change.said)


class Comparison:
    """The run before, dimmed on the position graph beside the new one (one gcurve a mass), its
    values kept on the graph's axis (Graphs.keep_on_axis)."""

    def __init__(self, vp):
        self.vp, self.curves, self.graphs = vp, [], None

    def show(self, graphs, before: list, *, label: str) -> None:
        self.forget()
        self.graphs = graphs
        for n, points in enumerate(before):
            if points:
                self.curves.append(self.vp.gcurve(graph=graphs.position_graph, color=self.vp.vector(*DIMMED), width=2,
                                                  label=label if n == 0 else "", data=points))
        graphs.keep_on_axis([y for points in before for _, y in points])

    def forget(self) -> None:
        for curve in self.curves:
            try:
                curve.delete()
            except Exception:      # the graph went with its page
                pass
        self.curves = []
        if self.graphs is not None:
            self.graphs.keep_on_axis([])
            self.graphs = None


UNSEEN = "position:absolute; width:1px; height:1px; overflow:hidden; clip:rect(0 0 0 0)"


class ForceBox:
    """The box in the caption, for one build of the page: `show` tells it what to show.

    start  the forces the scene was opened with (--force): Back to the file's program returns to them
    """

    def __init__(self, vp, put, *, setup, model, start=()):
        self.vp, self.start = vp, tuple(start)
        vp.scene.append_to_caption("\n")
        # the channel: vpython's text box sends its text to `message` on Enter (the script presses it)
        vp.winput(type="string", text="", width=10, bind=lambda box: self._heard(box.text, put))
        vp.wtext(text="").text = box_html(setup)
        self.state = vp.wtext(text="")
        self.show(setup=setup, model=model)

    @staticmethod
    def _heard(text: str, put) -> None:
        asked = message(text)
        if asked is not None:
            put(asked)

    def show(self, *, setup, model, said: str = "", problem: bool = False) -> None:
        """The forces added, the program's F_net line, and what happened, in one line."""
        state = {"forces": [{"name": name, "text": text} for name, text in setup.written], "line": net_line(model),
                 "said": said, "problem": bool(problem), "start": [list(pair) for pair in self.start]}
        data = json.dumps(state, ensure_ascii=False).replace("</", "<\\/").replace("<!--", "<\\u0021--")
        self.state.text = f"<script>window.smForceBox && window.smForceBox.show({data});</script>"


def box_html(setup) -> str:
    """The box's HTML and its script (see the module's docstring)."""
    own = setup.with_written(()).build()      # the scene's own forces: their names are taken
    constants = scene_constants(setup.values, own)
    names = "; ".join(name + (f" ({', '.join(named['aliases'])})" if named["aliases"] else "")
                      for name, named in NAMES.items() if name not in CONSTANT_NAMES or name in constants)
    examples = "".join(f"<option value='{n}'>{html.escape(example['what'])}: {html.escape(example['text'])}</option>"
                       for n, example in enumerate(EXAMPLES))
    data = json.dumps({"examples": EXAMPLES, "taken": [getattr(force, "LABEL", "") for force in own.forces]})
    return f"""<section id="force-box" aria-labelledby="force-box-title" style="margin:6px 0">
<b id="force-box-title">Add a force</b>
<form id="force-form" autocomplete="off" style="display:inline">
<label for="force-example">start from</label> <select id="force-example" style="font-size:inherit; max-width:100%"><option value="">an example…</option>{examples}</select>
<label for="force-name">name</label> <input type="text" id="force-name" size="8" maxlength="20" spellcheck="false" style="font-size:inherit" value="push">
<label for="force-text">F =</label> <input type="text" id="force-text" size="34" maxlength="300" spellcheck="false" style="font-size:inherit; font-family:monospace" placeholder="vector(2, 0, 0)"> N
<button id="force-add" type="submit" style="font-size:inherit">Add and run</button>
</form>
<span id="force-said" role="status" aria-live="polite" style="display:block; font-weight:600"></span>
the program's line: <code id="force-line" style="font-size:inherit">{html.escape(net_line(own))}</code>
<ul id="force-list" aria-label="forces added" style="margin:2px 0"></ul>
<button id="force-reset" type="button" style="font-size:inherit">Back to the file's program</button>
<button id="force-download" type="button" style="font-size:inherit">Download my program</button>
<details style="display:inline-block"><summary>What a force may use</summary>names: {html.escape(names)}, pi;
functions: {html.escape(', '.join(FUNCTIONS))}; + − * / and ** (a power). A force is a vector: vector(x, y, z),
or a number times a direction, like -2*hat(v).</details>
</section>
<script>{BOX_SCRIPT % {"data": data}}</script>"""


BOX_SCRIPT = r"""(function () {
  var DATA = %(data)s;
  var root = document.getElementById('force-box');
  if (!root || root.dataset.ready) return;
  root.dataset.ready = '1';
  var channel = root.parentNode;
  while (channel && channel.tagName !== 'INPUT') channel = channel.previousElementSibling;
  if (channel) { channel.style.cssText = '%(unseen)s'; channel.setAttribute('aria-hidden', 'true'); channel.tabIndex = -1; }
  function send(asked) { if (!channel) return; channel.value = JSON.stringify(asked); $(channel).trigger($.Event('keypress', {keyCode: 13})); channel.value = ''; }
  var byId = function (id) { return document.getElementById(id); };
  var shown = {forces: []};
  function nextName(base) {
    var taken = DATA.taken.concat(shown.forces.map(function (f) { return f.name; })), name = base, n = 2;
    while (taken.indexOf(name) >= 0) name = base + n++;
    return name;
  }
  byId('force-example').addEventListener('change', function (e) {
    var example = DATA.examples[Number(e.target.value)];
    if (!example || e.target.value === '') return;
    byId('force-text').value = example.text;
    byId('force-name').value = nextName(example.name);
  });
  byId('force-form').addEventListener('submit', function (e) {
    e.preventDefault();
    send({do: 'add', name: byId('force-name').value, text: byId('force-text').value});
  });
  byId('force-reset').addEventListener('click', function () { send({do: 'reset'}); });
  byId('force-download').addEventListener('click', function () { send({do: 'download'}); });
  window.smForceBox = {show: function (state) {
    var added = state.forces.length > shown.forces.length;
    shown = state;
    var said = byId('force-said');
    said.textContent = state.said;
    said.style.color = state.problem ? '#a00000' : '';
    byId('force-line').textContent = state.line;
    var list = byId('force-list');
    list.textContent = '';
    state.forces.forEach(function (force) {
      var item = document.createElement('li'), words = document.createElement('code'), remove = document.createElement('button');
      words.textContent = force.name + ': F = ' + force.text + ' N ';
      words.style.fontSize = 'inherit';
      remove.type = 'button';
      remove.style.fontSize = 'inherit';
      remove.textContent = 'Remove ' + force.name;
      remove.addEventListener('click', function () { send({do: 'remove', name: force.name}); });
      item.appendChild(words); item.appendChild(remove);
      list.appendChild(item);
    });
    byId('force-reset').disabled = JSON.stringify(state.forces.map(function (f) { return [f.name, f.text]; })) === JSON.stringify(state.start);
    if (added && !state.problem) byId('force-name').value = nextName('push');
  }};
})();""".replace("%(unseen)s", UNSEEN)
