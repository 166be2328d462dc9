"""The exact solution as lines of the program, where a closed form exists (physics/exact.py).

The closed form follows the displacement x from equilibrium along the spring's line û,

    m x'' + b x' + k x = F cos(ω t),   x(0) = x_start,  x'(0) = v_start along û,

as a transient in its damping regime (under-damped, critically damped, over-damped) plus the
steady swing the driving force keeps up. The lines work the coefficients out from the program's
own constants, and each case is a branch of the program (the damping regime, undamped resonance),
chosen as physics/exact.py chooses it, so the curve still fits after a student edits m, k, b or ω,
or the offline page moves their sliders, whichever case that makes. The start values are x_start
and v_start, not x0 and v0, which a scene's constants may name.

The constants are found by their role in the closed form (physics/exact.py Role: the stiffness,
the damping, the drive's amplitude, ...), through the constant each force declares for it
(CLOSED_FORM, physics/forces/): nothing here names a force's constant. The start position and
velocity are the program's own r0 and v0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from physics.exact import REGIME_TESTS, RESONANCE_RTOL, Role

from .lines import commented, number, vector

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


def exact_value(constants, *, axis: str) -> str:
    """The exact position's coordinate `axis`, from x (exact_lines): the anchor's point plus the
    spring's length along û."""
    return f"({Roles(constants).name(Role.ANCHOR)} + (s_eq + x)*u).{axis}"


def plot_line(constants, *, index: str, axis: str) -> str:
    """The line that plots the exact position on the graph of `axis` (`index`: "" for one mass,
    "[i]" in a loop)."""
    return f"exact{index}.plot(t, {exact_value(constants, axis=axis)})"


@dataclass(frozen=True)
class _Names:
    """How the program spells each constant the closed form reads, for one case: `k`, `b_each[i]`;
    None for a role the program has no constant for (no damping, no drive, no gravity)."""

    m: str
    k: str
    L0: str                 # "0" for a spring of zero length (each coordinate moves on its own)
    anchor: str
    g: str | None
    b: str | None
    F0: str | None
    omega: str | None
    drive_axis: str | None

    @property
    def linear(self) -> bool:
        return self.L0 == "0"


def _names(roles: Roles, m: str) -> _Names:
    def named(role):
        return roles.name(role) if roles.has(role) else None
    driven = roles.has(Role.DRIVE_AMPLITUDE)
    return _Names(m=m, k=roles.name(Role.STIFFNESS), L0=named(Role.NATURAL_LENGTH) or "0",
                  anchor=roles.name(Role.ANCHOR), g=named(Role.GRAVITY), b=named(Role.DAMPING),
                  F0=named(Role.DRIVE_AMPLITUDE), omega=roles.name(Role.DRIVE_FREQUENCY) if driven else None,
                  drive_axis=roles.name(Role.DRIVE_AXIS) if driven else None)


def covered(model, roles: Roles, forces) -> bool:
    """Whether the closed form covers this case: every force has one (each force's closed_form(),
    physics/forces/), there is a spring, and every mass moves on its spring's line (or the spring
    has zero length, so each coordinate moves on its own)."""
    if any(force.closed_form() is None for force in forces.forces) or not roles.has(Role.STIFFNESS):
        return False
    return model.exact is not None and (not roles.has(Role.NATURAL_LENGTH) or on_line(model, roles))


def exact_lines(model, constants, forces, *, axis: str, m: str):
    """(lines before the loop, lines giving x at time t) of the closed form, or None.

    The closed form (physics/exact.py) follows the displacement x from equilibrium along the
    spring's line û: m x'' + b x' + k x = F cos(ω t), started from x_start and v_start along û.
    `constants` spells the program's names (the program's constants): `b`, or `b_each[i]`.
    Each case is a branch in the program, so the same lines hold for any values of the constants.
    """
    roles = Roles(constants)
    if not covered(model, roles, forces):
        return None
    names = _names(roles, m)
    drive_before, shifted, drive_now = _steady_swing(names)
    free_before, free_now = _free_motion(names)
    before = _spring_line(names, axis, constants) + drive_before + _start(names, constants, shifted) + free_before
    return before, free_now + drive_now


def _spring_line(names: _Names, axis: str, constants) -> list[str]:
    """The line the mass moves on (û), its length at equilibrium, ω0 and γ."""
    n, m, k = constants.name, names.m, names.k
    linear = names.linear
    lines = ["# the exact solution (physics/exact.py): x = displacement from equilibrium along the spring"
             + ("" if linear else ",")] + ([] if linear else ["# good until the mass reaches its anchor"])
    lines.append(commented(f"u = {vector(np.eye(3)['xyz'.index(axis)])}",
                           "û: the plotted axis (L0 = 0: each axis on its own)") if linear else
                 commented(f"u = norm({n('r0')} - {names.anchor})", "direction of the spring, û"))
    lines += [commented(f"s_eq = {names.L0} + {m}*{names.g}*(-u.y)/{k}" if names.g else f"s_eq = {names.L0}",
                        "m: length of the spring at equilibrium"),
              commented(f"omega0 = sqrt({k}/{m})", "rad/s: natural angular frequency √(k/m)")]
    if names.b:
        lines.append(commented(f"gamma = {names.b}/(2*{m})", "1/s: decay rate b/2m"))
    return lines


