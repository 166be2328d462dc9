"""A scene as a standalone VPython program: the page's program, written out for one configured case.

The page teaches with a short VPython program: constants at the top, a support, a helix and a
sphere, a graph, and one `while` loop in which the momentum update is written out. This module
writes that program for any scene with its constants, preset and integrator as chosen, so a
teacher can set a case up and hand it to the class to read and edit:

    m = 10                   # kg: mass of the block
    ...
    while t < until:
        rate(1/dt)
        L = pos - anchor
        Fspring = k*(L0/mag(L) - 1)*L         # Hooke's law: F = −k (|L| − L0) L̂
        Fgravity = m*vector(0, -g, 0)          # gravity: F = m g, down (−y)
        Fnet = Fspring + Fgravity
        p = p + Fnet*dt                        # momentum principle: p_f = p_i + F_net Δt
        pos = pos + p/m*dt                     # r_f = r_i + v_f Δt, with v_f = p_f / m
        ...

Its arithmetic is the engine's, line for line: every force is written the way physics/forces.py
works it out (Hooke's law as k (L0/|L| − 1) L, drag as −½ C A ρ |v| v), the forces are added in the
scene's order, and the integrator's update is the one in physics/integrators.py, in the same
order of operations (euler-cromer works out v_i only where a force needs it; verlet's extra half
kick for velocity-dependent forces; rk4's (k1 + 2 k2 + 2 k3 + k4) Δt/6). Time is n·Δt from a
whole number of steps, and the loop stops after the same number of steps as a headless run
(physics.simulate.steps_to_reach), so the program's final position and momentum are those of
`python main.py SCENE --headless` to round-off (tests/test_export.py checks this for every scene).

The numbers come from the scene's model (the force objects and the initial state), written with
repr, so the program starts from exactly the same values. Constants are named as in the scene
files, with their unit (scenes/_constants.py's DECLARED) and their meaning from the scene's
constants block. Scenes with several masses keep a list per quantity that differs between the
masses and step each mass in a for loop; where a list follows a rule of the scene's build from its
constants (a row of anchors `spacing` apart, ω from omega_min to omega_max), the program writes
those constants and builds the list with the same arithmetic (see _masses).

The Web VPython form (glowscript.org, trinket) is the same program with `Web VPython 3.2` as its
first line instead of the import line.
"""
from __future__ import annotations

import math
import re

import numpy as np

from physics.forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring
from physics.integrators import INTEGRATORS
from physics.simulate import steps_to_reach
from scenes import DECLARED, ConstantError, catalog, summary
from scenes._view import DEFAULT_VIEW, MAX_DRAWN_MASSES

from . import program_arrows
from .exact_curve import exact_lines
from .lines import (CONSTANT_COLUMN, ProgramError, align_comments, commented, listed, number,
                    unit_and_meaning, vector)
from .numbers import clean
from .palette import (CURVE_COLOURS, EXACT_COLOUR, EXACT_WIDTH, MASS_COLOURS, mass_colours, shade,
                      simulation_width)

WEB_FIRST_LINE = "Web VPython 3.2"
IMPORTS = ["from vpython import *"]

# The meaning of each name the program may use where the scene's constants block has no constant
# of that name with that value (the units are DECLARED's).
MEANINGS = {
    "m": "mass", "k": "spring constant", "L0": "relaxed length of the spring",
    "anchor": "fixed end of the spring", "g": "strength of gravity, along −y",
    "b": "linear damping constant in F = −b v", "C": "drag coefficient",
    "A": "cross-section area, for drag", "rho": "air density, for drag",
    "F0": "driving force amplitude in F = F0 cos(ω t)",
    "omega": "driving angular frequency ω (rad/s, not Hz)",
    "drive_axis": "direction of the driving force (a unit vector)",
    "r0": "start position", "v0": "start velocity",
    "dt": "time step Δt of the momentum update", "until": "when to stop",
}
LABELLED = 6               # more masses than this: no labels on their curves (as the page's legend)
ROUND_OFF = 1e-15          # relative: a rule's list may differ from the model's by this (a few units
                           # in the last place: numpy's linspace sets its last value to the end exactly)


# ---- the program's constants ----

