"""Is Δt small enough? The one judgement of stability, for every path (command line, browser, sweeps).

An explicit step multiplies a small oscillation by a fixed matrix each time. Near equilibrium every
mass obeys, along its spring,

    x'' = −ω² x − γ x'        ω² = k/m (the spring),  γ = b/m + ρ C A |v| / m (damping and drag)

where the drag's γ is its rate at the present speed: the slope of ½ C A ρ |v| v with respect to v
is ρ C A |v|. One step of an integrator maps (x, v) to M (x, v), and the motion grows without
bound exactly when an eigenvalue of M is larger than 1 in size (the spectral radius ρ(M) > 1).
Rather than keep a formula per method, we take M from the method itself: step the unit states
(x, v) = (1, 0) and (0, 1) of this linear system once, with the registry's own step function.
So whatever a method does, its stability is judged by what it really does, and a new method
needs no new formula. Two classic results come out of it:

    euler-cromer, verlet:  stable while ω·Δt < 2 (undamped), and (ω·Δt)² + 2 γ Δt < 4 with damping
    euler:                 grows at every Δt on an undamped spring; damping γ > ω² Δt tames it

The largest stable Δt is found by bisection on Δt. Driving forces do not change M (they add to
the motion, they do not multiply it), so they do not limit Δt.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .forces import LinearDamping, Spring
from .rows import magnitude
from .integrators import INTEGRATORS, describe
from .state import make_state

TOLERANCE = 1e-14      # a spectral radius this close above 1 is round-off, not growth
# At a tiny Δt every method's growth per step is tiny too; what tells a method that grows at every
# Δt (euler: ρ ≈ 1 + ½(ωΔt)²) from one that does not is growth comparable to (ωΔt)² itself.
RELATIVE = 1e-3
BISECTIONS = 60
BOUNDARY = 1e-6        # the growth counted for a step exactly at the limit (an eigenvalue of −1)


def amplification(method: str, *, omega, rate, dt: float) -> np.ndarray:
    """ρ(M): how much one step of `method` multiplies the oscillation x'' = −ω² x − γ x', per pair.

    omega (rad/s) and rate γ (s⁻¹) are numbers or arrays of the same shape; returns an array.
    """
    omega, rate = np.broadcast_arrays(np.atleast_1d(np.asarray(omega, float)),
                                      np.atleast_1d(np.asarray(rate, float)))
    count = omega.size
    # Two unit masses per pair, in 1-D: one starts at x = 1 at rest, the other at x = 0 with v = 1.
    x0 = np.tile([1.0, 0.0], count)[:, None]
    v0 = np.tile([0.0, 1.0], count)[:, None]
    k = np.repeat(omega.ravel() ** 2, 2)
    b = np.repeat(rate.ravel(), 2)
    forces = (Spring(k=k, L0=0.0, anchor=(0.0,)), LinearDamping(b=b))
    with np.errstate(over="ignore", invalid="ignore"):
        after = INTEGRATORS[method](make_state(r=x0, v=v0, m=1.0), forces, float(dt))
        x, v = after.r[:, 0].reshape(count, 2), after.p[:, 0].reshape(count, 2)
        # M = [[x(1,0), x(0,1)], [v(1,0), v(0,1)]]; its eigenvalues are (tr ± √(tr² − 4 det)) / 2.
        trace = x[:, 0] + v[:, 1]
        det = x[:, 0] * v[:, 1] - x[:, 1] * v[:, 0]
        root = np.sqrt((trace * trace - 4.0 * det).astype(complex))
        radius = np.maximum(np.abs(trace + root), np.abs(trace - root)) / 2.0
        # An eigenvalue of exactly −1 (1 + tr + det = 0) is the limit itself, ω·Δt = 2 for euler-cromer:
        # the motion flips sign each step without decaying, and with no damping grows linearly.
        radius = np.where(np.abs(1.0 + trace + det) <= 1e-12 * (1.0 + np.abs(trace) + np.abs(det)),
                          np.maximum(radius, 1.0 + BOUNDARY), radius)
    return np.where(np.isfinite(radius), radius, np.inf).reshape(omega.shape)


def largest_stable_dt(method: str, *, omega: float, rate: float) -> float:
    """The largest Δt, s, at which `method` keeps x'' = −ω² x − γ x' from growing.

    math.inf without spring or damping (nothing to be unstable), 0.0 if it grows at every Δt.
    """
    scale = max(omega, rate)
    if scale == 0:
        return math.inf

    def stable(dt):
        return _grows(amplification(method, omega=omega, rate=rate, dt=dt)[0], dt * scale) is False

    low, high = 1e-6 / scale, 100.0 / scale
    if not stable(low):
        return 0.0
    if stable(high):
        return math.inf
    for _ in range(BISECTIONS):
        middle = math.sqrt(low * high)
        low, high = (middle, high) if stable(middle) else (low, middle)
    return low


@dataclass(frozen=True)
class Rates:
    """The rates that limit Δt, per mass: ω (rad/s), b/m and the drag's ρCA|v|/m (s⁻¹), and |v| (m/s)."""

    omega: np.ndarray
    damping: np.ndarray
    drag: np.ndarray
    speed: np.ndarray

    @property
    def gamma(self) -> np.ndarray:
        return self.damping + self.drag


