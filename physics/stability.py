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

Exactly at the limit (ω·Δt = 2 for euler-cromer and verlet, undamped) M has the eigenvalue −1
twice and is not −I, so the motion neither decays nor grows exponentially: the position flips
sign at every step, x_n = (A + B n)(−1)ⁿ, and grows linearly unless B = 0, which takes one
start (the eigenvector of M). Which start that is, is again read from the method's own M
(:func:`at_limit`): for verlet it is rest, x_n = x0 (−1)ⁿ (Langtangen's fdm-book tests exactly
this), and from a moving start x_n = (−1)ⁿ (x0 − n v0 Δt); for euler-cromer it is v0 = 2 x0/Δt,
and from rest x_n = x0 (1 + 2n)(−1)ⁿ. Such a Δt runs, with a sentence saying which it is.
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


def step_matrix(method: str, *, omega, rate, dt: float) -> np.ndarray:
    """M, (..., 2, 2): one step of `method` on x'' = −ω² x − γ x' maps (x, v) to M (x, v).

    omega (rad/s) and rate γ (s⁻¹) are numbers or arrays of the same shape. The columns of M are
    what one step makes of the unit states (x, v) = (1, 0) and (0, 1).
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
    return np.stack([x, v], axis=1).reshape(*omega.shape, 2, 2)


def amplification(method: str, *, omega, rate, dt: float) -> np.ndarray:
    """ρ(M): how much one step of `method` multiplies the oscillation x'' = −ω² x − γ x', per pair.

    omega (rad/s) and rate γ (s⁻¹) are numbers or arrays of the same shape; returns an array.
    """
    M = step_matrix(method, omega=omega, rate=rate, dt=dt)
    with np.errstate(over="ignore", invalid="ignore"):
        # the eigenvalues of M are (tr ± √(tr² − 4 det)) / 2
        trace = M[..., 0, 0] + M[..., 1, 1]
        det = M[..., 0, 0] * M[..., 1, 1] - M[..., 0, 1] * M[..., 1, 0]
        root = np.sqrt((trace * trace - 4.0 * det).astype(complex))
        radius = np.maximum(np.abs(trace + root), np.abs(trace - root)) / 2.0
        # An eigenvalue of exactly −1 (1 + tr + det = 0) is the limit itself, ω·Δt = 2 for euler-cromer:
        # the motion flips sign each step without decaying, and from most starts grows linearly.
        radius = np.where(_minus_one(trace, det), np.maximum(radius, 1.0 + BOUNDARY), radius)
    return np.where(np.isfinite(radius), radius, np.inf)


def _minus_one(trace, det):
    """Whether −1 is an eigenvalue of a 2 × 2 matrix with this trace and determinant (to round-off)."""
    return np.abs(1.0 + trace + det) <= 1e-12 * (1.0 + np.abs(trace) + np.abs(det))


@dataclass(frozen=True)
class Limit:
    """What a step exactly at a method's stability limit does (an eigenvalue −1 of M).

    from_rest    True if a start from rest stays bounded (flips sign at every step, x_n = x0 (−1)ⁿ)
    any_start    True if every start stays bounded; else all but one grow linearly
    """

    from_rest: bool
    any_start: bool


def at_limit(method: str, *, omega: float, rate: float, dt: float) -> Limit | None:
    """What `method` does at this Δt if Δt is exactly its stability limit, else None.

    At the limit M has the eigenvalue −1. If its other eigenvalue, det M / −1, is smaller in size,
    every start stays bounded: the flipping part neither grows nor dies. If it is −1 too and M is
    not −I, M + I sends every start to the one eigenvector, and x_n = (A + B n)(−1)ⁿ grows by the
    same amount each step unless the start is itself that eigenvector: a start from rest, (1, 0),
    stays bounded exactly when M + I sends it to zero.
    """
    M = step_matrix(method, omega=omega, rate=rate, dt=dt)[0]
    trace, det = M[0, 0] + M[1, 1], M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    if not np.all(np.isfinite(M)) or not _minus_one(trace, det):
        return None
    other = -det                                   # the eigenvalues multiply to det M
    if abs(other) > 1.0 + TOLERANCE:
        return None                                # past the limit: the other eigenvalue grows
    N = M + np.eye(2)
    scale = 1e-12 * (1.0 + float(np.max(np.abs(M))))
    if abs(other) < 1.0 - 1e-9 or np.all(np.abs(N) <= scale):
        return Limit(from_rest=True, any_start=True)
    return Limit(from_rest=bool(np.all(np.abs(N[:, 0]) <= scale)), any_start=False)


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
class Part:
    """One force's share of a rate, for the message that names it: its label, how it writes its rate
    (Force.rate_words: "b/m", "c/m", "ρCA|v|/m", "√(k/m)") and its value per mass ((N,): N/m for
    stiffness, s⁻¹ for damping and drag)."""

    kind: str
    label: str
    words: str
    value: np.ndarray


@dataclass(frozen=True)
class Rates:
    """The rates that limit Δt, per mass: ω (rad/s), b/m and the drag's ρCA|v|/m (s⁻¹), and |v| (m/s);
    and each force's part of them (parts), so a message names the force and its own constant."""

    omega: np.ndarray
    damping: np.ndarray
    drag: np.ndarray
    speed: np.ndarray
    parts: tuple = ()

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
    return Rates(omega=omega, damping=damping, drag=drag, speed=speed, parts=_parts(forces, m, speed))


