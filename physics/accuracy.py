"""Is Δt small enough to be right, not only stable? Accuracy beside stability, in one judgement.

A stable Δt can still be far from the real motion: on the page's Simple Example (ω = 2 rad/s)
Δt = 0.9 s gives ω·Δt = 1.8, inside euler-cromer's limit of 2, yet within a few periods the mass
swings above its anchor. :func:`judge_dt` asks both questions at once, and every front end asks it.

The measure is step doubling (Richardson's error estimate). Run the same engine
(physics/simulate.py) over a window twice, with Δt and with Δt/2, and compare the positions at the
times both reach. A method of order p has a global error e(Δt) ≈ C Δt^p, so

    r_Δt − r_Δt/2 ≈ C Δt^p (1 − 2^−p)    and    e(Δt) ≈ |r_Δt − r_Δt/2| · 2^p / (2^p − 1)

with p from the integrator registry. The error is read as a fraction of the size of the motion
(the farthest each mass gets from its start in the window), the largest over the window and over
the masses. Unlike E − W_nc it needs no zero of energy and it works for every force, damping and
driving included; unlike the exact solution it exists for every scene.

    window    WINDOW_PERIODS periods of the slowest spring (ω = √(k/m)), or WINDOW_PERIODS × 1/(b/m)
              where there is no spring: a few swings, whatever the question time (the page and the
              command line judge the same Δt alike), cut to STEP_BUDGET steps of Δt
    masses    a row of more than MAX_JUDGED independent masses (resonance) is judged on MAX_JUDGED
              of them spread evenly along it, so the judgement costs the same for any row
    warning   the error is more than WARN_ABOVE of the motion's size: a curve visibly off
    advice    a Δt of the form 1, 2 or 5 × 10ⁿ, from e ∝ Δt^p, that brings the error within
              SUGGEST_WITHIN; it is checked by the same measure before it is named

Masses whose motion grows (euler on an undamped spring; those a scene expects to run away) are
left out: the stability verdict already speaks for them, and a judgement that is unstable gets no
accuracy verdict at all.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields, is_dataclass, replace

import numpy as np

from .integrators import INTEGRATORS
from .rounding import round_down  # noqa: F401 (the suggested Δt, and the tests' name for it)
from .simulate import BlowUpError, Simulation, every
from .stability import Verdict, growing, joints, judge, rates
from .state import State, make_state

WINDOW_PERIODS = 3           # periods of the slowest spring over which accuracy is judged
STEP_BUDGET = 2_000          # most steps of Δt in the window (the Δt/2 run takes twice as many)
MIN_STEPS = 4                # the window is never shorter than this many steps of Δt
MAX_JUDGED = 8               # masses of a row judged (a sample spread along a longer row)
WARN_ABOVE = 0.2             # error, as a fraction of the motion's size, that draws the warning
SUGGEST_WITHIN = 0.01        # error, as a fraction of the motion's size, the suggested Δt keeps to
SAFETY = 0.8                 # the suggestion aims this far below what e ∝ Δt^p says is enough
TRIES = 4                    # Δt's tried (each checked by the same measure) before naming none


@dataclass(frozen=True)
class Accuracy:
    """How far a run at Δt strays from the real motion, as step doubling estimates it.

    error        the largest error in position, as a fraction of the motion's size (0.05: 5 %)
    window       the time the error was measured over, s
    accurate     error ≤ WARN_ABOVE
    dt           the Δt judged, s
    dt_advised   a Δt that keeps the error within SUGGEST_WITHIN, s (None if accurate, or if none
                 was found within TRIES)
    message      the one line for the page and the command line (None if accurate)
    """

    error: float
    window: float
    accurate: bool
    dt: float
    dt_advised: float | None = None
    message: str | None = None


@dataclass(frozen=True)
class Judgement:
    """Both verdicts on one Δt: stability (physics.stability.Verdict) and accuracy (None when the
    motion is unstable, or cannot be judged: the stability verdict then says all there is)."""

    stability: Verdict
    accuracy: Accuracy | None

    @property
    def advice(self) -> str | None:
        """The accuracy warning, when Δt is stable but inaccurate; else None."""
        return None if self.accuracy is None else self.accuracy.message


def judge_dt(state: State, forces, methods, dt: float, *, ignore=()) -> Judgement:
    """Judge Δt for stability and for accuracy: the one judgement every front end asks.

    state    the initial state (its velocities also set the drag's rate for stability)
    methods  one integrator name per mass
    ignore   masses a scene expects to run away, left out of both verdicts
    """
    methods = tuple(methods)
    stability = judge(forces, state.m, methods, dt, v=state.v, ignore=ignore)
    if not stability.stable:
        return Judgement(stability, None)
    left_out = set(int(i) for i in ignore) | set(np.flatnonzero(growing(forces, state.m, methods, dt)).tolist())
    return Judgement(stability, accuracy(state, forces, methods, dt, ignore=sorted(left_out)))


def accuracy(state: State, forces, methods, dt: float, *, ignore=()) -> Accuracy | None:
    """The step-doubling estimate at Δt, with a Δt to use where it is inaccurate (see the module).

    None if the trial runs blow up (the run itself will say why) or no mass is left to judge.
    """
    state, forces, methods, ignore = _sample(state, tuple(forces), tuple(methods), ignore)
    judged = [i for i in range(state.count) if i not in set(ignore)]
    if not judged:
        return None
    window = _window(state, forces)
    error = _error(state, forces, methods, dt, window=window, ignore=ignore)
    if error is None:
        return None
    if error <= WARN_ABOVE:
        return Accuracy(error=error, window=window, accurate=True, dt=dt)
    order = min(INTEGRATORS[methods[i]].order for i in judged)
    advised = _advise(state, forces, methods, dt, error=error, order=order, window=window, ignore=ignore)
    return Accuracy(error=error, window=window, accurate=False, dt=dt, dt_advised=advised,
                    message=accuracy_message(dt=dt, error=error, window=window, advised=advised))


def _advise(state, forces, methods, dt, *, error, order, window, ignore) -> float | None:
    """The largest Δt tried that keeps the error within SUGGEST_WITHIN, or None.

    From e ∝ Δt^p the next Δt to try is Δt (SUGGEST_WITHIN / e)^(1/p), a little less (SAFETY),
    rounded down to 1, 2 or 5 × 10ⁿ; each is measured as Δt was, so what is named really passes.
    Far from small Δt the error grows more slowly than Δt^p, so the first guess is often too
    small: a Δt that passes with room to spare leads to a larger one.
    """
    best, tried, guess, estimate = None, set(), dt, error
    for _ in range(TRIES):
        candidate = round_down(min(guess * (SUGGEST_WITHIN / estimate) ** (1.0 / order) * SAFETY, dt / 2))
        if candidate <= 0 or candidate in tried or (best is not None and candidate <= best):
            break
        tried.add(candidate)
        measured = None
        if judge(forces, state.m, methods, candidate, v=state.v, ignore=ignore).stable:
            measured = _error(state, forces, methods, candidate, window=window, ignore=ignore)
        if measured is not None and measured <= SUGGEST_WITHIN:
            best = candidate
        guess = candidate
        estimate = measured if measured else 4 * SUGGEST_WITHIN     # blew up, or nothing moved
        if best is not None and candidate * (SUGGEST_WITHIN / estimate) ** (1.0 / order) * SAFETY < 2 * best:
            break                                                    # no larger 1-2-5 value would pass
    return best


def accuracy_message(*, dt: float, error: float, window: float, advised: float | None) -> str:
    """`Δt = 0.9 s is stable but inaccurate here: ...`, the one line for the page and the command line."""
    line = (f"Δt = {dt:g} s is stable but inaccurate here: within {window:.3g} s the position is off by "
            f"about {percent(error)} of the size of the motion")
    if advised is None:
        return line + "; try a smaller Δt"
    return line + f"; Δt ≤ {advised:g} s keeps it within {percent(SUGGEST_WITHIN)}"


def percent(fraction: float) -> str:
    """0.0312 -> '3.1 %', 33.2 -> '3,300 %', 1e-7 -> '0.00001 %': two significant figures, plain digits."""
    value = float(f"{100 * fraction:.2g}")
    return f"{value:,.0f} %" if value >= 10 else f"{np.format_float_positional(value, trim='-')} %"


def _window(state: State, forces) -> float:
    """WINDOW_PERIODS periods of the slowest spring (or WINDOW_PERIODS / (b/m) with damping alone), s."""
    r = rates(forces, state.m, state.v)
    springs = r.omega[r.omega > 0]
    gamma = float(np.max(r.gamma, initial=0.0))
    if springs.size:
        return WINDOW_PERIODS * 2 * math.pi / float(np.min(springs))
    return WINDOW_PERIODS / gamma if gamma > 0 else math.inf


def _sample(state: State, forces: tuple, methods: tuple, ignore):
    """A row of more than MAX_JUDGED masses that do not act on each other, cut to MAX_JUDGED of
    them spread evenly along it (first and last included); anything else as it is.

    A force's per-mass values are the arrays with one row per mass, (N, 1) or (N, 3); they are cut
    to the same rows.
    """
    count = state.count
    if count <= MAX_JUDGED or joints(forces, state.m):
        return state, forces, methods, tuple(ignore)
    rows = np.unique(np.linspace(0, count - 1, MAX_JUDGED).round().astype(int))

    def cut(force):
        if not is_dataclass(force):   # a bare function of (t, r, v, m): its force follows r's rows
            return force
        per_mass = {f.name: getattr(force, f.name)[rows] for f in fields(force)
                    if isinstance(getattr(force, f.name), np.ndarray) and getattr(force, f.name).ndim == 2
                    and getattr(force, f.name).shape[0] == count}
        return replace(force, **per_mass) if per_mass else force

    position = {int(row): n for n, row in enumerate(rows)}
    return (make_state(r=state.r[rows], v=state.v[rows], m=state.m[rows], t=state.t),
            tuple(cut(force) for force in forces), tuple(methods[i] for i in rows),
            tuple(position[int(i)] for i in ignore if int(i) in position))


def _error(state: State, forces, methods, dt: float, *, window: float, ignore=()) -> float | None:
    """The step-doubling error at Δt over the window, as a fraction of the motion's size (None: blew up)."""
    steps = max(MIN_STEPS, min(STEP_BUDGET, math.ceil(window / dt - 1e-9) if math.isfinite(window) else STEP_BUDGET))
    try:
        coarse = Simulation(state, forces, dt=dt, integrator=methods, may_run_away=ignore, growth_limit=math.inf)
        fine = Simulation(state, forces, dt=dt / 2, integrator=methods, may_run_away=ignore, growth_limit=math.inf)
        r_coarse = coarse.advance(steps, record=every(1)).r
        r_fine = fine.advance(2 * steps, record=every(2)).r
    except (BlowUpError, ArithmeticError):
        return None
    order = np.array([INTEGRATORS[name].order for name in methods], dtype=float)
    # e(Δt) ≈ |r_Δt − r_Δt/2| · 2^p / (2^p − 1), the largest over the window
    with np.errstate(invalid="ignore", over="ignore"):
        error = np.max(np.linalg.norm(r_coarse - r_fine, axis=-1), axis=0) * 2 ** order / (2 ** order - 1)
        size = np.max(np.linalg.norm(r_fine - state.r[None], axis=-1), axis=0)
        reach = np.max(np.linalg.norm(r_fine, axis=-1), axis=0) + size
        moving = size > 1e-9 * reach          # a mass at rest (to round-off) has nothing to be wrong about
        fraction = np.where(moving, error / np.where(moving, size, 1.0), 0.0)
    fraction[list(ignore)] = 0.0
    if not np.all(np.isfinite(fraction)):
        return None
    return float(np.max(fraction))
