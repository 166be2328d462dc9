"""A scene as one HTML file that runs offline in any browser: GlowScript 3.2 and the handed-out
program inside, the lesson's controls around it.

`python main.py vertical --html vertical.html` writes a page that opens by double-click (file://)
with no network and no install: GlowScript's own files (export/glowscript/, pinned by sha256
below and never changed) are written into it whole, with the Web VPython program
(export/vpython_program.py) that GlowScript compiles and runs there. So its numbers are the
handout's, which are the engine's: it prints `--headless`'s answer at the question time.

The page around the program (export/offline_page.js) gives the local page's lesson controls:
Run/Pause, Step (one Δt written out in export/step_update.py's layout and digits), Reset, a slider
for each of the scene's main constants (scenes/_sliders.py, as the local page has them), the
arrows' check boxes, Jump to t (the program run on to a time without drawing, then paused there)
and the keys Space, →, R and J. It never steps the physics itself: it holds the
program at rate() while paused, and starts it again with new constants written into its
constants block (export/program_page.py has the lines the program adds for the page).

Which constants the page may change is worked out here, from the writer itself: a constant is
offered (a slider, or a value from the address `vertical.html#k=60&dt=0.05`) only over a span
where writing its new value into the constants block gives the very program the writer would write
for it, apart from what only frames the picture (the sphere's size, the support, the arrows'
scales). A constant that changes which lines the program has (a force switched on from 0, a
closed form of another kind, a label naming a value) is left as the file has it: the address
may not set it, and says how to write a file that has it. Two constants moved together can still
cross a line (b past critical damping as m and k fall): within the sliders' spans the built-in
scenes do not, and what changes then is the exact curve's formula, not the run.
"""
from __future__ import annotations

import hashlib
import html
import json
import os
from dataclasses import dataclass

import numpy as np

from physics.equilibrium import equilibrium
from physics.integrators import INTEGRATORS
from physics.period import formula_period, measured_period, record_spacing, why_no_period
from physics.recording import steps_to_reach
from physics.simulate import BlowUpError, every, trajectory
from scenes import DECLARED
from scenes._sliders import round_slider_values, slider_names, slider_range, symbol
from scenes._view import DEFAULT_VIEW

from . import files, offline_forces
from . import page_access
from .arrows import ARROW_LABELS, ARROWS, SEE_THROUGH, choose_scales
from .description import template_data
from .framing import frame
from .lines import ProgramError
from .page_keys import keys_html
from .plain_ticks import plain_ticks
from .program_command import description
from .step_update import number, step_layout
from .vpython_program import program

HERE = os.path.dirname(os.path.abspath(__file__))
GLOWSCRIPT = os.path.join(HERE, "glowscript")
# GlowScript 3.2's files, in the order the page loads them, each pinned by its sha256: the files of
# GlowScriptOffline3.2.zip (sha256 e2e0f3e5...c2e47e2c3, github.com/vpython/glowscript),
# GlowScriptOffline/glowscript_libraries/, unchanged. NOTICE beside them has their licences.
LIBRARIES = (
    ("jquery.min.js", "5f1ab65fe2ad6b381a1ae036716475bf78c9b2e309528cf22170c1ddeefddcbf"),
    ("jquery-ui.custom.min.js", "c4d8dbe77feb63e5a61bee0bead4e5f66e8fa6a927599bd1b74aced52467273c"),
    ("glow.3.2.min.js", "3c3393eb04a9ffa8016dad9d296e6c7db171673788db71c3bcab7847903f45e0"),
    ("RSrun.3.2.min.js", "2735844b615f87b4147e9cb2b90bf8a7a15da208fc8876eae469fc98861e429d"),
    ("RScompiler.3.2.min.js", "4fc76f1d6ab7d9b15d118fac2aa3f7c237a216f779b829801fb623b26d2c207c"),
)
COMPILER = "RScompiler.3.2.min.js"   # run anew for each program compiled (see _document)
NOTICE = os.path.join(GLOWSCRIPT, "NOTICE")
SCRIPT = os.path.join(HERE, "offline_page.js")
STYLE = os.path.join(HERE, "offline_page.css")
MAX_BYTES = 7_000_000          # the bound on the file's size
STEP_MASSES = 4                # masses whose Step is written out, as on the local page (browser/view.py)
FOV = 0.2                      # rad: the local page's long lens (browser/scene3d.py), the support and springs flat
SPEEDS = {"¼×": 0.25, "½×": 0.5, "1×": 1.0, "2×": 2.0, "4×": 4.0}   # as the local page's speed menu (browser/controls.py)
VIEW_LABEL = ("The 3-D view of the scene. Press D, or the Describe button, to hear where each mass is and "
              "how it moves.")