def rates(forces, m, v=None) -> Rates:
    """Each mass's ω, b/m and drag rate ρCA|v|/m at velocity v (rest if None).

    Each force says what it adds (physics.forces.Force.rates): stiffness from an anchor, a joint
    to another mass, a damping or a drag rate. ω is √(Σk/m) of the springs from anchors; a mass
    joined to others by springs gets the fastest normal mode of its chain
    (:func:`fastest_angular_frequency`), which is faster than any single √(k/m).
    """
    m = np.asarray(m, dtype=float)
    count = len(m)
    speed = np.zeros(count) if v is None else magnitude(np.asarray(v, dtype=float))[:, 0]
    k, joints, damping, drag = _terms(forces, m, speed)
    omega = np.sqrt(k / m)
    joined = sorted({index % count for i, j, _ in joints for index in (i, j)})
    if joined:
        omega[joined] = np.maximum(omega[joined], fastest_angular_frequency(forces, m))
    return Rates(omega=omega, damping=damping, drag=drag, speed=speed)


def joints(forces, m) -> list:
    """The springs between masses that the forces declare, [(i, j, k N/m)] (none for a row of
    independent springs)."""
    m = np.asarray(m, dtype=float)
    return _terms(forces, m, np.zeros(len(m)))[1]


def _terms(forces, m, speed) -> tuple:
    """The forces' declared rates, summed: (k from anchors N/m, joints [(i, j, k)], damping s⁻¹,
    drag s⁻¹), each per mass."""
    count = len(m)
    k, damping, drag = np.zeros(count), np.zeros(count), np.zeros(count)
    joints = []
    for force in forces:
        declared = getattr(force, "rates", None)     # a bare function of (t, r, v, m) declares none
        terms = declared(m, speed) if declared else {}
        k = k + terms.get("stiffness", 0.0)
        damping = damping + terms.get("damping", 0.0)
        drag = drag + terms.get("drag", 0.0)
        if "joint" in terms:
            joints.append(terms["joint"])
    return k, joints, damping, drag


def fastest_angular_frequency(forces, m) -> float:
    """The fastest natural angular frequency of the springs and masses, rad/s (0 without springs).

    One mass on a spring from an anchor: ω = √(k/m). Masses joined by springs between them (a
    chain) move in normal modes, and the fastest one is faster than any single √(k/m): for a
    uniform chain it approaches 2√(k/m). Along the springs the motion obeys M x'' = −K x, with
    the stiffness matrix

        K_ii = Σ k of the springs on mass i,   K_ij = −k of the spring joining i and j,

    and the normal modes' ω² are the eigenvalues of M^(−1/2) K M^(−1/2); we return the largest ω.
    (Sideways, a stretched spring is softer, k (1 − L0/|L|), so the modes along the springs are the
    fastest.)
    """
    m = np.asarray(m, dtype=float)
    k_anchor, joints, _, _ = _terms(forces, m, np.zeros(len(m)))   # N/m: springs from a fixed anchor, per mass
    omega_sq = float(np.max(k_anchor / m, initial=0.0))
    if joints:
        coupled = sorted({index % len(m) for i, j, _ in joints for index in (i, j)})
        row = {mass: n for n, mass in enumerate(coupled)}
        K = np.diag(k_anchor[coupled])
        for i, j, k in joints:
            i, j = row[i % len(m)], row[j % len(m)]
            K[i, i] += k
            K[j, j] += k
            K[i, j] -= k
            K[j, i] -= k
        scale = 1.0 / np.sqrt(m[coupled])
        omega_sq = max(omega_sq, float(np.linalg.eigvalsh(scale[:, None] * K * scale[None, :])[-1]))
    return float(np.sqrt(max(omega_sq, 0.0)))


@dataclass(frozen=True)
class Verdict:
    """The judgement of one Δt: does the motion grow, by how much per step, and why.

    stable    True if no mass's oscillation grows from step to step
    growth    the largest amplification per step, ρ(M) (≤ 1 when stable)
    dt_max    the largest stable Δt for the worst mass and its method, s (inf: any; 0: none)
    method    the method of the worst mass
    cause     what limits Δt: "spring", "damping", "drag", "spring and damping", or "" if stable
    message   one sentence naming Δt, the cause and the limit it implies (None if stable)
    """

    stable: bool
    growth: float
    dt_max: float
    method: str
    cause: str
    message: str | None

    @property
    def past_limit(self) -> bool:
        """Unstable although a smaller Δt would be stable: Δt is past the method's limit."""
        return not self.stable and self.dt_max > 0


