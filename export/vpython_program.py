"""A scene as a standalone VPython program: the page's program, written out for one configured case.

The page teaches with a short VPython program: constants at the top, a support, a helix and a
sphere, a graph, and one `while` loop in which the momentum update is written out. This module
writes that program for any scene with its constants, preset and integrator as chosen, so a
teacher can set a case up and hand it to the class to read and edit:

    m = 10.0                # kg: mass of the block
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

Every number comes from the scene's model (the force objects and the initial state), written with
repr, so the program starts from exactly the same values. Constants are named as in the scene
files, with their unit and meaning from the scene's constants block (scenes/_constants.py).
Scenes with several masses (a row of oscillators) keep lists and step each mass in a for loop.

The Web VPython form (glowscript.org, trinket) is the same program with `Web VPython 3.2` as its
first line and no import lines.
"""
from __future__ import annotations

import numpy as np

from physics.forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring
from physics.integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from physics.simulate import steps_to_reach
from scenes import summary

from .exact_curve import exact_lines
from .lines import ProgramError, align_comments, commented, number, vector

WEB_FIRST_LINE = "Web VPython 3.2"
IMPORTS = ["from vpython import *"]

# Unit and meaning of each name the program uses, where the scene's own constants block has no
# constant of that name (or the program's value differs from it: a list with one value per mass).
FALLBACK = {
    "m": ("kg", "mass"), "k": ("N/m", "spring constant"), "L0": ("m", "relaxed length of the spring"),
    "anchor": ("m", "fixed end of the spring"), "g": ("m/s²", "strength of gravity, along −y"),
    "b": ("kg/s", "linear damping constant in F = −b v"), "C": ("1", "drag coefficient"),
    "A": ("m²", "cross-section area, for drag"), "rho": ("kg/m³", "air density, for drag"),
    "F0": ("N", "driving force amplitude in F = F0 cos(ω t)"),
    "omega": ("rad/s", "driving angular frequency ω (rad/s, not Hz)"),
    "drive_axis": ("1", "direction of the driving force (a unit vector)"),
    "r0": ("m", "start position"), "v0": ("m/s", "start velocity"),
    "dt": ("s", "time step Δt of the momentum update"), "until": ("s", "when to stop"),
}
COLOURS = ["color.orange", "color.cyan", "color.green", "color.magenta", "color.yellow", "color.red"]
MOST_CURVES = 6            # more masses than this: their graph lines get no labels


# ---- what the program needs from the model ----

class _Values:
    """The program's constants: name -> (literal, unit, meaning, per_mass), in the order written."""

    def __init__(self, setup, count: int):
        self.setup, self.count = setup, count
        self.items: dict[str, tuple[str, str, str, bool]] = {}

    def add(self, name: str, value, *, is_vector: bool = False) -> None:
        """Record a constant from the model's numbers: one value, or one per mass if they differ."""
        array = np.asarray(value, dtype=float)
        if is_vector:
            rows = np.broadcast_to(array, (self.count, 3)) if array.ndim == 2 else array[None]
            per_mass = array.ndim == 2 and not np.all(rows == rows[0])
            literal = ("[" + ", ".join(vector(row) for row in rows) + "]") if per_mass else vector(rows[0])
        else:
            flat = np.broadcast_to(array.reshape(-1), (self.count,)) if array.ndim else array.reshape(1)
            per_mass = array.ndim > 0 and not np.all(flat == flat[0])
            literal = ("[" + ", ".join(number(x) for x in flat) + "]") if per_mass else number(flat[0])
        if name in self.items and self.items[name][0] != literal:
            raise ProgramError(f"two forces use different values of {name}: the program cannot name both")
        unit, meaning = FALLBACK.get(name, ("", name))
        constant = self.setup.constants.get(name)
        if constant is not None:
            unit = constant.unit
            scene_value = self.setup.values.get(name)
            same = scene_value is not None and not per_mass and np.array_equal(
                np.asarray(scene_value, dtype=float), rows[0] if is_vector else flat[0])
            meaning = constant.meaning if same else meaning
        if per_mass:
            meaning += ", one per mass"
        self.items[name] = (literal, unit, meaning, per_mass)

    def name(self, name: str) -> str:
        """How the loop spells a constant: `b`, or `b[i]` for one value per mass."""
        return f"{name}[i]" if self.items[name][3] else name