def _steady_swing(names: _Names) -> tuple[list[str], str, list[str]]:
    """The driving force's steady swing: (lines before the loop, what x_start and v_start lose to
    it at t = 0, its part of x at time t); undamped resonance is a branch of its own, where the
    swing grows as F t/(2 m ω0) and has no steady amplitude."""
    if not names.F0:
        return [], "", []
    m, k, b, w = names.m, names.k, names.b, names.omega
    at_resonance = f"abs({w} - omega0) <= {number(RESONANCE_RTOL)}*omega0"
    before = [commented(f"Fu = {names.F0}*dot({names.drive_axis}, u)", "N: driving amplitude along û"),
              commented(f"resonant = {b} == 0 and {at_resonance}" if b else f"resonant = {at_resonance}",
                        "undamped resonance: ω = ω0" + (" with b = 0" if b else "")),
              commented("if resonant:", "no steady swing: the swing grows as F t/(2 m ω0)"),
              "    amp = 0"]
    if b:
        before += ["    delta = 0", "else:",
                   commented(f"    amp = Fu/sqrt(({k} - {m}*{w}**2)**2 + ({b}*{w})**2)", "m: steady-state amplitude"),
                   commented(f"    delta = atan2({b}*{w}, {k} - {m}*{w}**2)", "rad: its phase lag")]
        shifted, swing = "delta", f"amp*cos({w}*t - delta)"
    else:   # undamped: the steady swing is in step (or opposite), its amplitude signed
        before += ["else:", commented(f"    amp = Fu/({k} - {m}*{w}**2)", "m: steady-state amplitude (signed)")]
        shifted, swing = "in step", f"amp*cos({w}*t)"
    now = ["if resonant:",
           commented(f"    x = x + Fu*t*sin(omega0*t)/(2*{m}*omega0)", "resonance: the swing grows as F t/(2 m ω0)"),
           "else:", f"    x = x + {swing}"]
    return before, shifted, now


def _start(names: _Names, constants, shifted: str) -> list[str]:
    """x_start and v_start: the start's displacement and velocity along û, less the steady swing's."""
    n = constants.name
    start = (f"dot({n('r0')} - {names.anchor}, u) - s_eq" if names.linear else
             f"mag({n('r0')} - {names.anchor}) - s_eq")
    velocity = f"dot({n('v0')}, u)"
    if shifted == "delta":
        return [commented(f"x_start = {start} - amp*cos(delta)", "m: start displacement, less the steady swing's"),
                commented(f"v_start = {velocity} - amp*{names.omega}*sin(delta)", "m/s: the same for the velocity")]
    if shifted:
        return [commented(f"x_start = {start} - amp", "m: start displacement, less the steady swing's"),
                commented(f"v_start = {velocity}", "m/s: start velocity along û")]
    return [commented(f"x_start = {start}", "m: start displacement"),
            commented(f"v_start = {velocity}", "m/s: start velocity along û")]


# Each damping regime's coefficients (before the loop) and x at time t (in it), in the order
# physics/exact.py's REGIME_TESTS tries them.
REGIMES = {
    "critically damped": ([commented("c2 = v_start + gamma*x_start", "critically damped: x = e^(−γt) (x_start + c2 t)")],
                          "x = exp(-gamma*t)*(x_start + c2*t)"),
    "under-damped": ([commented("omega_d = sqrt(omega0**2 - gamma**2)",
                                "under-damped: x = e^(−γt) (x_start cos ω_d t + c2 sin ω_d t)"),
                      "c2 = (v_start + gamma*x_start)/omega_d"],
                     "x = exp(-gamma*t)*(x_start*cos(omega_d*t) + c2*sin(omega_d*t))"),
    "over-damped": ([commented("mu = sqrt(gamma**2 - omega0**2)", "over-damped: x = c1 e^(λ1 t) + c2 e^(λ2 t)"),
                     "c1 = (v_start + (gamma + mu)*x_start)/(2*mu)", "c2 = x_start - c1"],
                    "x = c1*exp((mu - gamma)*t) + c2*exp(-(gamma + mu)*t)"),
}


def _free_motion(names: _Names) -> tuple[list[str], list[str]]:
    """The free motion from x_start and v_start: (its coefficients, x at time t). With damping,
    each regime is a branch, chosen before the loop (`regime`) and followed in it."""
    if not names.b:
        return [], [commented("x = x_start*cos(omega0*t) + v_start/omega0*sin(omega0*t)", "undamped")]
    before, now = [], []
    for n, (regime, test) in enumerate(REGIME_TESTS):
        keyword = "if" if n == 0 else "elif" if test else "else"
        coefficients, x = REGIMES[regime]
        condition = test.format(b=names.b, m=names.m, k=names.k)
        before += [f"{keyword} {condition}:" if test else "else:", f'    regime = "{regime}"']
        before += ["    " + line for line in coefficients]
        now += [f'{keyword} regime == "{regime}":' if test else "else:", "    " + x]
    return before, now
