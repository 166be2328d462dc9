"""Integrators: pure functions (state, forces, dt) -> new state, chosen by name from INTEGRATORS.

Every method advances time by one fixed step Δt. Velocity always comes from momentum,
v = p / m (physics/state.py). F(t, r, v) below means the net force of the list of forces.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

from .forces import net_force, uses_velocity
from .state import State, velocity


def euler_cromer(state: State, forces, dt: float) -> State:
    """The page's momentum update (Euler-Cromer, semi-implicit Euler). The default.

        F_net = F(t, r_i, v_i)
        p_f = p_i + F_net Δt
        v_f = p_f / m
        r_f = r_i + v_f Δt          (v_avg ≈ v_f, as Matter & Interactions teaches)

    First order. On an undamped spring its energy stays bounded (it is symplectic), as long as
    ω Δt < 2 with ω = √(k/m); beyond that the motion grows without bound.
    Only damping and drag read v_i, so without them the step does not work it out.
    """
    t, r, p, m = state.t, state.r, state.p, state.m
    v_i = velocity(p, m) if uses_velocity(forces) else None
    F_net = net_force(forces, t, r, v_i, m)
    p_f = p + F_net * dt
    v_f = velocity(p_f, m)
    r_f = r + v_f * dt
    return State(t=t + dt, r=r_f, p=p_f, m=m)


def euler(state: State, forces, dt: float) -> State:
    """Forward (explicit) Euler: the position moves with the OLD velocity.

        F_net = F(t, r_i, v_i)
        r_f = r_i + v_i Δt
        p_f = p_i + F_net Δt

    First order. Unstable on a spring for every Δt: each step multiplies the energy by about
    1 + (ω Δt)², so the amplitude always grows. Kept to show why the page uses v_f instead.
    """
    t, r, p, m = state.t, state.r, state.p, state.m
    v_i = velocity(p, m)
    F_net = net_force(forces, t, r, v_i, m)
    return State(t=t + dt, r=r + v_i * dt, p=p + F_net * dt, m=m)


def verlet(state: State, forces, dt: float) -> State:
    """Velocity Verlet (leapfrog in kick-drift-kick form).

        p_½ = p_i + F(t, r_i, v_i) Δt/2
        r_f = r_i + (p_½ / m) Δt
        p_f = p_½ + F(t + Δt, r_f, v_f) Δt/2

    Second order and symplectic for forces of position alone, so the energy of an undamped spring
    stays bounded (for ω Δt < 2). Velocity-dependent forces (damping, drag) need v_f before it is
    known; we estimate it with one explicit half kick, v_f ≈ (p_½ + F(t + Δt, r_f, v_½) Δt/2) / m,
    which keeps the method second order at the cost of one extra force evaluation. Without
    velocity-dependent forces that extra evaluation is skipped.
    """
    t, r, p, m = state.t, state.r, state.p, state.m
    half = 0.5 * dt
    p_half = p + net_force(forces, t, r, velocity(p, m), m) * half
    v_half = velocity(p_half, m)
    r_f = r + v_half * dt
    v_guess = v_half
    if uses_velocity(forces):
        v_guess = velocity(p_half + net_force(forces, t + dt, r_f, v_half, m) * half, m)
    p_f = p_half + net_force(forces, t + dt, r_f, v_guess, m) * half
    return State(t=t + dt, r=r_f, p=p_f, m=m)


def rk4(state: State, forces, dt: float) -> State:
    """Classical fourth-order Runge-Kutta on (r, p), with r' = p/m and p' = F(t, r, p/m).

        k1 = f(t,        y)
        k2 = f(t + Δt/2, y + k1 Δt/2)
        k3 = f(t + Δt/2, y + k2 Δt/2)
        k4 = f(t + Δt,   y + k3 Δt)
        y_f = y + (k1 + 2 k2 + 2 k3 + k4) Δt/6

    Fourth order and very accurate per step, but not symplectic: over very long undamped runs its
    energy drifts slowly down. Four force evaluations per step.
    """
    t, r, p, m = state.t, state.r, state.p, state.m

    def slopes(t_, r_, p_):
        v_ = velocity(p_, m)
        return v_, net_force(forces, t_, r_, v_, m)

    half = 0.5 * dt
    dr1, dp1 = slopes(t, r, p)
    dr2, dp2 = slopes(t + half, _plus(r, dr1, half), _plus(p, dp1, half))
    dr3, dp3 = slopes(t + half, _plus(r, dr2, half), _plus(p, dp2, half))
    dr4, dp4 = slopes(t + dt, _plus(r, dr3, dt), _plus(p, dp3, dt))
    sixth = dt / 6.0
    return State(
        t=t + dt,
        r=_plus(r, _rk4_sum(dr1, dr2, dr3, dr4), sixth),
        p=_plus(p, _rk4_sum(dp1, dp2, dp3, dp4), sixth),
        m=m,
    )


def _plus(y, slope, h):
    """y + slope h, as a new array; `slope` is left as it was.

    The same numbers as `y + slope * h`, with one temporary array instead of two (IEEE + and ×
    are commutative, so the order of the operands does not change a bit).
    """
    step = slope * h
    step += y
    return step


def _rk4_sum(k1, k2, k3, k4):
    """k1 + 2 k2 + 2 k3 + k4, added in that order, in place: k2 and k3 are used up.

    The slopes are rk4's own new arrays, so reusing them saves three temporaries per sum.
    """
    k2 *= 2
    k2 += k1
    k3 *= 2
    k2 += k3
    k2 += k4
    return k2


@dataclass(frozen=True)
class Integrator:
    """Everything about one method, in one registry entry.

    step          the pure function (state, forces, dt) -> state; calling the entry calls it
    order         p in: global error ∝ Δt^p
    omega_dt_limit  ω·Δt above which the motion on an undamped spring grows without bound
                  (None: it grows at every Δt). A fact of the step itself: physics/stability.py
                  works every limit out from the step, and a test checks it against this number.
    rule          how the step uses F_net, in words, for the step table a student checks by hand
    kicks_once    True if p_f = p_i + F(t_i, r_i, v_i) Δt: one kick with the force at the start
    damped_rule   the stability condition with linear damping b, in words, where it is known
    """

    name: str
    step: Callable
    order: int
    omega_dt_limit: Optional[float]
    rule: str
    kicks_once: bool = False
    damped_rule: Optional[str] = None

    def __call__(self, state: State, forces, dt: float) -> State:
        return self.step(state, forces, dt)


INTEGRATORS = {entry.name: entry for entry in (
    Integrator("euler-cromer", euler_cromer, order=1, omega_dt_limit=2.0,
               rule="F_net = F(t_i, r_i, v_i) at the start of the step; p_f = p_i + F_net·Δt; "
                    "v_f = p_f / m; r_f = r_i + v_f·Δt", kicks_once=True,
               damped_rule="stable while (ω·dt)² + 2·(b/m)·dt < 4"),
    Integrator("euler", euler, order=1, omega_dt_limit=None,
               rule="F_net = F(t_i, r_i, v_i) at the start of the step; p_f = p_i + F_net·Δt; "
                    "r_f = r_i + v_i·Δt (the old velocity); v_f = p_f / m", kicks_once=True),
    Integrator("verlet", verlet, order=2, omega_dt_limit=2.0,
               rule="F_net = (p_f − p_i)/Δt, the average of the half kicks at the start and end of "
                    "the step; r_f = r_i + (p_i + F_i·Δt/2)/m·Δt"),
    Integrator("rk4", rk4, order=4, omega_dt_limit=2.0 * 2.0 ** 0.5,
               rule="F_net = (p_f − p_i)/Δt, RK4's weighted average of its four force samples; "
                    "r_f from RK4's weighted average of velocities"),
)}
DEFAULT_INTEGRATOR = "euler-cromer"


def methods_for(integrator, count: int) -> tuple[str, ...]:
    """The one representation of "which method steps which mass": a tuple of count names.

    integrator is one name (every mass) or a sequence of one name per mass. Raises ValueError
    for an unknown name or a sequence of the wrong length.
    """
    names = (integrator,) * count if isinstance(integrator, str) else tuple(integrator)
    unknown = [name for name in names if name not in INTEGRATORS]
    if unknown:
        raise ValueError(f"unknown integrator {unknown[0]!r} (choose from {', '.join(INTEGRATORS)})")
    if len(names) != count:
        raise ValueError(f"{len(names)} integrator names for {count} masses")
    return names


def describe(methods) -> str:
    """'rk4' when every mass uses rk4, else the names in mass order: 'euler, euler-cromer, ...'."""
    methods = tuple(methods)
    return methods[0] if len(set(methods)) == 1 else ", ".join(methods)