class _Forces:
    """The scene's forces as lines of the program, in the order physics.forces.net_force adds them."""

    def __init__(self, model, values: _Values):
        self.values = values
        self.forces = list(model.forces)
        for force in self.forces:
            if isinstance(force, Spring):
                values.add("k", force.k)
                if not force._zero_length:
                    values.add("L0", force.L0)
                values.add("anchor", force.anchor, is_vector=True)
            elif isinstance(force, Gravity):
                if not np.allclose(force.direction, (0.0, -1.0, 0.0), rtol=0, atol=0):
                    raise ProgramError("the program writes gravity along −y only")
                values.add("g", force.g)
            elif isinstance(force, LinearDamping):
                values.add("b", force.b)
            elif isinstance(force, QuadraticDrag):
                for name in ("C", "A", "rho"):
                    values.add(name, getattr(force, name))
            elif isinstance(force, Driving):
                values.add("F0", force.F0)
                values.add("omega", force.omega)
                values.add("drive_axis", force.axis, is_vector=True)
            else:
                raise ProgramError(f"the program cannot write the force {type(force).__name__}")
        self.uses_velocity = any(force.uses_velocity for force in self.forces)

    def lines(self, *, t: str, r: str, v: str, m: str, laws: bool) -> list[str]:
        """Fnet at time t, position r and velocity v: one line per force, then their sum."""
        n = self.values.name
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
        lines = ["# velocity Verlet: half a kick, a drift, half a kick",
                 commented(f"v = {p}/{m}", "velocity at the start of the step")]
        lines += F("t", r, "v", laws=True)
        lines += [commented(f"{p} = {p} + Fnet*(dt/2)", "half a kick: p_½ = p_i + F_i Δt/2"),
                  commented(f"{r} = {r} + {p}/{m}*dt", "drift: r_f = r_i + (p_½/m) Δt"),
                  f"v = {p}/{m}"]
        if forces.uses_velocity:
            lines += ["# damping needs v_f, not known yet: estimate it with one more half kick"]
            lines += F("(t + dt)", r, "v")
            lines += [f"v = ({p} + Fnet*(dt/2))/{m}"]
        lines += F("(t + dt)", r, "v")
        lines += [commented(f"{p} = {p} + Fnet*(dt/2)", "half a kick with the force at the end")]
        return lines
    if method == "rk4":
        return [
            "# rk4: the slopes dr/dt = v and dp/dt = F_net at four points of the step",
            "dr = []",
            "dp = []",
            "v = vector(0, 0, 0)",
            "Fnet = vector(0, 0, 0)",
            commented("for h in [0, dt/2, dt/2, dt]:", "each point: h ahead along the slope before"),
            "    t_s = t + h",
            f"    r_s = {r} + v*h",
            f"    p_s = {p} + Fnet*h",
            f"    v = p_s/{m}",
            *("    " + line for line in F("t_s", "r_s", "v", laws=True)),
            "    dr.append(v)",
            "    dp.append(Fnet)",
            commented(f"{r} = {r} + (dr[0] + 2*dr[1] + 2*dr[2] + dr[3])*(dt/6)", "the slopes' weighted average"),
            f"{p} = {p} + (dp[0] + 2*dp[1] + 2*dp[2] + dp[3])*(dt/6)",
        ]
    raise ProgramError(f"unknown integrator {method!r} (known: {', '.join(INTEGRATORS)})")


# ---- the program ----