def _parts(forces, m, speed) -> tuple:
    """Each force's share of the stiffness, damping and drag, with its label and how it writes its rate."""
    parts = []
    for force in forces:
        declared = getattr(force, "rates", None)
        terms = declared(m, speed) if declared else {}
        for kind in ("stiffness", "damping", "drag"):
            if kind in terms:
                words = force.rate_words(kind) if hasattr(force, "rate_words") else "γ"
                label = getattr(force, "LABEL", "") or type(force).__name__
                parts.append(Part(kind, label, words, np.broadcast_to(np.asarray(terms[kind], float), (len(m),))))
    return tuple(parts)


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
    at_limit  True if Δt is exactly the method's limit (see at_limit): stable is then whether
              this start stays bounded, and message says what the motion does
    """

    stable: bool
    growth: float
    dt_max: float
    method: str
    cause: str
    message: str | None
    at_limit: bool = False

    @property
    def past_limit(self) -> bool:
        """Unstable although a smaller Δt would be stable: Δt is past the method's limit."""
        return not self.stable and self.dt_max > 0 and not self.at_limit


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
    limit = at_limit(method, omega=omega, rate=damping + drag, dt=dt) if method in INTEGRATORS else None
    if limit is not None:
        at_rest = v is None or not np.any(np.asarray(v, dtype=float)[worst])
        bounded = limit.any_start or (limit.from_rest and at_rest)
        return Verdict(bounded, 1.0, dt, method, "spring" if damping + drag == 0 else "spring and damping",
                       _limit_message(method, dt=dt, omega=omega, rate=damping + drag, bounded=bounded,
                                      limit=limit, at_rest=at_rest, named=_named(r, worst, omega=omega)),
                       at_limit=True)
    dt_max = largest_stable_dt(method, omega=omega, rate=damping + drag)
    cause = _cause(method, omega=omega, damping=damping, drag=drag, dt_max=dt_max)
    named = _named(r, worst, omega=omega)
    return Verdict(False, float(growth[worst]), dt_max, method, cause,
                   _message(method, dt=dt, dt_max=dt_max, cause=cause, growth=float(growth[worst]), named=named))


