"""Integrators: pure functions (state, forces, dt) -> new state, chosen by name from INTEGRATORS.

Every method advances time by one fixed step Δt. Velocity always comes from momentum,
v = p / m (physics/state.py). F(t, r, v) below means the net force of the list of forces.

Each method also gives its program template: the same update written out as lines of the
handed-out VPython program (export/ writes them). A template is a function

    template(F, *, r, p, m, uses_velocity) -> [(code, comment), ...]

of how the program spells the position, momentum and mass of one mass, where F(t, r, v, laws)
gives the lines that work out Fnet at time t, position r and velocity v (with each force's law as
its comment where laws is True). Its order of operations is the step's, so the program's numbers
are the engine's to round-off.
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


def euler_cromer_program(F, *, r, p, m, uses_velocity):
    """The page's update as the program writes it: v_i only where a force reads it, as the step."""
    lines = [(f"v = {p}/{m}", "velocity from momentum: v = p/m")] if uses_velocity else []
    return lines + F("t", r, "v", True) + [
        (f"{p} = {p} + Fnet*dt", "momentum principle: p_f = p_i + F_net Δt"),
        (f"{r} = {r} + {p}/{m}*dt", "r_f = r_i + v_f Δt, with v_f = p_f/m"),
    ]


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


def euler_program(F, *, r, p, m, uses_velocity):
    return [(f"v = {p}/{m}", "velocity from momentum: v_i = p_i/m")] + F("t", r, "v", True) + [
        (f"{r} = {r} + v*dt", "r_f = r_i + v_i Δt: the OLD velocity (why euler gains energy)"),
        (f"{p} = {p} + Fnet*dt", "momentum principle: p_f = p_i + F_net Δt"),
    ]


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


def verlet_program(F, *, r, p, m, uses_velocity):
    """verlet's half kick, drift and half kick; with a force that reads v, its guess of v_f first."""
    lines = [("# velocity Verlet: half a kick, a drift, half a kick", "")]
    if uses_velocity:
        lines.append((f"v = {p}/{m}", "velocity at the start of the step"))
    lines += F("t", r, "v", True)
    lines += [(f"{p} = {p} + Fnet*(dt/2)", "half a kick: p_½ = p_i + F_i Δt/2"),
              (f"{r} = {r} + {p}/{m}*dt", "drift: r_f = r_i + (p_½/m) Δt")]
    if uses_velocity:
        lines += [(f"v = {p}/{m}", ""),
                  ("for guess in range(2):", "F needs v_f, not known yet: guess it, then use it")]
        lines += _indented(F("(t + dt)", r, "v", False))
        lines.append((f"    v = ({p} + Fnet*(dt/2))/{m}", "v_f ≈ (p_½ + F Δt/2)/m"))
    else:
        lines += F("(t + dt)", r, "v", False)
    lines.append((f"{p} = {p} + Fnet*(dt/2)", "half a kick with the force at the end"))
    return lines


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


def rk4_program(F, *, r, p, m, uses_velocity):
    """rk4's four slopes in a for loop, and their weighted average."""
    return [
        ("dr = []", "rk4: the slopes dr/dt = v and dp/dt = F_net at four points of the step"),
        ("dp = []", ""),
        ("v = vector(0, 0, 0)", ""),
        ("Fnet = vector(0, 0, 0)", ""),
        ("for h in [0, dt/2, dt/2, dt]:", "each point: h ahead along the slope before"),
        (f"    r_s = {r} + v*h", ""),
        (f"    p_s = {p} + Fnet*h", ""),
        (f"    v = p_s/{m}", ""),
        *_indented(F("(t + h)", "r_s", "v", True)),
        ("    dr.append(v)", ""),
        ("    dp.append(Fnet)", ""),
        (f"{r} = {r} + (dr[0] + 2*dr[1] + 2*dr[2] + dr[3])*(dt/6)", "the slopes' weighted average"),
        (f"{p} = {p} + (dp[0] + 2*dp[1] + 2*dp[2] + dp[3])*(dt/6)", ""),
    ]


def _indented(lines):
    return [("    " + code, comment) for code, comment in lines]


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
    damped_rule   the stability condition with a damping rate γ (b/m of linear damping), in words, where it
                  is known: the message writes γ as the damping force's own rate (physics/stability.py)
    program       its template: the step as lines of the handed-out program (see the module's docstring)
    """

    name: str
    step: Callable
    order: int
    omega_dt_limit: Optional[float]
    rule: str
    kicks_once: bool = False
    damped_rule: Optional[str] = None
    program: Optional[Callable] = None

    def __call__(self, state: State, forces, dt: float) -> State:
        return self.step(state, forces, dt)


INTEGRATORS = {entry.name: entry for entry in (
    Integrator("euler-cromer", euler_cromer, order=1, omega_dt_limit=2.0,
               rule="F_net = F(t_i, r_i, v_i) at the start of the step; p_f = p_i + F_net·Δt; "
                    "v_f = p_f / m; r_f = r_i + v_f·Δt", kicks_once=True,
               damped_rule="stable while (ω·dt)² + 2·γ·dt < 4", program=euler_cromer_program),
    Integrator("euler", euler, order=1, omega_dt_limit=None,
               rule="F_net = F(t_i, r_i, v_i) at the start of the step; p_f = p_i + F_net·Δt; "
                    "r_f = r_i + v_i·Δt (the old velocity); v_f = p_f / m", kicks_once=True, program=euler_program),
    Integrator("verlet", verlet, order=2, omega_dt_limit=2.0,
               rule="F_net = (p_f − p_i)/Δt, the average of the half kicks at the start and end of "
                    "the step; r_f = r_i + (p_i + F_i·Δt/2)/m·Δt", program=verlet_program),
    Integrator("rk4", rk4, order=4, omega_dt_limit=2.0 * 2.0 ** 0.5,
               rule="F_net = (p_f − p_i)/Δt, RK4's weighted average of its four force samples; "
                    "r_f from RK4's weighted average of velocities", program=rk4_program),
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