def judge(forces, m, methods, dt: float, v=None, *, ignore=()) -> Verdict:
    """Judge Δt for these forces, masses and methods (one name per mass), at velocities v (or rest).

    Masses in `ignore` (those a scene expects to run away) are left out of the judgement.

    The worst mass decides. Its message names the real cause: the spring (ω·Δt against the
    method's limit), the damping (b/m), the drag (ρCA|v|/m at the present speed) or two of them
    together, and the Δt they make necessary; for a method that grows at every Δt (euler on an
    undamped spring) it says so and how fast the motion grows.
    """
    m = np.asarray(m, dtype=float)
    methods = tuple(methods)
    r = rates(forces, m, v)
    growth = _growth(r, methods, dt)
    growth[list(ignore)] = 0.0
    worst = int(np.argmax(growth))
    method = methods[worst] if methods else describe(methods)
    scale = float(max(r.omega[worst], r.gamma[worst]))
    if not _grows(growth[worst], dt * scale):
        return Verdict(True, float(growth[worst]), math.inf, method, "", None)
    omega, damping, drag = (float(x[worst]) for x in (r.omega, r.damping, r.drag))
    dt_max = largest_stable_dt(method, omega=omega, rate=damping + drag)
    cause = _cause(method, omega=omega, damping=damping, drag=drag, dt_max=dt_max)
    return Verdict(False, float(growth[worst]), dt_max, method, cause,
                   _message(method, dt=dt, dt_max=dt_max, cause=cause, growth=float(growth[worst]),
                            omega=omega, damping=damping, drag=drag, speed=float(r.speed[worst])))


def growing(forces, m, methods, dt: float, v=None) -> np.ndarray:
    """Which masses' oscillations grow from step to step with their methods at this Δt, (N,) bool."""
    r = rates(forces, np.asarray(m, dtype=float), v)
    growth = _growth(r, tuple(methods), dt)
    return np.array([_grows(g, dt * max(w, gamma)) for g, w, gamma in zip(growth, r.omega, r.gamma)],
                    dtype=bool)


def _growth(r: Rates, methods, dt: float) -> np.ndarray:
    """ρ(M) of each mass with its own method."""
    growth = np.ones(len(methods))
    for name in set(methods):
        rows = [i for i, method in enumerate(methods) if method == name]
        growth[rows] = amplification(name, omega=r.omega[rows], rate=r.gamma[rows], dt=dt)
    return growth


def _grows(radius: float, size: float) -> bool:
    """Whether a spectral radius means growth, for a step of `size` = Δt × the fastest rate."""
    return bool(radius > 1.0 + TOLERANCE + RELATIVE * min(size, 1e-3) ** 2)


def _cause(method, *, omega, damping, drag, dt_max) -> str:
    """Which rate alone implies (within 1 %) the limit that all of them together imply."""
    if dt_max == 0:
        return "spring"
    alone = {"spring": largest_stable_dt(method, omega=omega, rate=0.0),
             "damping": largest_stable_dt(method, omega=0.0, rate=damping),
             "drag": largest_stable_dt(method, omega=0.0, rate=drag)}
    close = [name for name, limit in alone.items() if math.isclose(limit, dt_max, rel_tol=0.01)]
    if close:
        return close[0]
    present = [name for name, rate in (("spring", omega), ("damping", damping), ("drag", drag)) if rate > 0]
    return " and ".join(present)


def _message(method, *, dt, dt_max, cause, growth, omega, damping, drag, speed) -> str:
    spring = f"ω = {omega:.4g} rad/s, √(k/m) for one mass"
    what = {"spring": f"the spring ({spring})",
            "damping": f"the damping (b/m = {damping:.4g} s⁻¹)",
            "drag": f"the drag (ρCA|v|/m = {drag:.4g} s⁻¹ at |v| = {speed:.4g} m/s)"}
    if dt_max == 0:
        return (f"dt = {dt:g} s: {method} is unstable on a spring at every dt ({spring}; the motion "
                f"grows about {100 * (growth - 1):.3g} % each step): use euler-cromer, verlet or rk4")
    named = " and ".join(what[part] for part in cause.split(" and "))
    entry = INTEGRATORS[method]
    rule = (f", {entry.damped_rule}" if "damping" in cause and entry.damped_rule else
            f", ω·dt < {entry.omega_dt_limit:.3g}" if cause == "spring" and entry.omega_dt_limit else "")
    verb = "makes" if " and " not in cause else "make"
    limit, digits = f"{dt_max:.4g}", 6
    while float(f"{dt:.{digits}g}") != dt and float(f"{dt:.{digits}g}") <= float(limit) and digits < 17:
        digits += 1   # dt = 1.0000001 s against dt < 1 s, not dt = 1 s
    return f"dt = {dt:.{digits}g} s, but {named} {verb} dt < {limit} s necessary for {method}{rule}"
