"""A scene as a standalone VPython program: the page's program, written out for one configured case.

The page teaches with a short VPython program: constants at the top, a support, a helix and a
sphere, a graph, and one `while` loop in which the momentum update is written out. This module
writes that program for any scene with its constants, preset and integrator as chosen, so a
teacher can set a case up and hand it to the class to read and edit:

    m = 10                   # kg: mass of the block
    ...
    while t < t_end:
        rate(1/dt)
        L = pos - anchor
        Fspring = k*(L0/mag(L) - 1)*L         # Hooke's law: F = −k (|L| − L0) L̂
        Fgravity = m*vector(0, -g, 0)          # gravity: F = m g, down (−y)
        Fnet = Fspring + Fgravity
        p = p + Fnet*dt                        # momentum principle: p_f = p_i + F_net Δt
        pos = pos + p/m*dt                     # r_f = r_i + v_f Δt, with v_f = p_f / m
        ...

Its arithmetic is the engine's, line for line: every force is written the way physics/forces/
works it out (Hooke's law as k (L0/|L| − 1) L, drag as −½ C A ρ |v| v), the forces are added in the
scene's order, and the integrator's update is the one in physics/integrators.py, in the same
order of operations (euler-cromer works out v_i only where a force needs it; verlet's extra half
kick for velocity-dependent forces; rk4's (k1 + 2 k2 + 2 k3 + k4) Δt/6). Time is n·Δt from a
whole number of steps. The program runs as long as the page's graph shows (VIEW's window, or
--until; :func:`run_end`) and, on the way, prints its answer at the step at which a headless run
to the scene's question time `until` stops (physics.simulate.steps_to_reach), rounded as the
command line writes it: `at t = 0.2 s: r = < 0, -1.7301, 0 > m, ...` is `python main.py SCENE
--headless`'s answer, and its state at t_end is a headless run's to t_end, to round-off
(tests/test_export.py checks both for every scene).

The numbers come from the scene's model (the force objects and the initial state), written with
repr, so the program starts from exactly the same values. Constants are named as in the scene
files, with their unit (scenes/_constants.py's DECLARED) and their meaning from the scene's
constants block. Scenes with several masses keep a list per quantity that differs between the
masses and step each mass in a for loop; where a list follows a rule of the scene's build from its
constants (a row of anchors `spacing` apart, ω from omega_min to omega_max), the program writes
those constants and builds the list with the same arithmetic (the scene declares those rules as
data, Model.per_mass; see export/program_masses.py).

The writer is split by job, each reading declarations rather than knowing forces or scenes:
program_constants.py (the constants block), program_forces.py (each force's declared line and
each integrator's template), program_masses.py (the lists of a row), program_objects.py (what is
drawn), program_command.py (the header's command) and exact_curve.py (the closed form). Lines that
another writer adds go in at two places here: after the objects (:func:`scene_setup_lines`) and
in the loop after each mass's momentum update (:func:`after_update_lines`).

The Web VPython form (glowscript.org, trinket) is the same program with `Web VPython 3.2` as its
first line instead of the import line.
"""
from __future__ import annotations

import math

import numpy as np

from physics.integrators import INTEGRATORS
from physics.simulate import steps_to_reach
from scenes import DECLARED
from scenes._view import DEFAULT_VIEW, MAX_DRAWN_MASSES
from scenes._written import add_forces

from . import program_arrows, program_page
from .exact_curve import exact_lines, plot_line
from .lines import ProgramError, align_comments, commented, vector
from .palette import EXACT_COLOUR, EXACT_WIDTH
from .program_answer import HELPERS, answer_line
from .program_command import command, description
from .program_constants import ProgramConstants, constants_block
from .program_forces import ProgramForces, update
from .program_masses import anchor, mass_count, masses, which_mass
from .program_objects import objects

WEB_FIRST_LINE = "Web VPython 3.2"
# vpython 7.6.5's own server listens on every network interface and serves any file on the disk to
# a crafted request: the two lines after the import keep it on this computer (issue 20).
IMPORTS = ["from vpython import *",
           "import socket  # vpython's server would show files of this computer to the whole network: keep it here (Web VPython has none)",
           "socket.socket.bind = lambda s, a, bind=socket.socket.bind: bind(s, ('127.0.0.1', *a[1:]) if a[0] in ('', '0.0.0.0') else a)"]