def _named(r: Rates, worst: int, *, omega: float) -> dict[str, str]:
    """What limits Δt, by kind, in the words of the forces that add to it at the worst mass, each
    with its own constant: "the spring (ω = 2 rad/s, √(k/m) for one mass)", "the damping (b/m =
    40 s⁻¹)", "the eddy brake (c/m = 40 s⁻¹)", "the drag (ρCA|v|/m = 3 s⁻¹ at |v| = 2 m/s)"."""
    speed = float(r.speed[worst])
    said: dict[str, list[str]] = {}
    for part in r.parts:
        value = float(part.value[worst])
        if not value > 0:
            continue
        if part.kind == "stiffness":
            text = f"the {part.label} (ω = {omega:.4g} rad/s, {part.words} for one mass)"
        elif part.kind == "damping":
            text = f"the {part.label} ({part.words} = {value:.4g} s⁻¹)"
        else:
            text = f"the {part.label} ({part.words} = {value:.4g} s⁻¹ at |v| = {speed:.4g} m/s)"
        said.setdefault(part.kind, []).append(text)
    words = {kind: [part.words for part in r.parts if part.kind == kind and float(part.value[worst]) > 0]
             for kind in ("stiffness", "damping", "drag")}
    return {"spring": " and ".join(said.get("stiffness", [])) or f"the spring (ω = {omega:.4g} rad/s)",
            "damping": " and ".join(said.get("damping", [])) or "the damping",
            "drag": " and ".join(said.get("drag", [])) or "the drag",
            "spring words": words["stiffness"][0] if len(words["stiffness"]) == 1 else "√(k/m)",
            "damping words": " + ".join(words["damping"]) or "γ"}


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


def _limit_message(method, *, dt, omega, rate, bounded, limit: Limit, at_rest, named: dict) -> str:
    """The one sentence for a Δt exactly at the limit: what the motion will do, started as it is."""
    damping = f", {named['damping words']} = {rate:.4g} s⁻¹" if rate else ""
    where = (f"dt = {dt:g} s is exactly {method}'s stability limit for the spring (ω = {omega:.4g} rad/s, "
             f"ω·dt = {omega * dt:.4g}{damping})")
    if limit.any_start:
        return f"{where}: the motion keeps a part that flips sign at every step, neither growing nor dying away"
    if bounded:
        return (f"{where}: started from rest, as here, the position flips sign at every step and stays "
                f"bounded (from a moving start it would grow by the same amount every step)")
    start = ("started from rest, as here" if at_rest else "started moving, as here" if limit.from_rest else
             "started moving, as here (from all but one start)")
    return (f"{where}: {start}, the position flips sign at every step and its swing grows by the same "
            f"amount every step (linearly, not exponentially); a dt below {dt:g} s keeps it bounded")


def _message(method, *, dt, dt_max, cause, growth, named: dict) -> str:
    """The sentence for a Δt past the limit: the forces that limit it, each by its label and its own
    constant (named, from _named), the Δt they make necessary, and the method's rule."""
    if dt_max == 0:
        spring = named["spring"].partition(" (")[2].rstrip(")")
        return (f"dt = {dt:g} s: {method} is unstable on a spring at every dt ({spring}; the motion "
                f"grows about {100 * (growth - 1):.3g} % each step): use euler-cromer, verlet or rk4")
    parts = [named[part] for part in cause.split(" and ")]
    what = " and ".join(parts)
    entry = INTEGRATORS[method]
    rate = named["damping words"]
    rule = (f", {entry.damped_rule.replace('γ', f'({rate})')}" if "damping" in cause and entry.damped_rule
            else f", ω·dt < {entry.omega_dt_limit:.3g}" if cause == "spring" and entry.omega_dt_limit else "")
    verb = "makes" if len(parts) == 1 and " and " not in what else "make"
    limit, digits = f"{dt_max:.4g}", 6
    while float(f"{dt:.{digits}g}") != dt and float(f"{dt:.{digits}g}") <= float(limit) and digits < 17:
        digits += 1   # dt = 1.0000001 s against dt < 1 s, not dt = 1 s
    return f"dt = {dt:.{digits}g} s, but {what} {verb} dt < {limit} s necessary for {method}{rule}"