class _Constants:
    """The program's named values, from the model's numbers: one value, or one per mass.

    A name that is one of the scene's constants, with the scene's value, keeps the comment of the
    scene's constants block; otherwise its unit is DECLARED's and its meaning MEANINGS'.
    """

    def __init__(self, setup, count: int):
        self.setup, self.count = setup, count
        self.single: dict[str, object] = {}       # name -> a float, or a 3-tuple for a vector
        self.per_mass: dict[str, np.ndarray] = {}  # name -> (count,) or (count, 3)

    def add(self, name: str, value, *, is_vector: bool = False) -> None:
        """Record a value of the model: one for all the masses, or one per mass where they differ."""
        array = np.asarray(value, dtype=float)
        rows = np.broadcast_to(array.reshape(-1, 3) if is_vector else array.reshape(-1),
                               (self.count, 3) if is_vector else (self.count,))
        varies = not np.all(rows == rows[0])
        value = rows.copy() if varies else (tuple(float(x) for x in rows[0]) if is_vector else float(rows[0]))
        before = self.per_mass.get(name, self.single.get(name))
        if before is not None and not np.array_equal(before, value):
            raise ProgramError(f"two forces use different values of {name}: the program cannot name both")
        (self.per_mass if varies else self.single)[name] = value

    def has(self, name: str) -> bool:
        return name in self.single or name in self.per_mass

    def list_name(self, name: str) -> str:
        """The name of a list with one value per mass: `anchor`, or `b_each` where the scene has a b."""
        return f"{name}_each" if name in self.setup.constants else name

    def name(self, name: str) -> str:
        """How the loop spells a value: `b`, or `b_each[i]` for one value per mass."""
        return f"{self.list_name(name)}[i]" if name in self.per_mass else name

    def comment(self, name: str, *, per_mass: bool = False) -> str:
        """`N/m: spring constant`: the scene's comment where the program's value is the scene's."""
        constant = self.setup.constants.get(name)
        same = (constant is not None and not per_mass and self.setup.values.get(name) is not None
                and np.array_equal(np.asarray(self.setup.values[name], dtype=float),
                                   np.asarray(self.single.get(name, self.setup.values[name]), dtype=float)))
        meaning = _without_none(constant.meaning) if same else MEANINGS.get(name, name)
        return unit_and_meaning(DECLARED[name].unit if name in DECLARED else "",
                                meaning + (", one per mass" if per_mass else ""))


def _without_none(meaning: str) -> str:
    """A scene's meaning without what None means in the scene file: the program has a number."""
    return re.sub(r"\s*\(None\b.*\)\s*$", "", meaning)


def _literal(value) -> str:
    return vector(value) if isinstance(value, (tuple, list, np.ndarray)) else number(value)


def _as_written(value):
    """A value as the program holds it: an int where number() writes a whole number, a numpy
    array for a vector (vpython's vector holds floats)."""
    if isinstance(value, (tuple, list, np.ndarray)):
        return np.asarray(value, dtype=float)
    text = number(value)
    return int(text) if re.fullmatch(r"-?\d+", text) else float(text)


# ---- the forces, written out ----

class _Forces:
    """The scene's forces as lines of the program, in the order physics.forces.net_force adds them."""

    def __init__(self, model, constants: _Constants):
        self.constants = constants
        self.forces = list(model.forces)
        for force in self.forces:
            if isinstance(force, Spring):
                constants.add("k", force.k)
                if not force._zero_length:
                    constants.add("L0", force.L0)
                constants.add("anchor", force.anchor, is_vector=True)
            elif isinstance(force, Gravity):
                if not np.allclose(force.direction, (0.0, -1.0, 0.0), rtol=0, atol=0):
                    raise ProgramError("the program writes gravity along −y only")
                constants.add("g", force.g)
            elif isinstance(force, LinearDamping):
                constants.add("b", force.b)
            elif isinstance(force, QuadraticDrag):
                for name in ("C", "A", "rho"):
                    constants.add(name, getattr(force, name))
            elif isinstance(force, Driving):
                constants.add("F0", force.F0)
                constants.add("omega", force.omega)
                constants.add("drive_axis", force.axis, is_vector=True)
            else:
                raise ProgramError(f"the program cannot write the force {type(force).__name__}")
        self.uses_velocity = any(force.uses_velocity for force in self.forces)

    def lines(self, *, t: str, r: str, v: str, m: str, laws: bool) -> list[str]:
        """Fnet at time t, position r and velocity v: one line per force, then their sum."""
        n = self.constants.name
        out, terms = [], []
        for force in self.forces:
            if isinstance(force, Spring):
                out.append((f"L = {r} - {n('anchor')}", "the spring, from its fixed end to the mass"))
                if force._zero_length:
                    out.append((f"Fspring = -{n('k')}*L", "Hooke's law with L0 = 0: F = −k L"))
                else:
                    out.append((f"Fspring = {n('k')}*({n('L0')}/mag(L) - 1)*L",
                                "Hooke's law: F = −k (|L| − L0) L̂, written k (L0/|L| − 1) L"))
                terms.append("Fspring")
            elif isinstance(force, Gravity):
                out.append((f"Fgravity = {m}*vector(0, -{n('g')}, 0)", "gravity: F = m g, down (−y)"))
                terms.append("Fgravity")
            elif isinstance(force, LinearDamping):
                out.append((f"Fdamping = -{n('b')}*{v}", "linear damping: F = −b v"))
                terms.append("Fdamping")
            elif isinstance(force, QuadraticDrag):
                out.append((f"Fdrag = -0.5*{n('C')}*{n('A')}*{n('rho')}*mag({v})*{v}",
                            "air drag: F = −½ C A ρ |v|² v̂ = −½ C A ρ |v| v"))
                terms.append("Fdrag")
            elif isinstance(force, Driving):
                out.append((f"Fdrive = {n('F0')}*cos({n('omega')}*{t})*{n('drive_axis')}",
                            "driving: F = F0 cos(ω t) along drive_axis"))
                terms.append("Fdrive")
        out.append(("Fnet = " + (" + ".join(terms) or "vector(0, 0, 0)"), "net force: the sum of the forces"))
        return [commented(code, comment if laws else "") for code, comment in out]