BODY_PX, PROJECTOR_PX = 18, 22  # px: the smallest text, as on the local page (browser/page_layout.py)
# What only frames the picture: the writer chooses it from the motion, and a constant moved on the
# page keeps the file's (the local page also keeps its arrow scales through a run).
FRAMING = ("radius = ", "box(", "pscale = ", "Fscale = ")


def library(name: str) -> str:
    """One of GlowScript's files, as text; ProgramError if it is not the pinned file."""
    pinned = dict(LIBRARIES)[name]
    with open(os.path.join(GLOWSCRIPT, name), "rb") as file:
        data = file.read()
    if hashlib.sha256(data).hexdigest() != pinned:
        raise ProgramError(f"export/glowscript/{name} is not GlowScript 3.2's file (its sha256 differs from the "
                           f"pinned one): restore it with git checkout")
    text = data.decode("utf-8")
    if "</script" in text.lower() or "<!--" in text:   # would end or confuse the <script> it goes in
        raise ProgramError(f"export/glowscript/{name} cannot be written into a page whole")
    return text


@dataclass(frozen=True)
class Settable:
    """A constant the page may change: its declaration, as the browser checks it, and the span
    this file can run (file_low to file_high)."""

    name: str
    written: float
    scene_default: float
    file_low: float
    file_high: float

    def as_data(self) -> dict:
        declared = DECLARED[self.name]
        unit = declared.unit
        return {"written": self.written, "scene_default": self.scene_default, "unit": unit,
                "symbol": symbol(self.name), "low": declared.low, "high": declared.high,
                "above_low": declared.above_low, "whole": declared.whole, "words": declared.words(unit),
                "file_low": self.file_low, "file_high": self.file_high}


def _code(text: str, skip: str) -> list[str]:
    """A program's code to compare: its lines without comments, framing, or the line of `skip`."""
    code = []
    for line in text.splitlines():
        line = line.split(" # ", 1)[0].rstrip()
        if line.lstrip().startswith("#") or line.startswith(FRAMING) or line.startswith(f"{skip} = "):
            continue
        code.append(line)
    return code


def _same_program(setup, name: str, value: float, base: list[str], integrator) -> bool:
    """Whether the program for setup with name = value is `base` but for that constant's line."""
    try:
        changed = setup.with_values(**{name: value})
        changed.build()
        text = program(changed, integrator=integrator, web=True, arrows=(), page=True, header=False)
    except (ValueError, ProgramError):
        return False
    return _code(text, name) == base


def settable(setup, *, integrator=None, view: dict) -> list[Settable]:
    """The constants the page may change and the span of each: every plain number (not a count)
    whose line in the constants block can take the ends of its slider's span (a tenth to three
    times the scene's value, or from 0: scenes/_sliders.py's slider_range) and give the program
    the writer writes for them. From 0, a force's constant switches the force off; its line then
    adds exactly nothing, so the file's program runs it unchanged (probed just above 0)."""
    text = program(setup, integrator=integrator, web=True, arrows=(), page=True, header=False)
    found = []
    for name, constant in setup.constants.items():
        value = setup.values[name]
        if not isinstance(value, (int, float)) or isinstance(value, bool) or DECLARED[name].whole:
            continue
        if not any(line.startswith(f"{name} = ") for line in text.splitlines()):
            continue
        default = constant.value if isinstance(constant.value, (int, float)) else value
        values = round_slider_values(name, float(value), default)
        low, high = (values[0], values[-1]) if values else slider_range(name, float(value), default)[:2]
        base = _code(text, name)
        probes = [low if low > 0 else high * 1e-3, high]
        if all(_same_program(setup, name, probe, base, integrator) for probe in probes if probe != value):
            found.append(Settable(name, float(value), float(default), float(low), float(high)))
    return found