def program(setup, *, integrator: str | None = None, web: bool = False) -> str:
    """The VPython program for a configured scene (scenes._catalog.Setup), as text.

    integrator  the method (default euler-cromer, the page's update); scenes that step each mass
                with its own method (integrators) keep theirs, as headless runs do.
    web         True for Web VPython (first line `Web VPython 3.2`, no imports).

    Raises ProgramError, or ValueError from the scene's build function, with a one-line message.
    """
    model = setup.build()
    count = model.state.count
    methods = tuple(model.integrators) if model.integrators is not None else None
    method = integrator or model.default_integrator or DEFAULT_INTEGRATOR   # as the engine picks
    for name in methods or (method,):
        if name not in INTEGRATORS:
            raise ProgramError(f"unknown integrator {name!r} (known: {', '.join(INTEGRATORS)})")
    view = {"support": "ceiling", "plot": "y", "exact": True, **getattr(setup.module, "VIEW", {})}
    single = count == 1

    starts = np.linalg.norm(model.state.r - np.broadcast_to(model.anchors, model.state.r.shape), axis=1)
    if any(isinstance(f, Spring) and not f._zero_length for f in model.forces) and np.any(starts == 0):
        raise ProgramError("a mass starts at its spring's anchor, where the spring's direction L̂ "
                           "is undefined: move r0 off the anchor")
    values = _Values(setup, count)
    values.add("m", model.state.m)
    forces = _Forces(model, values)
    values.add("r0", model.state.r, is_vector=True)
    values.add("v0", model.state.p / model.state.m[:, None], is_vector=True)
    values.add("dt", model.dt)
    values.add("until", model.until)
    n = values.name
    i = "" if single else "[i]"
    m = n("m")

    lines = [f"# {setup.name}: {summary(setup.module)}",
             "# Written by the spring-mass simulator (python main.py " + setup.name + " --vpython FILE.py)",
             "# with " + (f"each mass's own integrator ({', '.join(methods)})" if methods
                          else f"the {method} integrator") + ". Edit the constants and run it again."]
    changed = _changed(setup)
    if changed:
        lines.append(f"# Changed from the scene's defaults: {changed}.")
    lines += IMPORTS
    lines += ["", "# ---- constants (unit: meaning) ----"]
    for name, (literal, unit, meaning, _) in values.items.items():
        lines.append(commented(f"{name} = {literal}", f"{unit}: {meaning}", width=24))
    if methods:
        lines.append(commented("method = [" + ", ".join(f'"{x}"' for x in methods) + "]",
                                "the integrator of each mass", width=24))
    if not single:
        lines.append(commented("labels = [" + ", ".join(f'"{label}"' for label in model.labels) + "]",
                                "what each mass shows", width=24))

    lines += ["", "# ---- the objects ----"] + _objects(model, view, values, single)
    axes = list(view["plot"])
    exact = exact_lines(model, values, forces, axis=axes[0], m=m) if view["exact"] and len(axes) == 1 else None
    if exact is not None:
        lines.append(commented("exact = " + ("gcurve(color=color.black, label=\"exact\")" if single else
                                              "[gcurve(color=color.black) for i in range(len(labels))]"),
                                "the closed form, where there is one"))
        if single:
            lines += [""] + exact[0]

    lines += ["", "# ---- the loop: one momentum update per step ----",
              commented("t = 0", "s: time, n·Δt after n steps"), "n = 0"]
    lines += [_loop_condition(model), commented("    rate(1/dt)", "real time: 1/Δt steps a second")]
    if methods:
        body = []
        for name in INTEGRATORS:
            if name in methods:
                keyword = "if" if not body else "elif"
                body.append(f"{keyword} method[i] == \"{name}\":")
                body += ["    " + line for line in _update(name, forces, r="pos[i]", p="p[i]", m=m)]
    else:
        body = _update(method, forces, r=f"pos{i}", p=f"p{i}", m=m)
    if single:
        lines += ["    " + line for line in body]
    else:
        lines += ["    for i in range(len(pos)):"] + ["        " + line for line in body]
    lines += ["    n = n + 1", commented("    t = n*dt", "a whole number of steps: no round-off piles up")]
    draw = [f"balls{i}.pos = pos{i}".replace("balls", "ball" if single else "balls"),
            commented(f"spring{'s[i]' if not single else ''}.axis = pos{i} - {n('anchor')}",
                       "the helix follows the sphere")]
    draw += [f"{'position' if single else 'curves[i]'}"
             + (f"[{k}]" if len(axes) > 1 else "") + f".plot(t, pos{i}.{axis})" for k, axis in enumerate(axes)]
    if exact is not None:
        draw += (exact[1] if single else exact[0] + exact[1])
        draw += [f"exact{i}.plot(t, ({n('anchor')} + (s_eq + x)*u).{axes[0]})"]
    if single:
        lines += ["    " + line for line in draw]
    else:
        lines += ["    for i in range(len(pos)):"] + ["        " + line for line in draw]

    result = ('print("t =", t, "s:  r = <", pos{i}.x, ",", pos{i}.y, ",", pos{i}.z, "> m,  '
              'p = <", p{i}.x, ",", p{i}.y, ",", p{i}.z, "> kg·m/s")').format(i=i)
    lines += ["", "# ---- the answer ----"]
    lines += [result] if single else ["for i in range(len(pos)):", "    print(labels[i] + \":\", "
                                      + result[len("print("):]]
    lines = align_comments(lines)
    if web:
        lines = [WEB_FIRST_LINE] + [line for line in lines[1:] if line not in IMPORTS]
    return "\n".join(lines) + "\n"