# ---- the integrators, written out ----

def _update(method: str, forces: _Forces, *, r: str, p: str, m: str) -> list[str]:
    """The lines of one step of `method` for one mass (position r, momentum p, mass m), before t moves on."""
    def F(t, at, v, laws=False):
        return forces.lines(t=t, r=at, v=v, m=m, laws=laws)

    if method == "euler-cromer":
        # physics.integrators.euler_cromer works out v_i only if a force reads it
        lines = [commented(f"v = {p}/{m}", "velocity from momentum: v = p/m")] if forces.uses_velocity else []
        return lines + F("t", r, "v", laws=True) + [
            commented(f"{p} = {p} + Fnet*dt", "momentum principle: p_f = p_i + F_net Δt"),
            commented(f"{r} = {r} + {p}/{m}*dt", "r_f = r_i + v_f Δt, with v_f = p_f/m"),
        ]
    if method == "euler":
        return [commented(f"v = {p}/{m}", "velocity from momentum: v_i = p_i/m")] + F("t", r, "v", laws=True) + [
            commented(f"{r} = {r} + v*dt", "r_f = r_i + v_i Δt: the OLD velocity (why euler gains energy)"),
            commented(f"{p} = {p} + Fnet*dt", "momentum principle: p_f = p_i + F_net Δt"),
        ]
    if method == "verlet":
        lines = ["# velocity Verlet: half a kick, a drift, half a kick"]
        if forces.uses_velocity:
            lines.append(commented(f"v = {p}/{m}", "velocity at the start of the step"))
        lines += F("t", r, "v", laws=True)
        lines += [commented(f"{p} = {p} + Fnet*(dt/2)", "half a kick: p_½ = p_i + F_i Δt/2"),
                  commented(f"{r} = {r} + {p}/{m}*dt", "drift: r_f = r_i + (p_½/m) Δt")]
        if forces.uses_velocity:   # physics.integrators.verlet's guess of v_f, then the force with it
            lines += [f"v = {p}/{m}",
                      commented("for guess in range(2):", "F needs v_f, not known yet: guess it, then use it")]
            lines += ["    " + line for line in F("(t + dt)", r, "v")]
            lines.append(commented(f"    v = ({p} + Fnet*(dt/2))/{m}", "v_f ≈ (p_½ + F Δt/2)/m"))
        else:
            lines += F("(t + dt)", r, "v")
        lines.append(commented(f"{p} = {p} + Fnet*(dt/2)", "half a kick with the force at the end"))
        return lines
    if method == "rk4":
        return [
            commented("dr = []", "rk4: the slopes dr/dt = v and dp/dt = F_net at four points of the step"),
            "dp = []",
            "v = vector(0, 0, 0)",
            "Fnet = vector(0, 0, 0)",
            commented("for h in [0, dt/2, dt/2, dt]:", "each point: h ahead along the slope before"),
            f"    r_s = {r} + v*h",
            f"    p_s = {p} + Fnet*h",
            f"    v = p_s/{m}",
            *("    " + line for line in F("(t + h)", "r_s", "v", laws=True)),
            "    dr.append(v)",
            "    dp.append(Fnet)",
            commented(f"{r} = {r} + (dr[0] + 2*dr[1] + 2*dr[2] + dr[3])*(dt/6)", "the slopes' weighted average"),
            f"{p} = {p} + (dp[0] + 2*dp[1] + 2*dp[2] + dp[3])*(dt/6)",
        ]
    raise ProgramError(f"unknown integrator {method!r} (known: {', '.join(INTEGRATORS)})")


# ---- the program ----