def program(setup, *, integrator: str | None = None, web: bool = False, arrows=None,
            end: float | None = None, page: bool = False, header: bool = True, added=()) -> str:
    """The VPython program for a configured scene (scenes._catalog.Setup), as text.

    integrator  the method (default: the scene's own, else euler-cromer, the page's update), as
                Model.methods picks it; scenes that step each mass with its own method
                (integrators) keep theirs, as headless runs do.
    web         True for Web VPython (first line `Web VPython 3.2`, no imports).
    arrows      the arrows to draw (export/program_arrows.py: p, F_net, forces, split); None: the scene's VIEW's
    end         when the program stops, s (the command line's --until); None: run_end's choice.
                It prints its answer at the scene's question time, `until`, on the way.
    page        the program the offline page runs (export/offline_page.py): every kind of arrow
                written (`arrows` are the ones shown at first, which set the scales), the page's
                controls section and reports (export/program_page.py), and the question time's
                step worked out from until and dt as the program runs.
    header      False leaves out the header's comments (its description and the command of the
                same case, which takes most of the time to write): to compare programs' code.
    added       forces added after the model's own (export/offline_forces.py's place for the forces
                the offline page's box adds)

    Raises ProgramError, or ValueError from the scene's build function, with a one-line message.
    """
    model = setup.build()
    if added:
        model = add_forces(model, added)
    _check_size(setup, model)
    case = _Case(setup, model, integrator, arrows, end, page)
    lines = IMPORTS + (case.header() if header else []) + case.constants_lines()
    lines += program_page.controls_lines() if page else []
    lines += ["", "# ---- the objects ----"] + objects(model, case.view, case.constants, case.single)
    lines += case.exact_objects() + scene_setup_lines(case)
    lines += HELPERS + case.loop() + case.answer()
    lines = align_comments(lines)
    if web:
        lines = [WEB_FIRST_LINE] + [line for line in lines if line not in IMPORTS]
    return "\n".join(lines) + "\n"


def scene_setup_lines(case) -> list[str]:
    """Lines after the objects are made, before the loop: where another writer adds objects of its
    own, from case.model and case.constants (the arrows, export/program_arrows.py)."""
    written = program_arrows.WRITTEN if case.page else case.arrows
    lines = program_arrows.setup_lines(case.model, shown=case.arrows, integrator=case.integrator,
                                       single=case.single, view=case.view, written=written)
    if case.page:
        lines += ["", program_page.drawn_line(single=case.single,
                                              arrows=program_page.arrow_objects(written, single=case.single))]
    return lines


def after_update_lines(case) -> list[str]:
    """Lines in the loop after one mass's momentum update, before time moves on: where another
    writer adds what follows the update (the arrows). `case.index` is "" for one
    mass or "[i]" inside the loop over the masses."""
    written = program_arrows.WRITTEN if case.page else case.arrows
    lines = program_arrows.loop_lines(case.model, shown=written, single=case.single)
    terms = [force.TERM for force in case.model.forces]
    return lines + ([program_page.stepped_line(single=case.single, m=case.m, terms=terms)] if case.page else [])


def _check_size(setup, model) -> None:
    count = model.state.count
    if count > MAX_DRAWN_MASSES:
        whole = [name for name in setup.constants if DECLARED[name].whole]
        raise ProgramError(f"{count:,} masses are more than the {MAX_DRAWN_MASSES:,} a program (like the page) "
                           f"can draw" + (f"; make {' or '.join(whole)} smaller" if whole else ""))


