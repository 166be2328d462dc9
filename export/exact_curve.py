"""The exact solution as lines of the program, where a closed form exists (physics/exact.py).

The closed form follows the displacement x from equilibrium along the spring's line û,

    m x'' + b x' + k x = F cos(ω t),   x(0) = x_start,  x'(0) = v_start along û,

as a transient in its damping regime (under-damped, critically damped, over-damped) plus the
steady swing the driving force keeps up. The lines work the coefficients out from the program's
own constants, so the curve still fits after a student edits m, k or b (within the same regime).
The start values are x_start and v_start, not x0 and v0, which a scene's constants may name.

The constants are found by their role in the closed form (physics/exact.py Role: the stiffness,
the damping, the drive's amplitude, ...), through the constant each force declares for it
(CLOSED_FORM, physics/forces/): nothing here names a force's constant. The start position and
velocity are the program's own r0 and v0.
"""
from __future__ import annotations

import math

import numpy as np

from physics.exact import Role, damping_regime

from .lines import commented, vector

DOWN = (0.0, -1.0, 0.0)        # the program writes gravity along −y


class Roles:
    """The program's constants (export/program_constants.py) by their role in the closed form: the
    constant each of the model's forces declares for the role (ProgramConstants.roles, from
    physics/forces/ closed_form_constants)."""

    def __init__(self, constants):
        self.constants = constants
        self.held = constants.roles

    def has(self, role: str) -> bool:
        """Whether the program has the constant of this role."""
        return role in self.held and self.constants.has(self.held[role])

    def name(self, role: str) -> str:
        """The program's name for it: `b`, or `b_each[i]`."""
        return self.constants.name(self.held[role])

    def each(self, role: str) -> np.ndarray:
        """Its value for each mass."""
        return self.constants.each(self.held[role])


def on_line(model, roles: Roles) -> bool:
    """Whether every mass moves on the line of its spring (what the closed form needs)."""
    anchors = np.broadcast_to(model.anchors, model.state.r.shape)
    offsets = model.state.r - anchors
    lengths = np.linalg.norm(offsets, axis=1)
    if np.any(lengths == 0):
        return False
    u = offsets / lengths[:, None]
    along = [model.state.v]
    along += [np.broadcast_to(DOWN, u.shape)] if roles.has(Role.GRAVITY) else []
    along += [np.reshape(roles.each(Role.DRIVE_AXIS), (-1, 3))] if roles.has(Role.DRIVE_AMPLITUDE) else []
    for vectors in along:
        off = vectors - np.sum(vectors * u, axis=1)[:, None] * u
        if np.any(np.linalg.norm(off, axis=1) > 1e-12 * np.maximum(1.0, np.linalg.norm(vectors, axis=1))):
            return False
    return True


def plot_line(constants, *, index: str, axis: str) -> str:
    """The line that plots the exact position on the graph of `axis`, from x (exact_lines): the
    anchor's point plus the spring's length along û (`index`: "" for one mass, "[i]" in a loop)."""
    return f"exact{index}.plot(t, ({Roles(constants).name(Role.ANCHOR)} + (s_eq + x)*u).{axis})"