def program(setup, *, integrator: str | None = None, web: bool = False, arrows=None) -> str:
    """The VPython program for a configured scene (scenes._catalog.Setup), as text.

    integrator  the method (default: the scene's own, else euler-cromer, the page's update), as
                Model.methods picks it; scenes that step each mass with its own method
                (integrators) keep theirs, as headless runs do.
    web         True for Web VPython (first line `Web VPython 3.2`, no imports).
    arrows      the arrows to draw (export/program_arrows.py: p, F_net); None: the scene's VIEW's

    Raises ProgramError, or ValueError from the scene's build function, with a one-line message.
    """
    model = setup.build()
    count = model.state.count
    if count > MAX_DRAWN_MASSES:
        whole = [name for name in setup.constants if DECLARED[name].whole]
        raise ProgramError(f"{count:,} masses are more than the {MAX_DRAWN_MASSES:,} a program (like the page) "
                           f"can draw" + (f"; make {' or '.join(whole)} smaller" if whole else ""))
    methods = model.methods(integrator)
    view = {**DEFAULT_VIEW, **getattr(setup.module, "VIEW", {})}
    single = count == 1

    constants = _Constants(setup, count)
    constants.add("m", model.state.m)
    forces = _Forces(model, constants)
    constants.add("r0", model.state.r, is_vector=True)
    constants.add("v0", _start_velocity(setup, model), is_vector=True)
    constants.add("dt", model.dt)
    constants.add("until", model.until)
    masses, used = _masses(setup, model, constants, methods)
    n = constants.name
    i = "" if single else "[i]"
    m = n("m")

    lines = IMPORTS + [
        f"# {setup.name}: {summary(setup.module)}",
        "# Written by the spring-mass simulator with " + (f"the {methods[0]} integrator" if len(set(methods)) == 1
                                                          else "each mass's own integrator (the list method)")
        + ". Edit the constants and run it again.",
        f"# The same case on the simulator's page: {_command(setup, model, integrator)}",
        "", "# ---- constants (unit: meaning) ----"]
    lines += _constants_block(setup, constants, used)
    if masses:
        lines += ["", "# ---- the masses: one spring each ----"] + masses

    lines += ["", "# ---- the objects ----"] + _objects(model, view, constants, single)
    arrows = view["arrows"] if arrows is None else arrows
    lines += program_arrows.setup_lines(model, shown=arrows, integrator=integrator, single=single)
    axes = list(view["plot"])
    exact = exact_lines(model, constants, forces, axis=axes[0], m=m) if view["exact"] and len(axes) == 1 else None
    exact_curve = f"gcurve(color={vector(EXACT_COLOUR)}, width={EXACT_WIDTH}"
    if exact is not None:
        lines.append(commented("exact = " + (f"{exact_curve}, label=\"exact\")" if single else
                                             f"[{exact_curve}) for i in range({_mass_count(constants)})]"),
                               "the closed form: thin, drawn on top"))
        if single:
            lines += [""] + exact[0]

    lines += ["", "# ---- the loop: one momentum update per step ----",
              commented("t = 0", "s: time, n·Δt after n steps"), "n = 0"]
    lines += [_loop_condition(model), commented("    rate(1/dt)", "real time: 1/Δt steps a second")]
    if len(set(methods)) > 1:
        body = []
        for name in INTEGRATORS:
            if name in methods:
                body.append(f"{'elif' if body else 'if'} method[i] == \"{name}\":")
                body += ["    " + line for line in _update(name, forces, r="pos[i]", p="p[i]", m=m)]
    else:
        body = _update(methods[0], forces, r=f"pos{i}", p=f"p{i}", m=m)
    body += program_arrows.loop_lines(shown=arrows, single=single)
    if single:
        lines += ["    " + line for line in body]
    else:
        lines += ["    for i in range(len(pos)):"] + ["        " + line for line in body]
    lines += ["    n = n + 1", commented("    t = n*dt", "a whole number of steps: no round-off piles up")]
    draw = [f"{'ball' if single else 'balls[i]'}.pos = pos{i}",
            commented(f"spring{'' if single else 's[i]'}.axis = pos{i} - {n('anchor')}",
                      "the helix follows the sphere")]
    draw += [f"position{i}" + (f"[{k}]" if len(axes) > 1 else "") + f".plot(t, pos{i}.{axis})"
             for k, axis in enumerate(axes)]
    if exact is not None:
        draw += (exact[1] if single else exact[0] + exact[1])
        draw += [f"exact{i}.plot(t, ({n('anchor')} + (s_eq + x)*u).{axes[0]})"]
    if single:
        lines += ["    " + line for line in draw]
    else:
        lines += ["    for i in range(len(pos)):"] + ["        " + line for line in draw]

    position = '"t =", t, "s:  r = <", pos{i}.x, ",", pos{i}.y, ",", pos{i}.z, "> m,'.format(i=i)
    momentum = '"p = <", p{i}.x, ",", p{i}.y, ",", p{i}.z, "> kg·m/s")'.format(i=i)
    lines += ["", "# ---- the answer ----"]
    lines += [f'print({position} {momentum[1:]}'] if single else [
        "for i in range(len(pos)):",
        f'    print({_which_mass(model, constants)},', f'          {position}",', f'          {momentum}']
    lines = align_comments(lines)
    if web:
        lines = [WEB_FIRST_LINE] + [line for line in lines if line not in IMPORTS]
    return "\n".join(lines) + "\n"


def _start_velocity(setup, model):
    """v0 as the scene gives it, where m v0 is the model's start momentum; else v = p/m (the state's)."""
    given = setup.values.get("v0")
    if given is not None and np.array_equal(model.state.m[:, None] * np.asarray(given, dtype=float), model.state.p):
        return given
    return model.state.v