def _changed(setup) -> str:
    """The constants set differently from the scene file's defaults, as `k = 60 N/m, b = 2 kg/s`."""
    from scenes import format_value

    return ", ".join(f"{name} = {format_value(setup.values[name], constant.unit)}"
                     for name, constant in setup.constants.items()
                     if setup.values.get(name) != constant.value)


def _loop_condition(model) -> str:
    """`while t < until:`, unless round-off in n·Δt would make it take another step than a headless run."""
    steps = steps_to_reach(model.until - model.state.t, model.dt)
    taken = 0
    while taken * model.dt < model.until:
        taken += 1
    if taken == steps:
        return "while t < until:"
    return commented("while t < until - 1e-9*dt:", "1e-9·Δt forgives round-off in n·Δt")


def _objects(model, view, values: _Values, single: bool) -> list[str]:
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
    n = values.name
    axes = list(view["plot"])
    ytitle = ", ".join(axes) + " (m)"
    lines = [commented(f"radius = {_round(radius)}", "m: size of the sphere (display only)"),
             commented(box, "the support")]
    if single:
        lines += [f"spring = helix(pos=anchor, axis=r0 - anchor, radius=0.45*radius, thickness=0.12*radius, coils=12)",
                  f"ball = sphere(pos=r0, radius=radius, color=color.orange"
                  + (", make_trail=True, retain=300)" if view.get("trail") else ")"),
                  commented("pos = r0", "m: position of the mass"),
                  commented(f"p = {n('m')}*v0", "kg·m/s: its momentum"),
                  f"graph(title=\"Position\", xtitle=\"t (s)\", ytitle=\"{ytitle}\")"]
        if len(axes) > 1:
            lines.append("position = [" + ", ".join(f"gcurve(color={COLOURS[k]}, label=\"{axis}\")"
                                                     for k, axis in enumerate(axes)) + "]")
        else:
            lines.append(f"position = gcurve(color=color.blue, label=\"{axes[0]}\")")
        return lines
    coils = max(4, min(12, round(48 / model.state.count)))
    label = "labels[i]" if model.state.count <= MOST_CURVES else "\"\""
    lines += [f"graph(title=\"Position\", xtitle=\"t (s)\", ytitle=\"{ytitle}\")",
              "colours = [" + ", ".join(COLOURS) + "]",
              commented("pos = []", "m: position of each mass"),
              commented("p = []", "kg·m/s: momentum of each mass"),
              "springs = []", "balls = []", "curves = []",
              "for i in range(len(labels)):",
              f"    pos.append({n('r0')})",
              f"    p.append({n('m')}*{n('v0')})",
              f"    springs.append(helix(pos={n('anchor')}, axis={n('r0')} - {n('anchor')}, radius=0.45*radius, "
              f"thickness=0.12*radius, coils={coils}))",
              f"    balls.append(sphere(pos={n('r0')}, radius=radius, color=colours[i % len(colours)]))",
              f"    curves.append(gcurve(color=colours[i % len(colours)], label={label}))"]
    return lines


def _round(x: float) -> str:
    """A display size, to 3 significant figures (the physics numbers are written exactly)."""
    return number(float(f"{float(x):.3g}"))