def exact_lines(model, constants, forces, *, axis: str, m: str):
    """(lines before the loop, lines giving x at time t) of the closed form, or None.

    The closed form (physics/exact.py) follows the displacement x from equilibrium along the
    spring's line û: m x'' + b x' + k x = F cos(ω t), started from x_start and v_start along û.
    `constants` spells the program's names (the program's constants): `b`, or `b_each[i]`.
    """
    roles = Roles(constants)
    n = constants.name
    # only where the closed form covers every force (each force's closed_form(), physics/forces/)
    if any(force.closed_form() is None for force in forces.forces) or not roles.has(Role.STIFFNESS):
        return None
    k, g = roles.name(Role.STIFFNESS), roles.name(Role.GRAVITY) if roles.has(Role.GRAVITY) else None
    damped, gravity, driven = roles.has(Role.DAMPING), g is not None, roles.has(Role.DRIVE_AMPLITUDE)
    linear = not roles.has(Role.NATURAL_LENGTH)     # L0 = 0: F = −k L, so each coordinate moves on its own
    if model.exact is None or not (linear or on_line(model, roles)):
        return None
    k_all = roles.each(Role.STIFFNESS)
    b_all = roles.each(Role.DAMPING) if damped else np.zeros(model.state.count)
    regimes = {damping_regime(m=mi, k=ki, b=bi) for mi, ki, bi in zip(model.state.m, k_all, b_all)}
    L0 = roles.name(Role.NATURAL_LENGTH) if not linear else "0"
    b = roles.name(Role.DAMPING) if damped else "0"
    anchor = roles.name(Role.ANCHOR)
    before = [
        "# the exact solution (physics/exact.py): x = displacement from equilibrium along the spring"
        + ("" if linear else ",")] + ([] if linear else ["# good until the mass reaches its anchor"]) + [
        commented(f"u = {vector(np.eye(3)['xyz'.index(axis)])}", "û: the plotted axis (L0 = 0: each axis on its own)")
        if linear else commented(f"u = norm({n('r0')} - {anchor})", "direction of the spring, û"),
        commented(f"s_eq = {L0} + {m}*{g}*(-u.y)/{k}" if gravity else f"s_eq = {L0}",
                  "m: length of the spring at equilibrium"),
        commented(f"omega0 = sqrt({k}/{m})", "rad/s: natural angular frequency √(k/m)"),
    ]
    if damped:
        before.append(commented(f"gamma = {b}/(2*{m})", "1/s: decay rate b/2m"))
    start = f"{'dot' if linear else 'mag'}({n('r0')} - {anchor}{', u' if linear else ''}) - s_eq"
    x_start = [commented(f"x_start = {start}", "m: start displacement"),
               commented(f"v_start = dot({n('v0')}, u)", "m/s: start velocity along û")]
    steady = []
    if driven:
        F0, w = roles.name(Role.DRIVE_AMPLITUDE), roles.name(Role.DRIVE_FREQUENCY)
        omega_all = roles.each(Role.DRIVE_FREQUENCY)
        resonant = [bi == 0 and np.isclose(wi, math.sqrt(ki / mi), rtol=1e-12, atol=0)
                    for bi, wi, ki, mi in zip(b_all, omega_all, k_all, model.state.m)]
        if any(resonant) and not all(resonant):
            return None
        before.append(commented(f"Fu = {F0}*dot({roles.name(Role.DRIVE_AXIS)}, u)", "N: driving amplitude along û"))
        if all(resonant):
            steady = [commented(f"x = x + Fu*t*sin(omega0*t)/(2*{m}*omega0)",
                                "resonance: the swing grows as F t/(2 m ω0)")]
        elif not damped:   # undamped: the steady swing is in step (or opposite)
            before.append(commented(f"amp = Fu/({k} - {m}*{w}**2)", "m: steady-state amplitude (signed)"))
            x_start = [commented(f"x_start = {start} - amp", "m: start displacement, less the steady swing's"),
                       x_start[1]]
            steady = [f"x = x + amp*cos({w}*t)"]
        else:
            before += [
                commented(f"amp = Fu/sqrt(({k} - {m}*{w}**2)**2 + ({b}*{w})**2)", "m: steady-state amplitude"),
                commented(f"delta = atan2({b}*{w}, {k} - {m}*{w}**2)", "rad: its phase lag"),
            ]
            x_start = [commented(f"x_start = {start} - amp*cos(delta)", "m: start displacement, less the steady swing's"),
                       commented(f"v_start = dot({n('v0')}, u) - amp*{w}*sin(delta)", "m/s: the same for the velocity")]
            steady = [f"x = x + amp*cos({w}*t - delta)"]
    before += x_start
    branches = {
        "under-damped": ([commented("omega_d = sqrt(omega0**2 - gamma**2)",
                                    "under-damped: x = e^(−γt) (x_start cos ω_d t + c2 sin ω_d t)"),
                          "c2 = (v_start + gamma*x_start)/omega_d"],
                         ["x = exp(-gamma*t)*(x_start*cos(omega_d*t) + c2*sin(omega_d*t))"]),
        "critically damped": ([commented("c2 = v_start + gamma*x_start",
                                         "critically damped: x = e^(−γt) (x_start + c2 t)")],
                              ["x = exp(-gamma*t)*(x_start + c2*t)"]),
        "over-damped": ([commented("mu = sqrt(gamma**2 - omega0**2)", "over-damped: x = c1 e^(λ1 t) + c2 e^(λ2 t)"),
                         "c1 = (v_start + (gamma + mu)*x_start)/(2*mu)", "c2 = x_start - c1"],
                        ["x = c1*exp((mu - gamma)*t) + c2*exp(-(gamma + mu)*t)"]),
    }
    if not damped:
        return before, [commented("x = x_start*cos(omega0*t) + v_start/omega0*sin(omega0*t)", "undamped")] + steady
    if len(regimes) == 1:
        coefficients, now = branches[regimes.pop()]
        return before + coefficients, now + steady
    now = []
    for keyword, regime, condition in (("if", "under-damped", f"{b}**2 < 4*{m}*{k}"),
                                       ("elif", "over-damped", f"{b}**2 > 4*{m}*{k}"),
                                       ("else", "critically damped", "")):
        now.append(f"{keyword} {condition}:  # {regime}" if condition else f"else:  # {regime}")
        now += ["    " + line for line in branches[regime][0] + branches[regime][1]]
    return before, now + steady