def _constants_block(setup, constants: _Constants, used: set[str]) -> list[str]:
    """One line per constant, `k = 40  # N/m: spring constant`, in the scene file's order (dt and
    until last): the program's values, and the scene's constants the lists of masses are built from."""
    values = {name: constants.single[name] for name in constants.single}
    values.update({name: setup.values[name] for name in used if name not in values})
    scene = [name for name in setup.constants if name not in ("dt", "until")]
    order = [name for name in scene if name in values] + [name for name in values if name not in scene]
    order = [name for name in order if name not in ("dt", "until")] + [name for name in ("dt", "until") if name in values]
    return [commented(f"{name} = {_literal(values[name])}", constants.comment(name), width=CONSTANT_COLUMN)
            for name in order]


def _command(setup, model, integrator) -> str:
    """The command line that shows this case on the page: `python main.py driven --preset "scenario 4"
    --integrator verlet`, with a preset where one gives some of the changed constants, and
    --set NAME=VALUE for the others (checked: it configures exactly these values)."""
    best = _options(setup, None)
    for label, _ in catalog.presets(setup):   # a preset where it needs no more options than --set alone
        options = _options(setup, label)
        if options is not None and (best is None or len(options) <= len(best)) and not (
                best and best[0].startswith("--preset") and len(options) == len(best)):
            best = options
    if best is None:   # cannot happen for a scene configured from the command line or the page
        best = [f"--set {name}={_set_value(value)}" for name, value in setup.values.items()]
    if model.methods(integrator) != model.methods():
        best.append(f"--integrator {integrator}")
    return " ".join(["python main.py", setup.name, *best])


def _options(setup, preset: str | None) -> list[str] | None:
    """[--preset ..., --set ...] giving setup's values from `preset`, or None if they cannot."""
    try:
        if preset is not None:
            preset = _short_label(setup, preset)
        start = catalog.configure(setup.name, preset=preset).values
        sets = [f"{name}={_set_value(value)}" for name, value in setup.values.items()
                if value is not None and value != start.get(name)]
        if catalog.configure(setup.name, preset=preset, assignments=sets).values != setup.values:
            return None
    except (ConstantError, ValueError):
        return None
    quoted = f'"{preset}"' if preset is not None and " " in preset else preset
    return ([f"--preset {quoted}"] if preset is not None else []) + [f"--set {text}" for text in sets]


def _short_label(setup, label: str) -> str:
    """"scenario 4" for "scenario 4: as 3, with F0 = 2 N", where --preset finds it by that much."""
    short = label.partition(":")[0]
    try:
        return short if catalog.find_preset(setup, short)[0] == label else label
    except ConstantError:
        return label


def _set_value(value) -> str:
    """A value as --set reads it: 2.5, or 0,-1.5,0 for a vector."""
    return ",".join(number(x) for x in value) if isinstance(value, (tuple, list)) else number(value)


def _loop_condition(model) -> str:
    """`while t < until:`, unless round-off in n·Δt would make it take another step than a headless run."""
    steps = steps_to_reach(model.until - model.state.t, model.dt)
    if _steps_while_below(model.until, model.dt) == steps:
        return "while t < until:"
    if _steps_while_below(model.until - 1e-9 * model.dt, model.dt) == steps:
        return commented("while t < until - 1e-9*dt:", "1e-9·Δt forgives round-off in n·Δt")
    return commented(f"while n < {steps}:", "the steps that reach until")


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


# ---- the masses of a row ----

def _masses(setup, model, constants: _Constants, methods) -> tuple[list[str], set[str]]:
    """The lines that make the lists of one value per mass, and the scene's constants they use.

    Where a list follows a rule of the scene's build from its constants (scenes/_row.py: anchors
    `spacing` apart in a row, each mass x0 beyond its equilibrium; regimes: b from 2√(mk);
    resonance: a row per b·b_ratio^row, ω from omega_min to omega_max in count steps), the
    program works the list out the same way with a for loop, so a teacher can change those
    constants. A rule is used only where its own lines, run here, give the model's numbers (to
    ROUND_OFF). Any other list is written out, by name where a value is the scene's constant of
    that name, else as a number cleaned of round-off (15 digits), one a line where it is long.
    """
    if constants.count == 1:
        return [], set()
    rules = _Rules(setup, model, constants)
    lines = rules.lines()
    for name, values in constants.per_mass.items():
        if name not in rules.chosen:
            lines += listed(constants.list_name(name), [rules.spelled(name, x) for x in values],
                            constants.comment(name, per_mass=True))
    if len(set(methods)) > 1:
        lines += listed("method", [f'"{x}"' for x in methods], "the integrator of each mass")
    if constants.count <= LABELLED:
        lines += listed("labels", [f'"{label}"' for label in model.labels], "what each mass shows")
    return lines, rules.used


