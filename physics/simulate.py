"""Running a model forward: many fixed steps of Δt, with a guard against numerical blow-up.

A run is the page's loop: repeat the chosen integrator's step until the question time. It also
watches for blow-up, which an explicit method hits when Δt is too large for the spring
(ω Δt > 2 for Euler-Cromer, with ω = √(k/m)) or for strong damping ((ω Δt)² + 2 (b/m) Δt > 4 for
Euler-Cromer), so that a run never returns NaN as an answer.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .energy import WorkMeter, report
from .forces import LinearDamping, Spring, SpringBetween, for_rows
from .compiled import compile_loop
from .integrators import INTEGRATORS, STABILITY_LIMIT_OMEGA_DT
from .state import State


CHECK_EVERY = 256          # steps between two blow-up checks
COMPILE_FROM_STEPS = 100   # shorter runs are not worth tracing and compiling a loop for
BLOCK_NUMBERS = 2 ** 17    # numbers per (rows, D) array (1 MB) when a big batch runs a block at a time


class BlowUpError(RuntimeError):
    """The state became non-finite or grew without bound: Δt is too large for this method.

    t is the time of the check that found it, in s.
    """

    t: float = math.nan


def fastest_angular_frequency(forces, m) -> float:
    """The fastest natural angular frequency of the springs and masses, rad/s (0 without springs).

    One mass on a spring from an anchor: ω = √(k/m). Masses joined by springs between them (a
    chain) move in normal modes, and the fastest one is faster than any single √(k/m): for a
    uniform chain it approaches 2√(k/m). Along the springs the motion obeys M x'' = −K x, with
    the stiffness matrix

        K_ii = Σ k of the springs on mass i,   K_ij = −k of the spring joining i and j,

    and the normal modes' ω² are the eigenvalues of M^(−1/2) K M^(−1/2); we return the largest ω.
    (Sideways, a stretched spring is softer, k (1 − L0/|L|), so the modes along the springs are the
    fastest.) Euler-Cromer steps each normal mode on its own, so ω·Δt < 2 must hold for this ω.
    """
    m = np.asarray(m, dtype=float)
    k_anchor = np.zeros(len(m))          # N/m: springs from a fixed anchor, per mass
    for force in forces:
        if isinstance(force, Spring):
            k_anchor += np.broadcast_to(force.k, (len(m), 1))[:, 0]
    joints = [force for force in forces if isinstance(force, SpringBetween)]
    omega_sq = float(np.max(k_anchor / m, initial=0.0))
    if joints:
        # Only the masses joined to others are coupled; the rest stay √(k/m) each.
        coupled = sorted({index % len(m) for joint in joints for index in (joint.i, joint.j)})
        row = {mass: n for n, mass in enumerate(coupled)}
        K = np.diag(k_anchor[coupled])
        for joint in joints:
            i, j = row[joint.i % len(m)], row[joint.j % len(m)]
            K[i, i] += joint.k
            K[j, j] += joint.k
            K[i, j] -= joint.k
            K[j, i] -= joint.k
        scale = 1.0 / np.sqrt(m[coupled])
        omega_sq = max(omega_sq, float(np.linalg.eigvalsh(scale[:, None] * K * scale[None, :])[-1]))
    return float(np.sqrt(max(omega_sq, 0.0)))


def fastest_damping_rate(forces, m) -> float:
    """b/m, the largest over linear damping and masses, s⁻¹ (0 without damping)."""
    rates = [np.max(np.broadcast_to(f.b, (len(m), 1))[:, 0] / m)
             for f in forces if isinstance(f, LinearDamping)]
    return float(max(rates, default=0.0))


def stability_advice(integrator, dt: float, omega: float, *, damping_rate: float = 0.0) -> str:
    """One sentence naming Δt and the stability limit of the method on this spring.

    damping_rate is b/m in s⁻¹. Damping is stepped explicitly too, so strong damping also limits
    Δt: one Euler-Cromer step multiplies (x, v) by a matrix with trace 2 − (ωΔt)² − bΔt/m and
    determinant 1 − bΔt/m, which is stable exactly while (ωΔt)² + 2 (b/m) Δt < 4.
    """
    if not isinstance(integrator, str):  # several methods side by side: the strictest one
        integrator = min(integrator, key=lambda name: STABILITY_LIMIT_OMEGA_DT[name] or 0.0)
    limit = STABILITY_LIMIT_OMEGA_DT[integrator]
    # The root of (ωΔt)² + 2 (b/m) Δt = 4, named when damping lowers the limit by over 1 %.
    dt_max = 4.0 / (damping_rate + math.hypot(damping_rate, 2.0 * omega)) if damping_rate > 0 else 0
    if integrator == "euler-cromer" and damping_rate > 0 and dt_max * omega < 0.99 * limit:
        return (f"dt = {dt:g} s, but euler-cromer with damping is stable here only for "
                f"(ω·dt)² + 2·(b/m)·dt < 4, i.e. dt < {dt_max:.4g} s "
                f"({_omega_words(omega)}, b/m = {damping_rate:.4g} s⁻¹)")
    damping_note = (f"; strong damping also limits dt: here b·dt/m = {damping_rate * dt:.3g}, "
                    f"and every method needs it below about 2" if damping_rate * dt > 1 else "")
    if omega == 0:
        return f"dt = {dt:g} s" + damping_note
    if limit is None:
        return (f"dt = {dt:g} s; {integrator} is unstable on a spring at every dt "
                f"({_omega_words(omega)}): use euler-cromer, verlet or rk4" + damping_note)
    return (f"dt = {dt:g} s, but {integrator} is stable on this spring only for ω·dt < {limit:.3g}, "
            f"i.e. dt < {limit / omega:.4g} s ({_omega_words(omega)})" + damping_note)


def _omega_words(omega: float) -> str:
    return f"ω = {omega:.4g} rad/s, the fastest natural angular frequency: √(k/m) for one mass on a spring"


def steps_to_reach(until: float, dt: float) -> int:
    """Number of steps of dt that reaches time `until` (rounding up, forgiving round-off)."""
    return max(0, math.ceil(until / dt - 1e-9))


@dataclass
class Trajectory:
    """Samples of a run: t (n,), r and p (n, N, 3); energy (dict of (n,) arrays, J) if recorded."""

    t: np.ndarray
    r: np.ndarray
    p: np.ndarray
    m: np.ndarray
    energy: dict | None = None

    @property
    def v(self) -> np.ndarray:
        return self.p / self.m[None, :, None]

    @property
    def final(self) -> State:
        """The last recorded state, ready to run on (copied into make_state's column-major layout)."""
        return State(t=float(self.t[-1]), r=np.asfortranarray(self.r[-1]), p=np.asfortranarray(self.p[-1]),
                     m=self.m)


def stepper(integrator):
    """The step function for an integrator name, or for a tuple of names, one per mass.

    A tuple steps mass i with integrator i (by stepping the whole state with each method and
    keeping row i), which is right only for masses that do not act on each other, such as the
    side-by-side comparison of integrators.
    """
    if isinstance(integrator, str):
        return INTEGRATORS[integrator]
    methods = [INTEGRATORS[name] for name in integrator]

    def mixed_step(state: State, forces, dt: float) -> State:
        results = {method: method(state, forces, dt) for method in set(methods)}
        rows = np.arange(state.count)
        r = np.stack([results[method].r[i] for i, method in zip(rows, methods)])
        p = np.stack([results[method].p[i] for i, method in zip(rows, methods)])
        return State(t=state.t + dt, r=r, p=p, m=state.m)
    return mixed_step


def run(state: State, forces, *, dt: float, until: float, integrator="euler-cromer",
        with_energy: bool = False, growth_limit: float = 1e6, record_every: int | None = 1,
        compiled: bool = True) -> Trajectory:
    """Step from state.t to `until` with fixed dt, recording the state every `record_every` steps.

    record_every = 1 (the default) records every step; n records every n-th step and always the
    final one; None records only the start and the final state, for big batches and long runs
    where the samples in between are not wanted. The steps themselves are the same either way.

    Raises BlowUpError if the state stops being finite, or any mass strays more than
    `growth_limit` times the starting size of the motion from its spring's anchor.

    For one mass (up to a few), the steps run as a loop over plain floats that the integrator's
    own vector code wrote (physics/compiled.py): the same arithmetic, several times faster than
    numpy calls on arrays of 3 numbers. compiled=False keeps to the numpy step throughout.
    A big batch of masses that do not act on one another runs a block of masses at a time.
    """
    step = stepper(integrator)
    n = steps_to_reach(until - state.t, dt)
    every = _recording_interval(n, record_every)
    samples = 1 + n // every + (n % every != 0)       # the start, every n-th step, the last one
    omega = fastest_angular_frequency(forces, state.m)
    limit = _motion_scale(state, forces, omega) * growth_limit
    t = np.empty(samples)
    r = np.empty((samples,) + state.r.shape)
    p = np.empty_like(r)
    t[0], r[0], p[0] = state.t, state.r, state.p
    meter = WorkMeter(state, forces) if with_energy else None
    energy = {key: np.empty(samples) for key in ("K", "U", "E", "W_nc", "E_minus_W_nc")} if with_energy else None
    if with_energy:
        _store(energy, 0, report(state, forces, meter.work))

    def check(now: State, now_forces):
        _check(now, now_forces, limit, lambda: stability_advice(
            integrator, dt, omega, damping_rate=fastest_damping_rate(forces, state.m)))

    compiled = compiled and isinstance(integrator, str)
    # A blow-up may overflow to inf and NaN between two checks; _check then reports it in one
    # sentence, so numpy's overflow warnings would only print noise.
    with np.errstate(over="ignore", invalid="ignore"):
        if _in_blocks(state, forces, integrator, with_energy):
            _steps_in_blocks(state, forces, step, dt, n, every, t, r, p, check, compiled=compiled)
        else:
            _steps(state, forces, step, dt, n, every, t, r, p, check, compiled=compiled,
                   meter=meter, energy=energy)
    return Trajectory(t=t, r=r, p=p, m=state.m, energy=energy)


def _steps(state: State, forces, step, dt: float, n: int, every: int, t, r, p, check, *,
           compiled: bool, meter=None, energy=None):
    """Take n steps from `state`, writing samples 1, 2, ... into t, r, p (and energy), and call
    check(state, forces) every CHECK_EVERY steps and after the last."""
    loop = (compile_loop(step, forces, dt, state)
            if compiled and meter is None and n >= COMPILE_FROM_STEPS else None)
    if loop is not None:
        _run_compiled(loop, state, n, every, t, r, p, check=lambda now: check(now, forces))
        return
    sample = 0
    for i in range(1, n + 1):
        state = step(state, forces, dt)
        if meter is not None:
            work = meter.advance(state)      # W_nc = ∫ P_nc dt needs every step
        if i % every == 0 or i == n:
            sample += 1
            t[sample], r[sample], p[sample] = state.t, state.r, state.p
            if meter is not None:
                _store(energy, sample, report(state, forces, work))
        if i % CHECK_EVERY == 0 or i == n:
            check(state, forces)


def _block_rows(state: State) -> int:
    """Masses in one block of _steps_in_blocks: BLOCK_NUMBERS numbers of r."""
    return BLOCK_NUMBERS // state.r.shape[1]


def _in_blocks(state: State, forces, integrator, with_energy: bool) -> bool:
    """Whether run() should step this batch in blocks of masses (see _steps_in_blocks)."""
    return (state.count > _block_rows(state) and isinstance(integrator, str) and not with_energy
            and not any(getattr(force, "couples_masses", True) for force in forces))


def _steps_in_blocks(state: State, forces, step, dt: float, n: int, every: int, t, r, p, check, *,
                     compiled: bool):
    """_steps for a block of masses at a time, each block from the start to the end.

    The masses do not act on one another, so each block's steps are exactly the steps it would
    take inside the whole batch. A block's arrays (BLOCK_NUMBERS numbers, 1 MB each) stay in the
    processor's cache through all its steps, where the whole batch's (24 MB each for 10⁶ masses
    in 3-D) would stream through memory on every step: 2–3× slower (docs/performance.md).
    Every block is checked at the same steps against the whole batch's limit, and the earliest
    blow-up of any block is the one raised, so the outcome is that of the whole batch.
    """
    count = state.count
    block = _block_rows(state)
    first = None
    for start in range(0, count, block):
        rows = slice(start, min(count, start + block))
        part = State(t=state.t, r=np.asfortranarray(state.r[rows]), p=np.asfortranarray(state.p[rows]),
                     m=state.m[rows])
        try:
            _steps(part, [for_rows(force, rows, count) for force in forces], step, dt, n, every,
                   t, r[:, rows], p[:, rows], check, compiled=compiled)
        except BlowUpError as error:
            if first is None or error.t < first.t:
                first = error
    if first is not None:
        raise first


def _run_compiled(loop, state: State, n: int, every: int, t, r, p, check):
    """The steps of run() through a compiled loop, recording into t, r, p (row 0 is the start)."""
    rows = []
    sample = 1
    done = 0
    while done < n:
        stop = min(n, done + CHECK_EVERY - done % CHECK_EVERY)
        state = loop.advance(state, done, stop, every=every, total=n, record=rows.append)
        done = stop
        if rows:
            recorded = np.array(rows)
            size = state.r.size
            end = sample + len(rows)
            t[sample:end] = recorded[:, 0]
            r[sample:end] = recorded[:, 1:size + 1].reshape((-1,) + state.r.shape)
            p[sample:end] = recorded[:, size + 1:].reshape((-1,) + state.r.shape)
            sample = end
            rows.clear()
        check(state)


def _recording_interval(n: int, record_every: int | None) -> int:
    """Steps between recorded states: record_every, or n when only the final state is wanted."""
    if record_every is None:
        return max(n, 1)
    if isinstance(record_every, bool) or not isinstance(record_every, (int, np.integer)) or record_every < 1:
        raise ValueError("record_every must be a whole number ≥ 1, or None for the final state only")
    return int(record_every)


def _store(energy, i, values):
    for key, value in values.items():
        energy[key][i] = value


def _motion_scale(state: State, forces, omega: float) -> float:
    """A generous size of the motion (m): start offset, speed/ω, and the spring's own length."""
    springs = [f for f in forces if isinstance(f, Spring)]
    if not springs or omega == 0:
        return math.inf
    spring = springs[0]
    offset = np.max(np.linalg.norm(state.r - spring.anchor, axis=-1))
    speed = np.max(np.linalg.norm(state.p / state.m[:, None], axis=-1))
    return float(offset + speed / omega + np.max(spring.L0) + 9.8 / omega**2 + 1.0)


def _check(state: State, forces, limit: float, advice):
    """Raise BlowUpError if the state is not finite or a mass is beyond `limit` from its anchor."""
    finite = np.all(np.isfinite(state.r)) and np.all(np.isfinite(state.p))
    springs = [f for f in forces if isinstance(f, Spring)]
    too_far = finite and springs and np.max(np.linalg.norm(state.r - springs[0].anchor, axis=-1)) > limit
    if not finite or too_far:
        error = BlowUpError(
            f"the simulation blew up by t = {state.t:.4g} s ({'non-finite state' if not finite else 'motion growing without bound'}): "
            + advice())
        error.t = state.t
        raise error
