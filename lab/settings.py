"""Which integrator and Δt the model runs with in a fit, so that the model's own error is never taken
for the spring's.

    given   --integrator or --set dt (or the page's menu and slider): kept as chosen; after the fit the
            report says how far the values move at Δt/2, and the numbers are flagged when that move
            is larger than their σ (lab/trust.py), with a Δt that would do
    own     the data are this program's own --csv run (its header, one row per step): the model runs
            as that file was made, the scene's integrator at the file's own step, so the fit returns
            the constants the file was made with
    chosen  otherwise: the registry's method of the highest order, at the largest round Δt whose own
            error (step doubling: a run at Δt and one at Δt/2, physics/accuracy.py's measure) is
            below a tenth of the data's noise, and smaller still for a long record, whose σ is
            smaller: below noise / max(10, 3·√N) (an error that follows a constant's own change
            moves it by about error·√N/noise of its σ); after the fit, halved again while halving
            moves a value by more than a third of its σ

Step doubling: a method of order p has a global error e(Δt) ≈ C Δt^p, so e(Δt) ≈ |r_Δt − r_Δt/2| ·
2^p / (2^p − 1), and the Δt for an error e* is Δt · (e*/e)^(1/p).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from physics.integrators import INTEGRATORS
from physics.rounding import round_down, round_up

from .model_run import MAX_STEPS_PER_RUN, FitError

MOST_STEPS = 400_000       # steps of a chosen Δt per run of the model at most (a fit takes dozens)
TRIES = 3                  # Δt's tried by step doubling before the finest allowed is taken


@dataclass
class ModelSettings:
    """The integrator (None: the scene's) and Δt a fit's model runs with, who chose them, and, for a
    chosen Δt, its estimated error (m) against the target (m)."""

    integrator: str | None
    dt: float
    chosen_by: str            # "user", "data" (the program's own run) or "fit"
    error: float = math.nan
    target: float = math.nan


def best_method() -> str:
    """The registry's method of the highest order (rk4)."""
    return max(INTEGRATORS.values(), key=lambda entry: entry.order).name


def order_of(name: str | None, default: str) -> int:
    return INTEGRATORS[name or default].order


def target_error(noise: float, points: int, swing: float) -> float:
    """The model's own error a chosen Δt must keep below, m (see the module's docstring); never below
    a millionth of the swing (noise-free data are matched to that by a fine run in any case)."""
    return max(noise / max(10.0, 3.0 * math.sqrt(points)), 1e-7 * swing)


def error_at(problem, constants, dt: float, order: int) -> float:
    """The model's own RMS error at Δt over the record, by step doubling (two runs), m."""
    tau = np.linspace(0.0, problem.span, min(len(problem.t), 4000))
    coarse = problem.columns(constants, 0.0, dt=dt, tau=tau)[0]
    fine = problem.columns(constants, 0.0, dt=dt / 2, tau=tau)[0]
    return float(np.sqrt(np.mean((coarse - fine) ** 2))) * 2 ** order / (2 ** order - 1)


def choose_dt(problem, constants, *, order: int, period: float, noise: float, scene_dt: float) -> ModelSettings:
    """The largest round Δt whose own error is below target_error (see the module's docstring)."""
    target = target_error(noise, len(problem.t), problem.scale)
    finest = round_up(1.2 * (problem.span + period) / min(MOST_STEPS, MAX_STEPS_PER_RUN))
    dt = max(round_down(min(scene_dt, period / 20)), finest)
    error = math.nan
    for _ in range(TRIES):
        try:
            error = error_at(problem, constants, dt, order)
        except FitError:       # it blew up at this Δt: a quarter of it
            dt = max(round_down(dt / 4), finest)
            continue
        if error <= target or dt <= finest:
            break
        wanted = dt * (0.7 * target / error) ** (1.0 / order) if error > 0 else dt
        dt = max(round_down(min(wanted, dt / 2)), finest)
    return ModelSettings(integrator=None, dt=dt, chosen_by="fit", error=error, target=target)


def suggest_dt(dt: float, move_in_sigma: float, order: int) -> float:
    """A round Δt at which a move of `move_in_sigma` σ at Δt/2 shrinks to a third of σ (moves ∝ Δt^p)."""
    if not move_in_sigma > 0:
        return dt
    return round_down(dt * (1.0 / (3.0 * move_in_sigma)) ** (1.0 / order))