def measured(model, *, view: dict, integrator: str | None) -> dict:
    """The period and the equilibrium of the file's own set-up, worked out by the physics the local
    page uses (physics/period.py, physics/equilibrium.py): each mass's equilibrium, m, and a line
    per mass (at most STEP_MASSES) giving its period measured over the page's window (upward
    crossings of the equilibrium along the graphed axis) beside 2π/ω_d, or why there is none."""
    centre = equilibrium(model.forces, model.state)
    axis = "xyz".index(view["plot"][0])
    covered = False if model.exact is None else np.isfinite(model.exact_where_valid([0.0])[0][0]).all(axis=-1)
    formula, formula_why = formula_period(model.forces, model.state, closed_form=covered)
    end = max(view["window"], model.until)
    every_s = record_spacing(model.forces, model.state.m, model.dt)   # s between samples
    traj, why = None, ""
    if centre is None or every_s is None:
        why = "nothing pulls the mass back to an equilibrium, so the motion does not repeat"
    else:
        engine = model.simulation(integrator)
        try:
            samples = engine.advance(steps_to_reach(end - model.state.t, model.dt),
                                     record=every(max(1, int(every_s / model.dt))))
            traj = trajectory(engine, samples, with_energy=False)
        except BlowUpError as problem:
            why = f"the run blew up ({problem})"
    lines = []
    for i in range(min(model.state.count, STEP_MASSES)):
        head = f"{model.labels[i]}: " if model.state.count > 1 else ""
        if traj is not None:
            x = traj.r[:, i, axis]
            found = measured_period(traj.t, x, centre=float(centre[i, axis]))
            said = (f"T = {number(found.measured)} ± {number(found.spread, 2)} s over {found.cycles} cycles"
                    if found is not None else "no period: " + why_no_period(traj.t, x, centre=float(centre[i, axis])))
        else:
            said = "no period: " + why
        if formula is not None and np.isfinite(formula[i]):
            said += f"; 2π/ω_d = {number(formula[i])} s"
        lines.append(head + said)
    return {"equilibrium": None if centre is None else centre.tolist(), "axis": axis,
            "period": lines, "window": end, "formula_note": formula_why if formula is None else ""}


def sliders(setup, view: dict, offered: dict[str, Settable]) -> dict[str, dict]:
    """The page's sliders: the local page's (scenes/_sliders.py), for the constants this file can change."""
    made = {}
    for name in slider_names(setup, view):
        if name not in offered:
            continue
        value, default = float(setup.values[name]), offered[name].scene_default
        values = round_slider_values(name, value, default)
        low, high, step = slider_range(name, value, default)
        made[name] = {"values": values or None, "low": low, "high": high, "step": step}
    return made