class _Rules:
    """The lists of a row of masses that follow a rule of the scene's build, each checked by running
    the program's own lines on the scene's constants (numpy arrays standing in for vpython's vector,
    whose arithmetic is the same: one double operation per component)."""

    def __init__(self, setup, model, constants: _Constants):
        self.setup, self.constants = setup, constants
        self.v = setup.values
        self.N = model.state.count
        self.anchors = np.broadcast_to(model.anchors, model.state.r.shape)
        self.known = {name: _as_written(value) for name, value in self.v.items() if value is not None}
        self.known.update({name: _as_written(value) for name, value in constants.single.items()})
        curves, count = self.v.get("curves"), self.v.get("count")
        self.nested = (_whole(curves) and _whole(count) and curves * count == self.N)
        if self.nested:
            self.loop = ["for row in range(curves):", "    for col in range(count):"]
            self.index, self.centre, self.indent = "col", "0.5*(count - 1)", " " * 8
        else:
            self.loop = [f"for i in range({'count' if count == self.N else self.N}):"]
            self.index, self.centre, self.indent = "i", number(0.5 * (self.N - 1)), " " * 4
        self.code: list[str] = []              # lines before the loop, as run here: s_eq, b_c, omega_step
        self.before: list[str] = []            # the same, with their comments
        self.inside: list[str] = []            # lines in the loop, appending to the lists
        self.looped: list[str] = []            # the lists the loop appends to
        self.chosen: dict[str, str] = {}       # list name -> its rule
        self.used: set[str] = set()            # the scene's constants the rules read
        self._choose()

    def lines(self) -> list[str]:
        if not self.inside:
            return self.before
        self._note_names(self.loop)
        empty = [commented(f"{self.constants.list_name(name)} = []", self.constants.comment(name, per_mass=True),
                           width=CONSTANT_COLUMN) for name in self.looped]
        return self.before + empty + self.loop + self.inside

    def spelled(self, name: str, x) -> str:
        """One value of a written-out list: the scene's constant's name where it has that value."""
        if np.ndim(x):
            return vector(clean(c) for c in x)
        same = self.v.get(name) is not None and np.ndim(self.v[name]) == 0 and float(self.v[name]) == x
        if same:
            self.used.add(name)
        return name if same else number(clean(x))

    def _choose(self) -> None:
        per_mass = self.constants.per_mass
        if "anchor" in per_mass and "spacing" in self.v:
            for expr, comment in self._anchor_rules():
                if self._try("anchor", [], f"a = {expr}", "a", comment):
                    break
        if "r0" in per_mass and "anchor" in self.chosen:
            for before, expr, comment in self._start_rules():
                if self._try("r0", before, None, expr, comment):
                    break
        if "b" in per_mass and self.nested and "b_ratio" in self.v:
            self._try("b", [], None, "b*b_ratio**row", "row by row: b, b·b_ratio, b·b_ratio², …")
        if "b" in per_mass and not self.nested and self.N == 3 and {"under_fraction", "over_multiple"} <= set(self.v):
            self._try_whole_list("b", ["b_c = 2*sqrt(m*k)"], "[under_fraction*b_c, b, over_multiple*b_c]",
                                 "kg/s: critical damping, 2√(mk)")
        if "omega" in per_mass and self.nested and {"omega_min", "omega_max"} <= set(self.v):
            self._try("omega", ["omega_step = (omega_max - omega_min)/(count - 1)"], None,
                      "omega_min + col*omega_step", "from omega_min to omega_max along each row")

    def _anchor_rules(self):
        """anchors_in_a_row: spacing apart along ±x, ±y or ±z, centred on the origin (and in
        resonance's rows, one row behind another along −z)."""
        depth = ""
        if self.nested:
            step = self.anchors[0, 2] - self.anchors[int(self.v["count"]) % self.N, 2]
            depth = "-row" if step in (0, 1) else f"-row*{number(step)}"
        for axis in range(3):
            for ahead, offset in ((1, f"({self.index} - {self.centre})*spacing"),
                                  (-1, f"({self.centre} - {self.index})*spacing")):
                parts = ["0", "0", "0"]
                parts[axis] = offset
                if depth and axis != 2:
                    parts[2] = depth
                along = f"{'+' if ahead > 0 else '−'}{'xyz'[axis]}"
                yield "vector(" + ", ".join(parts) + ")", (f"m: rows along {along}, spacing apart, one behind another"
                                                           if depth else f"m: a row along {along}, spacing apart")

    def _start_rules(self):
        """start_positions: each mass at anchor + (s_eq + x0) û, s_eq = L0 + m g/k hanging down."""
        offsets = self.constants.per_mass["r0"] - self.anchors
        u = offsets[0] / np.linalg.norm(offsets[0])
        if not np.allclose(np.abs(u), np.round(np.abs(u)), rtol=0, atol=1e-12):
            return
        u_text = vector(np.round(u))
        stretch = " + x0" if "x0" in self.v else ""
        if tuple(np.round(u)) == (0, -1, 0):
            yield (["s_eq = L0 + m*g/k"], f"a + (s_eq{stretch})*{u_text}" if stretch else f"a + s_eq*{u_text}",
                   "m: " + ("x0 below" if stretch else "at rest at") + " equilibrium")
        yield [], f"a + (L0{stretch})*{u_text}", "m: " + ("x0 beyond" if stretch else "at") + " the relaxed length"

    def _try(self, name, before, setup_line, expr, comment) -> bool:
        """Use `expr` for the list `name` if the program's lines give the model's values."""
        inside = [setup_line] if setup_line else []
        anchor_line = self.chosen.get("anchor")
        lines = (self.code + before + ["_got = []"] + self.loop
                 + [self.indent + line for line in ([anchor_line] if anchor_line and name != "anchor" else [])
                    + inside + [f"_got.append({expr})"]])
        if not self._matches(lines, self.constants.per_mass[name]):
            return False
        self.code += before
        self.before += [commented(line, self._before_comment(line)) for line in before]
        list_name = self.constants.list_name(name)
        if setup_line:
            self.inside.append(self.indent + commented(setup_line, comment))
            self.inside.append(self.indent + f"{list_name}.append(a)")
        else:
            self.inside.append(self.indent + commented(f"{list_name}.append({expr})", comment))
        self.chosen[name] = setup_line or expr
        self.looped.append(name)
        self._note_names(before + [setup_line or "", expr])
        return True

    def _try_whole_list(self, name, before, expr, comment) -> bool:
        """Use `name_each = [...]` worked out before the loop if it gives the model's values."""
        list_name = self.constants.list_name(name)
        lines = self.code + before + [f"_got = {expr}"]
        if not self._matches(lines, self.constants.per_mass[name]):
            return False
        self.code += before + [f"{list_name} = {expr}"]
        self.before += [commented(before[0], comment)] + before[1:]
        self.before.append(commented(f"{list_name} = {expr}", self.constants.comment(name, per_mass=True)))
        self.chosen[name] = expr
        self._note_names(before + [expr])
        return True

    @staticmethod
    def _before_comment(line: str) -> str:
        return {"s_eq": "m: length of each spring at equilibrium, where k (s_eq − L0) = m g",
                "omega_step": "rad/s: from one spring's drive to the next"}.get(line.partition(" =")[0], "")

    def _note_names(self, lines) -> None:
        words = set(re.findall(r"[A-Za-z_]\w*", " ".join(lines)))
        self.used |= {name for name in words if name in self.v}

    def _matches(self, lines, expected) -> bool:
        scope = dict(self.known)
        try:
            exec("\n".join(lines), {"__builtins__": {}, "vector": _vector, "sqrt": math.sqrt, "range": range}, scope)
            got = np.asarray(scope["_got"], dtype=float)
        except Exception:   # a rule that does not fit: a constant missing, a division by zero, ...
            return False
        return got.shape == expected.shape and bool(np.allclose(got, expected, rtol=ROUND_OFF, atol=0))


