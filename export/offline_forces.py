"""The offline page's "Add a force" box: what its script (export/force_box.js) needs to write the
student's forces into the program GlowScript runs, with no Python in the browser.

The program with forces added is the program `--force` writes (export/vpython_program.py: each
force's line `F_push = vector(2, 0, 0)` before every F_net, its term in each sum, its arrow). The
page cannot run that writer, so the writer runs here, once, with a place held for the forces: a
SlotForce, written as one marked line at each place a force is worked out,

    F_⁂ = ⟦t=(t + h)⟧⟦r=r_s⟧⟦v=v⟧⟦m=m⟧      # ⁂

which names the program's own spellings there (rk4's r_s, a row's pos[i]), and as the term F_⁂ in
each sum, the name ⁂ among the force arrows' names and F_⁂ in their lines. The script puts each
force the student wrote in its place (its line written from the grammar's tree as
physics/expression.py's program_text writes it, the arrows numbered on), takes out the constants
only the place held (a line `b = 0` where no force reads b), and gives the header's command the
forces as --force options. tests/test_force_box_offline.py holds the script's programs to the
writer's own, line for line (the framing of the picture aside: it keeps the file's).

Each integrator the page offers has the programs for a place that reads v and one that does not
(verlet kicks twice, and euler-cromer works v out, only where a force reads v), for the page
(with its controls' lines) and for the "Download my program" button (the handout, as --webvpython
writes it, with the arrows the page shows and each force's).
"""
from __future__ import annotations

import html
import os
from dataclasses import dataclass

from physics.expression import CONSTANT_NAMES, grammar, parse
from physics.forces import FORCES
from physics.forces.base import _new_like
from physics.forces.written import WrittenForce
from physics.state import velocity
from scenes import DECLARED
from scenes._written import scene_constants

from .arrows import LABEL_PX
from .lines import COMMENT_COLUMN
from .vpython_program import program

# What only frames the picture (the sphere's size, the support, the arrows' scales): the page keeps
# the file's (export/offline_page.py's FRAMING), and the programs with forces get it too.
FRAMING = ("radius = ", "box(", "pscale = ", "Fscale = ")

SLOT = "⁂"
OPEN, CLOSE = "⟦", "⟧"


@dataclass(frozen=True, eq=False)
class SlotForce(WrittenForce):
    """The place of the forces the page adds: no force at all (zero), written as a marked line."""

    def __call__(self, t, r, v, m):
        F = _new_like(r)
        F[...] = 0.0
        return F

    def program(self):
        sites = "".join(f"{OPEN}{name}={{{name}}}{CLOSE}" for name in ("t", "r", "v", "m"))
        return ((f"{self.TERM} = {sites}", SLOT),)


FORCES.remove(SlotForce)     # a place in a program, not a force of the physics: nothing lists it


def slot(constants: dict, *, velocity: bool) -> SlotForce:
    """The place, reading every constant of the scene a force may read (and v, if `velocity`), so
    that the program has each one's line for a force that reads it."""
    text = "r*t*m" + "".join(f"*{name}" for name in constants) + ("*mag(v)" if velocity else "")
    return SlotForce(SLOT, parse(text), constants)


def _constant_lines(text: str) -> set[str]:
    return {name for name in CONSTANT_NAMES if any(line.startswith(f"{name} = ") for line in text.splitlines())}


def templates(setup, *, integrators: dict, shown, end, pages: dict) -> dict:
    """For each integrator: the page's programs with the place for forces ("page", and "page_v"
    where it reads v), the handout's ("handout", "handout_v"), the handout with none ("handout_none")
    and, where the file has forces of its own, the page's with none ("page_none"); each without its
    header (the script puts the page program's own header on). "optional": the constants whose lines
    only the place put there, by program. `integrators`: the page's name of each program and the
    writer's integrator for it (None where the scene fixes each mass's); `pages`: the page's own
    programs, by that name."""
    bare = setup.with_written(())
    model = bare.build()
    constants = scene_constants(setup.values, model)
    reads_v = any(force.uses_velocity for force in model.forces)
    arrows = tuple(dict.fromkeys((*shown, "forces")))
    made = {}
    for key, integrator in integrators.items():
        def written(page: bool, velocity: bool | None) -> str:
            added = () if velocity is None else (slot(constants, velocity=velocity),)
            return program(bare, integrator=integrator, web=True, arrows=shown if page else arrows, page=page,
                           end=end, header=False, added=added)
        texts = {"page": written(True, False), "handout": written(False, False), "handout_none": written(False, None)}
        if not reads_v:
            texts.update(page_v=written(True, True), handout_v=written(False, True))
        if setup.written:
            texts["page_none"] = written(True, None)
        nones = {"page": texts.get("page_none", pages[key]), "handout": texts["handout_none"]}
        texts["optional"] = {kind: sorted(_constant_lines(texts[kind]) - _constant_lines(nones[kind.split("_")[0]]))
                             for kind in ("page", "page_v", "handout", "handout_v") if kind in texts}
        made[key] = texts
    return made