def page(setup, *, integrator: str | None = None, arrows=None, end: float | None = None) -> str:
    """The whole HTML file for a configured scene (scenes._catalog.Setup), as text.

    integrator  the method the page starts with (None: the scene's own, else euler-cromer); the file
                holds the program for every method, which the address can choose
    arrows      the arrows shown at first (None: the scene's VIEW's)
    end         when the program stops, s (--until; None: as long as the page's graph shows)

    Raises ProgramError, or ValueError from the scene's build, with a one-line message.
    """
    model = setup.build()
    view = {**DEFAULT_VIEW, **setup.hooks.view}
    shown = tuple(view["arrows"] if arrows is None else arrows)
    fixed = list(model.integrators) if model.integrators is not None else None
    first = model.methods(integrator)[0]
    names = [first] if fixed else [first] + [name for name in INTEGRATORS if name != first]
    programs = {name: program(setup, integrator=None if fixed else name, web=True, arrows=shown, page=True,
                              end=end)
                for name in names}
    offered = {found.name: found for found in settable(setup, integrator=None if fixed else first, view=view)}
    # the Add a force box: its programs for the integrator the page starts with (a few programs each)
    forces = offline_forces.box_data(setup, integrators={first: None if fixed else first}, shown=shown, end=end,
                                     pages=programs)
    methods = sorted(set(fixed or INTEGRATORS))
    framed = frame(model, view)   # the local page's camera (export/framing.py), and room for the arrows
    scales = choose_scales(model, view=view, integrator=first if not fixed else None, forces="forces" in shown)
    reach = max(framed.camera.range, scales.view_range) if shown else framed.camera.range
    data = {
        "scene": setup.name,
        "until": float(model.until),   # the question time: where Jump to t starts
        "programs": programs,
        "integrator": first,
        "scene_integrator": model.methods()[0],
        "fixed_methods": fixed,
        "constants": {name: found.as_data() for name, found in offered.items()},
        "all_constants": list(setup.constants),
        "smallest": 1e-9,
        "sliders": sliders(setup, view, offered),
        "arrows": {"kinds": list(ARROWS), "see_through": SEE_THROUGH, "legend": scales.legend()},
        "camera": {"centre": [float(x) for x in framed.camera.centre], "range": float(reach),
                   "pitch": float(framed.camera.pitch), "fov": FOV},
        "speeds": SPEEDS,
        "measured": {**measured(model, view=view, integrator=None if fixed else first),
                     "radius": float(framed.radius)},
        "step": {"layouts": {name: dict(zip(("lines", "drift"), step_layout(name))) for name in methods},
                 "kicks_once": {name: INTEGRATORS[name].kicks_once for name in methods},
                 "labels": list(model.labels), "masses": STEP_MASSES},
        "describe": {**template_data(model), "m": [float(m) for m in model.state.m]},   # export/description.py
        "forces": forces,
    }
    text = _document(setup, data, shown=shown)
    if len(text.encode("utf-8")) > MAX_BYTES:
        raise ProgramError(f"the page would be {len(text.encode()) / 1e6:.1f} MB, more than {MAX_BYTES / 1e6:g} MB")
    return text


def _json(data) -> str:
    """JSON to put inside a <script> element: nothing in it can end the element."""
    return json.dumps(data, ensure_ascii=False).replace("</", "<\\/").replace("<!--", "<\\u0021--")


def _read(path: str) -> str:
    with open(path, encoding="utf-8") as file:
        return file.read()


