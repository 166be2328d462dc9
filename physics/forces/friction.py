"""Sliding friction with static sticking, on a horizontal table: a force in a module of its own.

This file is the whole of friction: its law, its constants, its label, its line in the handed-out
program, its stop rule, and that no closed form covers it. Being in physics/forces/ is what makes
it known (physics/forces/__init__.py imports every module here); nothing else names it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..declared import Declared
from ..rows import magnitude, row_dot
from .base import Force, _column, _per_mass, compare, where
from .page import Gravity


@dataclass(frozen=True, eq=False)
class Friction(Force):
    """Kinetic friction on a horizontal table, with static friction holding a mass at rest.

    F = −μ_k N v̂,  N = m g,  along the table (x and z; y is up)
    μ_k and μ_s (no unit) the kinetic and static coefficients, μ_s ≥ μ_k; g in m/s², the scene's;
    m in kg; F in N. v̂ is the direction of the velocity along the table; at rest (v = 0 there)
    the law gives 0, and the stop rule below decides whether the mass stays. The table holds the
    mass up (its push balances gravity), so a scene on a table leaves gravity out of its forces;
    g gives the load N = m g. Friction always takes energy (F·v = −μ_k N |v| ≤ 0): the engine
    counts its work in W_nc, like damping's. No closed form covers it (each half swing of a
    spring has one, about a centre moved by ±μ_k m g/k, but not the whole run), so a model with
    friction reports no exact answer.

    At rest the law also reads the other forces (responds: net_force hands it their sum, F_rest):
    static friction balances their part along the table, F = −F_rest, while that is at most
    μ_s N; beyond, the mass starts to slide the way they push, F = −μ_k N F̂_rest.

    The stop rule (stop(), which the engine applies after every step of every integrator, and
    STOP, the same rule in the handed-out program after its update). An integrator steps the law,
    which cannot stop a sliding mass: near rest it would push the velocity back and forth through
    0, a little each step (chatter). So after each step, with p the momentum along the table at
    the step's start and F the other forces along it there (F_rest),

        the mass comes to rest within the step   if p·(p + F Δt) ≤ μ_k N Δt |p|: against
                                                   friction its momentum along p̂ reaches 0
                                                   (always so for a mass at rest, p = 0),
        and static friction holds it             if |F| ≤ μ_s N;

    where both hold, the step ends where it began, at rest along the table: r along the table as
    at the start, p along it 0 (across the table the step stands). So friction can stop a mass
    but never reverse it, and a stopped mass stays exactly where it is, step after step, as long
    as the other forces are at most μ_s N: there is nothing to chatter. Where the other forces
    turn the mass round (a spring beyond the dead band |x| ≤ μ_s m g/k), the rule does not hold
    it and the step stands. The law and the rule are written with physics.forces.where and
    compare, so the fast loop traces them without guards: a choice made afresh at every step.
    """

    mu_k: object = 0.0
    mu_s: object = 0.0
    g: float = 9.8
    surface: object = (1.0, 0.0, 1.0)    # the axes along the table, 1 each: x and z
    conservative = False
    uses_velocity = True
    responds = True
    SINGLE_MASS = False        # it needs a table: switched_on refuses it in a single-mass scene, in one line
    LABEL = "friction"
    CONSTANTS = {
        "mu_k": Declared("1", 0, 100, symbol="μ_k", slider=True, slider_from_zero=True, default=0.0,
                         meaning="kinetic friction coefficient in F = −μ_k N v̂, N = m g"),
        "mu_s": Declared("1", 0, 100, symbol="μ_s", slider_from_zero=True, default=0.0, switch=True,
                         meaning="static friction coefficient: a mass at rest stays while the other "
                                 "forces along the table are at most μ_s N"),
        "g": Gravity.CONSTANTS["g"],
    }
    TERM = "Ffriction"
    VECTORS = {"surface": "surface"}
    PROGRAM = (("vs = vector({v}.x, 0, {v}.z)", "friction: the velocity and the other forces along the table"),
               ("Fs = vector({F_rest}.x, 0, {F_rest}.z)", ""),
               ("if mag(vs) > 0:", ""),
               ("    Ffriction = -{mu_k}*{m}*{g}*hat(vs)", "sliding: kinetic friction F = −μ_k N v̂, N = m g"),
               ("elif mag(Fs) <= {mu_s}*{m}*{g}:", ""),
               ("    Ffriction = -Fs", "at rest: static friction balances the others, up to μ_s N"),
               ("else:", ""),
               ("    Ffriction = -{mu_k}*{m}*{g}*hat(Fs)", "at rest, pushed harder: it starts to slide"))
    STOP = (("ps = vector({p_i}.x, 0, {p_i}.z)", "friction's stop rule: p and the other forces along the table, "
                                                  "at the step's start"),
            ("Fs = vector({F_rest}.x, 0, {F_rest}.z)", ""),
            ("if dot(ps, ps + Fs*dt) <= {mu_k}*{m}*{g}*dt*mag(ps) and mag(Fs) <= {mu_s}*{m}*{g}:",
             "it comes to rest within the step, and static friction can hold it"),
            ("    {r} = vector({r_i}.x, {r}.y, {r_i}.z)", "so it stays where it was, at rest along the table"),
            ("    {p} = vector(0, {p}.y, 0)", ""))

    def __post_init__(self):
        for name in ("mu_k", "mu_s"):
            object.__setattr__(self, name, _per_mass(getattr(self, name)))
        if np.any(np.asarray(self.mu_s) < np.asarray(self.mu_k)):
            raise ValueError(f"mu_s must be at least mu_k (got mu_s = {np.max(self.mu_s):g}, mu_k = "
                             f"{np.max(self.mu_k):g}): a mass at rest is held at least as firmly as a "
                             f"sliding one is slowed")
        if not self.g > 0:
            raise ValueError("friction needs a load N = m g, but g = 0 here: set g > 0 (a scene on a "
                             "table keeps gravity out of its forces; the table holds the mass up)")
        object.__setattr__(self, "surface", np.asarray(self.surface, dtype=float))

    @classmethod
    def switched_on(cls, **constants):
        """None where μ_k and μ_s are 0. A scene of one mass switches its forces on from its constants
        (physics.forces.switched_on), and none of them has a table: its mass hangs, or swings on its
        spring, with gravity on (g > 0), or lies on a frictionless table with gravity off (g = 0, no
        load N = m g). Friction there would do nothing or nonsense, so it is refused in one line,
        naming the scene that has a table (scenes/friction.py builds its Friction itself)."""
        if not (constants.get("mu_k", 0.0) or constants.get("mu_s", 0.0)):
            return None
        raise ValueError("friction needs a block sliding on a table, and this scene has none (its mass "
                         "hangs or swings on its spring, or lies on a frictionless table with g = 0): "
                         "leave mu_k and mu_s at 0 here; the friction scene puts a spring on a table "
                         "(python main.py friction)")

    def __call__(self, t, r, v, m, F_rest=None):
        m = m[:, None]
        v_s = v * self.surface                              # the velocity along the table
        moving = compare(row_dot(v_s, v_s)[:, None], ">", 0.0)
        # sliding: F = −μ_k N v̂ with N = m g, written (−μ_k m g) (v/|v|) as the program writes it
        sliding = -self.mu_k * m * self.g * _direction(v_s, moving)
        if F_rest is None:                                  # alone: only its part along v counts
            return where(moving, sliding, 0.0)
        # at rest: static friction balances the other forces along the table up to μ_s N, F = −F_rest;
        # beyond that the mass starts to slide the way they push it, F = −μ_k N F̂_rest
        F_s = F_rest * self.surface
        pushed = compare(row_dot(F_s, F_s)[:, None], ">", 0.0)
        held = compare(magnitude(F_s), "<=", self.mu_s * m * self.g)
        starting = -self.mu_k * m * self.g * _direction(F_s, pushed)
        return where(moving, sliding, where(held, -F_s, starting))

    def stop(self, *, t, r, p, m, F_rest, dt, r_f, p_f):
        m = m[:, None]
        p_s, F_s = p * self.surface, F_rest * self.surface      # along the table, at the step's start
        # p·(p + F Δt) ≤ μ_k N Δt |p|: sliding against friction it comes to rest within the step
        rests = compare(row_dot(p_s, p_s + F_s * dt)[:, None], "<=", self.mu_k * m * self.g * dt * magnitude(p_s))
        holds = compare(magnitude(F_s), "<=", self.mu_s * m * self.g)   # |F| ≤ μ_s N: static friction holds it
        keep = where(where(rests, holds, False), self.surface != 0, False)
        return where(keep, r, r_f), where(keep, 0.0, p_f)

    def acts_on(self, count):
        return (_column(self.mu_k, count) != 0) | (_column(self.mu_s, count) != 0)


def _direction(a, nonzero):
    """â = a/|a| of each row where `nonzero`, else a (then 0): the hat() of the program."""
    return a / np.sqrt(where(nonzero, row_dot(a, a)[:, None], 1.0))