class _Case:
    """One configured case being written: its model, methods, view, named values and forces."""

    def __init__(self, setup, model, integrator, arrows=None, end=None, page=False):
        self.setup, self.model, self.integrator, self.page = setup, model, integrator, page
        self.methods = model.methods(integrator)
        self.view = {**DEFAULT_VIEW, **setup.hooks.view}
        self.arrows = self.view["arrows"] if arrows is None else arrows
        self.single = model.state.count == 1
        self.index = "" if self.single else "[i]"
        self.constants = ProgramConstants(setup, model.state.count, model.forces)
        self.constants.add("m", model.state.m)
        self.forces = ProgramForces(model, self.constants)
        self.constants.add("r0", model.state.r, is_vector=True)
        self.constants.add("v0", _start_velocity(setup, model), is_vector=True)
        self.constants.add("dt", model.dt)
        self.end = run_end(model, self.view, end)
        if page:   # always a t_end, with the answer in the loop: a new until or Δt moves only n_until
            self.end = max(self.view["window"], model.until) if end is None else max(float(end), model.until)
        if self.end is None:
            self.constants.add("until", model.until)
        else:
            self.constants.add("until", model.until, meaning="s: question time: the answer below is printed then")
            self.constants.add("t_end", self.end, meaning="s: when the program stops"
                               + (" (as long as the page's graph shows)" if end is None else ""))
        self.axes = list(self.view["plot"])
        self.m = self.constants.name("m")
        self.exact = (exact_lines(model, self.constants, self.forces, axis=self.axes[0], m=self.m)
                      if self.view["exact"] and len(self.axes) == 1 else None)

    def header(self) -> list[str]:
        methods = self.methods
        how = f"the {methods[0]} integrator" if len(set(methods)) == 1 else "each mass's own integrator (the list method)"
        return [*description(self.setup),
                f"# It steps with {how}. Edit the constants and run it again.",
                f"# The same case on the simulator's page: {command(self.setup, self.model, self.integrator)}"]

    def constants_lines(self) -> list[str]:
        lists, used = masses(self.setup, self.model, self.constants, self.methods)
        lines = ["", "# ---- constants (unit: meaning) ----"] + constants_block(self.setup, self.constants, used)
        return lines + (["", "# ---- the masses: one spring each ----"] + lists if lists else [])

    def exact_objects(self) -> list[str]:
        if self.exact is None:
            return []
        curve = f"gcurve(color={vector(EXACT_COLOUR)}, width={EXACT_WIDTH}"
        made = f"{curve}, label=\"exact\")" if self.single else f"[{curve}) for i in range({mass_count(self.constants)})]"
        lines = [commented(f"exact = {made}", "the closed form: thin, drawn on top")]
        return lines + ([""] + self.exact[0] if self.single else [])

    def loop(self) -> list[str]:
        lines = ["", "# ---- the loop: one momentum update per step ----",
                 commented("t = 0", "s: time, n·Δt after n steps"), "n = 0"]
        lines += [line[4:] for line in self._each_mass(self.plot_position())]   # t = 0 (the exact curve from the first step)
        if self.page:
            return lines + self._page_loop()
        asked_at_start = steps_to_reach(self.model.until - self.model.state.t, self.model.dt) == 0
        if self.end is not None and asked_at_start:
            lines += self.printed()
        lines += [_loop_condition(self.model, self.end), commented("    rate(1/dt)", "real time: 1/Δt steps a second")]
        lines += self._each_mass(self.update() + after_update_lines(self))
        lines += ["    n = n + 1", commented("    t = n*dt", "a whole number of steps: no round-off piles up")]
        lines += self._each_mass(self.draw())
        if self.end is None or asked_at_start:
            return lines
        return lines + [commented(f"    if {_question_condition(self.model)}:", "the question time: where is the mass now?"),
                        *("        " + line for line in self.printed())]

    def _page_loop(self) -> list[str]:
        """The loop of the offline page's program: the handout's, with the question time's step
        worked out as it runs (program_page.question_lines), since the page may change until or Δt."""
        lines = program_page.question_lines()
        lines += [f"if {program_page.QUESTION_CONDITION}:", *("    " + line for line in self.printed())]
        lines += [_loop_condition(self.model, self.end), commented("    rate(1/dt)", "real time: 1/Δt steps a second")]
        lines += self._each_mass(self.update() + after_update_lines(self))
        lines += ["    n = n + 1", commented("    t = n*dt", "a whole number of steps: no round-off piles up")]
        lines += self._each_mass(self.draw())
        return lines + [commented(f"    if {program_page.QUESTION_CONDITION}:", "the question time: where is the mass now?"),
                        *("        " + line for line in self.printed())]

    def _each_mass(self, body: list[str]) -> list[str]:
        """body in the loop: as it is for one mass, else in a for loop over the masses."""
        if self.single:
            return ["    " + line for line in body]
        return ["    for i in range(len(pos)):"] + ["        " + line for line in body]

    def update(self) -> list[str]:
        """One step of each mass's method: its integrator's template, with the forces' lines."""
        i, m = self.index, self.m
        if len(set(self.methods)) == 1:
            return update(self.methods[0], self.forces, r=f"pos{i}", p=f"p{i}", m=m)
        body = []
        for name in (name for name in INTEGRATORS if name in self.methods):
            body.append(f"{'elif' if body else 'if'} method[i] == \"{name}\":")
            body += ["    " + line for line in update(name, self.forces, r="pos[i]", p="p[i]", m=m)]
        return body

    def plot_position(self) -> list[str]:
        i = self.index
        return [f"position{i}" + (f"[{k}]" if len(self.axes) > 1 else "") + f".plot(t, pos{i}.{axis})"
                for k, axis in enumerate(self.axes)]

    def draw(self) -> list[str]:
        i, n, axes = self.index, self.constants.name, self.axes
        lines = [f"{'ball' if self.single else 'balls[i]'}.pos = pos{i}",
                 commented(f"spring{'' if self.single else 's[i]'}.axis = pos{i} - {n(anchor(self.constants))}",
                           "the helix follows the sphere")]
        lines += self.plot_position()
        if self.exact is not None:
            lines += self.exact[1] if self.single else self.exact[0] + self.exact[1]
            lines += [plot_line(self.constants, index=i, axis=axes[0])]
        return lines

    def answer(self) -> list[str]:
        """The answer after the loop, where the loop ends at the question time (else it is in the loop)."""
        return [] if self.end is not None else ["", "# ---- the answer ----", *self.printed()]

    def printed(self) -> list[str]:
        """print() of t, r and p as the command line writes them: `at t = 0.2 s: r = < 0, -1.7301,
        0 > m, p = < 0, -15.21, 0 > kg·m/s`, by the program's number() (export/program_answer.py),
        which gives the same digits in Web VPython."""
        if self.single:
            return [f"print({answer_line('')})"]
        return ["for i in range(len(pos)):", f"    print({which_mass(self.model, self.constants)},",
                f"          {answer_line('[i]')})"]