def _document(setup, data: dict, *, shown) -> str:
    title = description(setup)[0].lstrip("# ")
    notice = _read(NOTICE).replace("--", "- -")    # an HTML comment may not hold "--"
    arrows = "".join(f'<label><input type="checkbox" id="arrow-{kind}"{" checked" if kind in shown else ""}> '
                     f'{html.escape(ARROW_LABELS[kind])}</label> ' for kind in ARROWS)
    slider_rows = "".join(
        f'<div class="slider"><input type="range" id="slider-{name}" aria-label="{html.escape(symbol(name))}" '
        + (f'min="0" max="{len(spec["values"]) - 1}" step="1"' if spec["values"] else
           f'min="{spec["low"]!r}" max="{spec["high"]!r}" step="{spec["step"]!r}"')
        + f'> <span id="slider-{name}-value"></span></div>' for name, spec in data["sliders"].items())
    # GlowScript's compiler compiles once per load of its file (its own editor page loads the file
    # again for every run), so the page keeps the file as text and runs it before each compile.
    scripts = "".join(f'<script type="text/x-glowscript-compiler" id="compiler">{library(name)}</script>\n'
                      if name == COMPILER else f"<script>{library(name)}</script>\n" for name, _ in LIBRARIES)
    speeds = "".join(f'<option{" selected" if value == 1 else ""}>{label}</option>' for label, value in SPEEDS.items())
    return f"""<!DOCTYPE html>
<!-- The spring-mass simulator's offline page (python main.py {setup.name} --html): {html.escape(title)} -->
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(setup.name)}: spring-mass simulator (offline page)</title>
<!--
This file holds GlowScript 3.2 and the libraries bundled in it, each under its own licence:

{notice}
-->
<style>{_read(STYLE) % {"body": BODY_PX, "projector": PROJECTOR_PX}}{page_access.STYLE}{offline_forces.STYLE}</style>
</head>
<body>
<h1>{html.escape(title)}</h1>
<main>
<div id="view"></div>
<div id="panel">
<div class="buttons"><button id="run" type="button">Pause</button> <button id="step-button" type="button">Step</button>
<button id="reset" type="button">Reset</button>
<label>jump to t = <input id="jump-t" type="text" inputmode="decimal" size="5" value="{_short_time(data["until"])}"></label> s
<button id="jump" type="button">Jump</button> <label>speed <select id="speed">{speeds}</select></label>
<span id="time" class="time">t = 0.00 s</span></div>
<p id="status" class="status" role="status"></p>
<p class="describe"><button id="describe" type="button">Describe (D)</button>
<span id="description" class="sm-description" role="status" aria-live="polite" aria-atomic="true"></span></p>
<div class="arrows">arrows: {arrows}<br><span class="legend">{html.escape(data["arrows"]["legend"])}</span></div>
{slider_rows}
<div class="measure"><label><input type="checkbox" id="show-equilibrium"> equilibrium</label>
<label><input type="checkbox" id="show-period"> period</label>
<span id="measure-note" class="note"></span><pre id="period" class="period" hidden></pre></div>
<p class="hint">Moving a slider restarts the run from t = 0.
<label><input type="checkbox" id="projector"> projector</label></p>
<p class="hint">{keys_html()}</p>
<h2>Answer at the question time</h2>
<pre id="answer" class="answer"></pre>
<pre id="step" class="step"></pre>
<p class="link"><label for="link">This set-up's link (add it to the file's address once the file is on a web site):</label>
<input id="link" readonly size="28"></p>
<details><summary>The program this page runs (Web VPython 3.2)</summary><pre id="program-text"></pre></details>
{offline_forces.box_html(data["forces"])}
</div>
</main>
<script type="application/json" id="offline-data">{_json(data)}</script>
{scripts}{plain_ticks(clear_outside=False)}
<script>{page_access.script()}</script>
<script>{_read(offline_forces.SCRIPT)}</script>
<script>{_read(SCRIPT)}</script>
<script>{page_access.install_call(viewLabel=VIEW_LABEL)}</script>
</body>
</html>
"""


def link_fragment(setup, integrator: str | None = None) -> str:
    """The address fragment of a set-up, in `--set`'s grammar: each constant that differs from
    the scene's own value, then the integrator where it is not the scene's (`k=60&integrator=rk4`).
    An offline page of the scene served over http(s) reads it from its address; '' for the scene
    as shipped."""
    parts = []
    for name, constant in setup.constants.items():
        value, shipped = setup.values[name], constant.value
        if value is None or value == shipped:
            continue
        text = ",".join(_short(x) for x in value) if isinstance(value, (tuple, list)) else _short(value)
        parts.append(f"{name}={text}")
    model = setup.build()
    if integrator is not None and model.integrators is None and integrator != model.methods()[0]:
        parts.append(f"integrator={integrator}")
    return "&".join(parts)


def _short_time(t: float) -> str:
    """The question time as the Jump box shows it: 0.2, 30."""
    return f"{t:g}"


def _short(x) -> str:
    """A number as the address writes it: as short as reads back exactly (60, 0.05, 1e-07)."""
    x = float(x)
    return str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)


def check_page_path(path: str, *, overwrite: bool = False) -> None:
    """Raise OutputError (one line) if the page cannot be written to path: files.check_writable's
    checks (an existing file is replaced only where it is ours, unchanged: export/marks.py)."""
    files.check_writable(path, what="the offline page", overwrite=overwrite)


def write_page(path: str, text: str, *, overwrite: bool = False) -> None:
    """Write the page whole (a temporary file renamed over the target), after check_page_path,
    stamped with its mark line and fingerprint under <!DOCTYPE html> (export/marks.py stamped)."""
    check_page_path(path, overwrite=overwrite)
    files.write_text(path, files.stamped(text), what="the offline page", overwrite=overwrite)