def box_data(setup, *, integrators: dict, shown, end, pages: dict) -> dict:
    """What the page's script reads for the box (#offline-data's "forces"): the grammar, the
    scene's constants a force may read, the labels taken, the file's own forces, where the masses
    start (to judge a force there), the place's markers and the programs (templates)."""
    model = setup.build()
    bare = setup.with_written(()).build()
    constants = scene_constants(setup.values, bare)
    return {
        "grammar": grammar(),
        "constants": {name: {"unit": DECLARED[name].unit, "meaning": DECLARED[name].meaning or name}
                      for name in constants},
        "taken": [force.LABEL for force in bare.forces],
        "terms": [force.TERM for force in bare.forces],
        "start": [list(pair) for pair in setup.written],
        "state": {"r": model.state.r.tolist(), "v": velocity(model.state.p, model.state.m).tolist(),
                  "m": model.state.m.tolist(), "t": float(model.state.t), "values": constants},
        "slot": {"name": SLOT, "open": OPEN, "close": CLOSE, "index": len(bare.forces),
                 "xoffset": LABEL_PX["xoffset"], "column": COMMENT_COLUMN, "framing": list(FRAMING)},
        "programs": templates(setup, integrators=integrators, shown=shown, end=end, pages=pages),
    }


SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "force_box.js")
STYLE = """
#force-box { border-top: 1px solid #888; margin-top: 10px; padding-top: 4px; }
#force-box label { white-space: nowrap; }
#force-example { max-width: 100%; }
#force-box input[type=text] { font-family: monospace; }
#force-text { width: 95%; }
#force-line { font-size: inherit; }
.force-said { margin: 4px 0; font-weight: 600; min-height: 1.3em; }
.force-said.problem { color: #a00000; }
#force-list { margin: 4px 0; padding-left: 1.2em; }
#force-list li { margin: 2px 0; font-family: monospace; }
#force-list button { font-family: sans-serif; }
.force-names { margin: 4px 0; }
"""


def box_html(data: dict) -> str:
    """The box: an example menu, the force's name and its expression (Enter adds it), the one line
    that says what happened, the program's F_net line, the forces added (each with its Remove
    button), back to the file's program, and Download my program; every control labelled."""
    names = "; ".join(f"{name}" + (f" ({', '.join(named['aliases'])})" if named["aliases"] else "")
                      for name, named in data["grammar"]["names"].items()
                      if name not in data["grammar"]["constants"] or name in data["constants"])
    functions = ", ".join(data["grammar"]["functions"])
    return f"""<section id="force-box" aria-labelledby="force-box-title">
<h2 id="force-box-title">Add a force</h2>
<form id="force-form" autocomplete="off">
<label for="force-example">start from</label> <select id="force-example"><option value="">an example…</option></select><br>
<label for="force-name">name</label> <input type="text" id="force-name" size="10" maxlength="20" spellcheck="false">
<label for="force-text">F =</label> <span class="note">(N, a vector)</span><br>
<input type="text" id="force-text" maxlength="300" spellcheck="false" placeholder="vector(2, 0, 0)">
<button id="force-add" type="submit">Add and run</button>
</form>
<p id="force-said" class="force-said" role="status" aria-live="polite"></p>
<p>the program's line: <code id="force-line"></code></p>
<ul id="force-list" aria-label="forces added"></ul>
<button id="force-reset" type="button">Back to the file's program</button>
<button id="force-download" type="button">Download my program</button>
<details class="force-names"><summary>What a force may use</summary>
<p>names: {html.escape(names)}, pi<br>functions: {html.escape(functions)}<br>
+ − * / and ** (a power); a force is a vector: vector(x, y, z), or a number times a direction, like -2*hat(v).</p></details>
</section>"""