def _start_velocity(setup, model):
    """v0 as the scene gives it, where m v0 is the model's start momentum; else v = p/m (the state's)."""
    given = setup.values.get("v0")
    if given is not None and np.array_equal(model.state.m[:, None] * np.asarray(given, dtype=float), model.state.p):
        return given
    return model.state.v


def run_end(model, view, end: float | None) -> float | None:
    """When the program stops, s, where that is after the question time `until`: `end` if given
    (--until), else the time the page's graph shows (VIEW's window), so that a handout whose
    question is at 0.2 s (two steps) still runs long enough to watch. None: it stops at `until`."""
    end = max(view["window"], model.until) if end is None else max(float(end), model.until)
    later = steps_to_reach(end - model.state.t, model.dt) > steps_to_reach(model.until - model.state.t, model.dt)
    return end if later else None


def _loop_condition(model, end: float | None = None) -> str:
    """`while t < until:` (or t_end), unless round-off in n·Δt would make it take another step than
    a headless run."""
    name = "until" if end is None else "t_end"
    t, limit, why = _limit(model.until if end is None else end, model, name)
    return commented(f"while {t} < {limit}:", why)


def _question_condition(model) -> str:
    """`t >= until and (n - 1)*dt < until`: true at the one step at which a headless run to `until`
    stops (see _limit); (n - 1)*dt is the float the step before had as t."""
    t, limit, _ = _limit(model.until, model, "until")
    return f"n == {limit}" if t == "n" else f"t >= {limit} and (n - 1)*dt < {limit}"


def _limit(limit: float, model, name: str) -> tuple[str, str, str]:
    """("t", "until", "") for `t < until`, which takes the steps of a headless run to `limit` unless
    round-off in n·Δt makes it take one more or fewer; then the limit that does, and why."""
    steps = steps_to_reach(limit - model.state.t, model.dt)
    if _steps_while_below(limit, model.dt) == steps:
        return "t", name, ""
    if _steps_while_below(limit - 1e-9 * model.dt, model.dt) == steps:
        return "t", f"{name} - 1e-9*dt", "1e-9·Δt forgives round-off in n·Δt"
    return "n", str(steps), f"the steps that reach {name}"


def _steps_while_below(limit: float, dt: float) -> int:
    """How many steps `while t < limit:` takes, with t = n*dt worked out in floats as the program does.

    ceil(limit/Δt) is that count or off by one from round-off (in the division, or in n*dt), so at
    most one step either way corrects it: the work does not grow with the number of steps.
    """
    steps = max(0, math.ceil(limit / dt))
    if steps > 0 and (steps - 1) * dt >= limit:
        steps -= 1
    elif steps * dt < limit:
        steps += 1
    return steps
