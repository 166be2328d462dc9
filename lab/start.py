"""Where the fit starts (lab/fit.py): constants that give the model the data's own frequency and decay,
and the time offset (with the data's sign) that matches the data best.

    matched   the fitted constants moved until the model's natural ω₀ and damping rate, as its forces
              declare them (physics/stability.py's rates: a spring's stiffness, a damping's b/m), are
              the data's damped sinusoid's (lab/swing.py): ω₀² = ω² + λ² and b/m = 2λ. Newton's
              method on the declared rates, which cost no run of the engine; a constant they do not
              depend on keeps its value.
    offsets   every time offset on a grid of a fiftieth of a period, over the record's first period
              and well beyond, each with its linear unknowns solved (lab/problem.py's costs), then the
              best valleys refined. A valley outside the first period is taken only where the data
              say so: its cost is lower by more than the noise allows (a χ² of 4). Of valleys the data
              cannot tell apart (a free swing with its release fitted looks the same let go at any
              turning point before the record), the release nearest the record's first point.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from physics.stability import rates
from scenes._constants import DECLARED

from .model_run import FitError, with_fitted

CLEARLY = 4.0            # χ² units by which a valley outside the first period must be lower to be taken
PRECISION = 1e-5         # of a grid step: how closely each valley's t_offset is found


@dataclass(frozen=True)
class Start:
    """A start of the fit: its constants, t_offset (model time 0 on the data's clock less t_first),
    the data's sign, and its cost (Σ residual² on the data the grid used, and on how many points)."""

    constants: tuple
    t_offset: float
    sign: int
    cost: float
    points: int


def _rates(setup, names, values, axis):
    model = with_fitted(setup, dict(zip(names, values)), axis).build()
    found = rates(model.forces, model.state.m)
    return float(found.omega[0]), float(found.damping[0])


def matched(setup, names, constants, *, omega: float, decay: float, axis: int):
    """The constants `names` (from `constants`) moved so that the model's declared ω₀ and damping
    rate are the swing's: ω₀ = √(ω² + λ²), b/m = 2λ (see the module's docstring); None where no fitted
    constant moves them (or the model declares no spring). A positive constant moves on a log scale
    (the rates are powers of it), one at 0 on a plain one. Raises FitError where the swing asks for
    a value outside a constant's declared range: the data's units, or a constant not fitted, are
    not what the scene takes them for."""
    target = np.array([math.sqrt(omega ** 2 + decay ** 2), 2.0 * decay])
    start = np.array(constants, dtype=float)
    logged = start > 0

    def values_of(x):
        return np.where(logged, np.exp(np.clip(x, -700, 700)), x)

    def misses(x):       # on a log scale where both start positive: a power of each constant is then a line
        omega0, damping = _rates(setup, names, values_of(x), axis)
        return np.array([math.log(omega0 / target[0]) if omega0 > 0 else -50.0,
                         (math.log(damping / target[1]) if damping > 0 else -50.0) if log_damping
                         else (damping - target[1]) / target[0]])

    x = np.where(logged, np.log(np.where(logged, start, 1.0)), start)
    try:
        omega_start, damping_start = _rates(setup, names, start, axis)
    except (ValueError, ZeroDivisionError, OverflowError):
        return None
    if not omega_start > 0:
        return None
    log_damping = damping_start > 0 and target[1] > 0
    for _ in range(12):
        try:
            miss = misses(x)
            if np.max(np.abs(miss)) < 1e-10:
                break
            J = np.empty((2, len(x)))
            for j in range(len(x)):
                h = 1e-6 if logged[j] else 1e-6 * max(abs(x[j]), 1e-3)
                moved = x.copy()
                moved[j] += h
                J[:, j] = (misses(moved) - miss) / h
        except (ValueError, ZeroDivisionError, OverflowError):   # the physics refuses these: judged below
            break
        if not np.any(np.abs(J) > 1e-12):
            return None
        x = x - np.linalg.pinv(J, rcond=1e-9) @ miss
    values = values_of(x)
    for name, value in zip(names, values):
        if name in DECLARED and not DECLARED[name].allows(float(value)):
            unit = setup.constants[name].unit
            raise FitError(f"--fit {name}: the data's swing (ω = {omega:.4g} rad/s, dying away at "
                           f"{decay:.3g} per s) asks for {name} = {value:.3g} {unit}, outside its range "
                           f"({DECLARED[name].words(unit)}); check the data's units (time in s, position in "
                           f"m) and the constants not fitted (--set ...)")
    return tuple(float(v) for v in values)


def offsets(problem, constants, *, period: float, sign=None, wide: bool = True, longest=np.inf,
            held: float = 0.0) -> list[Start]:
    """The best (t_offset, sign) for these constants, one per sign tried, each refined (see the
    module's docstring). t_offset runs over the first period of the record (a period before its
    first point to one after, and a quarter period about the time `held` the data leave the value
    they start at, where the record starts with the mass held still), and with `wide` over half the
    record before and after it, as far as a run of the model no longer than `longest` s reaches. Of
    valleys the data cannot tell apart, the one nearest `held` (the record's first point, where
    nothing was held)."""
    span = problem.span
    near = (min(-period, held - period / 4), max(period, held + period / 4))
    earliest = max(-min(0.5 * span, 50 * period) - period, -(0.95 * longest - 1.1 * span - problem.reach))
    far = (min(earliest, near[0]), min(0.5 * span, 50 * period)) if wide else near
    step = period / 50
    count = int((far[1] - far[0]) / step) + 1
    if count > 6000:                               # a long record: a coarser grid beyond the first period
        outer = np.linspace(far[0], far[1], 6000)
        grid = np.unique(np.concatenate([outer, np.arange(near[0], near[1], step)]))
    else:
        grid = np.linspace(far[0], far[1], count)
    found, points = problem.costs(constants, grid)
    signs = [sign] if sign is not None else list(found)
    starts = []
    for way in signs:
        costs = found.get(way, found.get(1))
        candidates = _valleys(grid, costs, near)
        refined = [_refine(problem, constants, way, t_offset, step, (grid[0], grid[-1])) for t_offset in candidates]
        lowest = min(cost for cost, _ in refined)
        # within the noise's χ² of 4, or where the data have no noise (the program's own run) within
        # what the refining leaves: a t_offset off by PRECISION of a step, at the swing's speed
        speed = 2 * math.pi / period * problem.scale
        allowed = lowest + max(CLEARLY * lowest / max(points - 3, 1), points * (speed * PRECISION * step) ** 2)
        inside = [(abs(t_offset - held), cost, t_offset) for cost, t_offset in refined
                  if cost <= allowed and near[0] <= t_offset <= near[1]]
        # of valleys the data cannot tell apart, the release nearest the record's first point
        cost, t_offset = min(inside)[1:] if inside else min(refined)
        starts.append(Start(tuple(constants), t_offset, way, cost, points))
    return starts


def _valleys(grid, costs, near, most: int = 6) -> list[float]:
    """The grid's local minima, lowest first (at most `most`), and the lowest ones inside the first
    period (a free swing's valleys, one a half period, may all cost alike)."""
    inner = np.flatnonzero((costs[1:-1] <= costs[:-2]) & (costs[1:-1] <= costs[2:])) + 1
    ends = [i for i in (0, len(costs) - 1) if len(costs) > 1]
    order = sorted(set(inner.tolist() + ends), key=lambda i: costs[i])
    inside = [i for i in order if near[0] <= grid[i] <= near[1]]
    return [float(grid[i]) for i in dict.fromkeys(order[:most] + inside[:4])]


def _refine(problem, constants, sign, t_offset, step, within):
    """(cost, t_offset): the grid's valley at t_offset narrowed to PRECISION of a grid step by golden
    section on the same thinned data (no new runs)."""
    def cost(x):
        return float(problem.costs(constants, [x])[0][sign if problem.mode != "scale" else 1][0])
    a, b = max(t_offset - step, within[0]), min(t_offset + step, within[1])
    golden = (math.sqrt(5) - 1) / 2
    c, d = b - golden * (b - a), a + golden * (b - a)
    fc, fd = cost(c), cost(d)
    while b - a > PRECISION * step:
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - golden * (b - a)
            fc = cost(c)
        else:
            a, c, fc = c, d, fd
            d = a + golden * (b - a)
            fd = cost(d)
    best = (fc, c) if fc < fd else (fd, d)
    here = cost(t_offset)
    return best if best[0] <= here else (here, t_offset)