def _vector(x, y, z) -> np.ndarray:
    return np.array([x, y, z], dtype=float)


def _whole(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and float(x).is_integer() and x >= 1


def _mass_count(constants: _Constants) -> str:
    """How the program counts its masses: the length of one of its lists."""
    for name in ("r0", "anchor", *constants.per_mass):
        if name in constants.per_mass:
            return f"len({constants.list_name(name)})"
    return str(constants.count)


def _which_mass(model, constants: _Constants) -> str:
    """What the answer names each mass by: its label, or the values that set it apart."""
    if model.state.count <= LABELLED:
        return 'labels[i] + ":"'
    shown = [name for name, values in constants.per_mass.items() if values.ndim == 1]
    if not shown:
        return '"mass", i, ":"'
    parts = []
    for k, name in enumerate(shown):
        declared = DECLARED.get(name)
        unit = f" {declared.unit}" if declared and declared.unit != "1" else ""
        parts.append(f'"{(declared.symbol if declared else "") or name} =", {constants.name(name)}, '
                     f'"{unit.strip()}{":" if k == len(shown) - 1 else ","}"')
    return ", ".join(parts)


# ---- what is drawn ----

def _objects(model, view, constants: _Constants, single: bool) -> list[str]:
    """The support box, a helix per spring, a sphere per mass and the position graph."""
    anchors = np.broadcast_to(model.anchors, model.state.r.shape)
    points = [anchors, model.state.r]
    if model.exact is not None:   # where the masses go over the first 20 s, as the page frames it
        points.append(np.reshape(model.exact(np.linspace(0.0, 20.0, 401))[0], (-1, 3)))
    points = np.concatenate(points)
    points = points[np.all(np.isfinite(points), axis=1)]
    size = max(float(np.max(points.max(axis=0) - points.min(axis=0))), 1e-3)
    gaps = [np.linalg.norm(a - b) for j, a in enumerate(anchors) for b in anchors[j + 1:]]
    radius = min([0.08 * size] + [0.3 * gap for gap in gaps if gap > 0])
    thick = 0.4 * radius
    low, high = points.min(axis=0) - 2 * radius, points.max(axis=0) + 2 * radius
    centre = 0.5 * (low + high)
    if view["support"] == "wall":
        x = float(anchors[:, 0].min())
        box = (f"box(pos=vector({_round(x - thick / 2)}, {_round(centre[1])}, {_round(centre[2])}), "
               f"size=vector({_round(thick)}, {_round(high[1] - low[1])}, {_round(2 * radius)}), color=color.gray(0.6))")
    else:
        y = float(anchors[:, 1].max())
        box = (f"box(pos=vector({_round(centre[0])}, {_round(y + thick / 2)}, {_round(centre[2])}), "
               f"size=vector({_round(high[0] - low[0])}, {_round(thick)}, {_round(2 * radius)}), color=color.gray(0.6))")
    n = constants.name
    axes = list(view["plot"])
    graph = f"graph(title=\"Position\", xtitle=\"t (s)\", ytitle=\"{', '.join(axes)} (m)\")"
    lines = [commented(f"radius = {_round(radius)}", "m: size of the sphere (display only)"),
             commented(box, "the support")]
    colour = _colour(MASS_COLOURS[0])
    if single:
        curves = [f"gcurve(color={_colour(shade(MASS_COLOURS[0], k))}, width={number(simulation_width(0, 1))}, "
                  f"label=\"{axis}\")" for k, axis in enumerate(axes)]
        lines += [f"spring = helix(pos=anchor, axis=r0 - anchor, radius=0.45*radius, thickness=0.12*radius, "
                  f"coils={view['coils']})",
                  f"ball = sphere(pos=r0, radius=radius, color={colour}"
                  + (", make_trail=True, retain=300)" if view.get("trail") else ")"),
                  commented("pos = r0", "m: position of the mass"),
                  commented(f"p = {n('m')}*v0", "kg·m/s: its momentum"),
                  graph]
        if len(axes) > 1:
            lines += [f"position = [{curves[0]},"] + [f"            {curve}," for curve in curves[1:-1]] + [
                      f"            {curves[-1]}]"]
        else:
            lines.append(commented(f"position = {curves[0]}", "the simulation: thick"))
        return lines
    count = model.state.count
    coils = max(4, min(view["coils"], round(4 * view["coils"] / count)))
    labelled = count <= LABELLED
    palette, each, which = _palette(constants.setup, model, view)
    widths = [simulation_width(i, count, crowded=not labelled) for i in range(count)]
    width = number(widths[0]) if len(set(widths)) == 1 else "widths[i]"
    lines += listed("colours", [_colour(c) for c in palette], f"the palette: one colour {which}")
    if len(set(widths)) > 1:
        lines += listed("widths", [_round(w) for w in widths],
                        "px: each curve wider than the next, so both show where they meet")
    lines += [graph,
              commented("pos = []", "m: position of each mass"),
              commented("p = []", "kg·m/s: momentum of each mass"),
              "springs = []", "balls = []", commented("position = []", "each mass's curve"),
              f"for i in range({_mass_count(constants)}):",
              f"    pos.append({n('r0')})",
              f"    p.append({n('m')}*{n('v0')})",
              f"    springs.append(helix(pos={n('anchor')}, axis={n('r0')} - {n('anchor')}, radius=0.45*radius, "
              f"thickness=0.12*radius, coils={coils}))",
              f"    balls.append(sphere(pos={n('r0')}, radius=radius, color={each}))",
              f"    position.append(gcurve(color={each}, width={width}"
              + (", label=labels[i]))" if labelled else "))")]
    return lines


def _palette(setup, model, view) -> tuple[list, str, str]:
    """(the colours the program lists, how mass i picks its colour, what a colour stands for), as
    export/palette.py's mass_colours colours the masses on the page: mass i in MASS_COLOURS[i], or
    (resonance) each row of springs in its b's CURVE_COLOURS[row]; the palettes repeat past their end."""
    wanted = [tuple(c) for c in mass_colours(model, view)]
    count, per_row = len(wanted), setup.values.get("count")
    choices = [(MASS_COLOURS, "i", count, "per mass")]
    if _whole(per_row) and count % int(per_row) == 0:
        choices.append((CURVE_COLOURS, "i // count", count // int(per_row), "per row of b"))
    for palette, index, groups, which in choices:
        group = (lambda i: i) if index == "i" else (lambda i: i // int(per_row))
        if [palette[group(i) % len(palette)] for i in range(count)] == wanted:
            repeat = " % len(colours)" if groups > len(palette) else ""
            return list(palette[:groups]), f"colours[{index}{repeat}]", which
    return wanted, "colours[i]", "per mass"


def _colour(rgb) -> str:
    """A palette colour (export/palette.py) as the program writes it: vector(1, 0.55, 0.1)."""
    return "vector(" + ", ".join(_round(c) for c in rgb) + ")"


def _round(x: float) -> str:
    """A display size, to 3 significant figures (the physics numbers are written exactly)."""
    return number(float(f"{float(x):.3g}"))
