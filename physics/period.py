"""The period of an oscillation: measured from the motion as a lab does, and from the formula.

Measured. A lab reads the period off a record of x(t) by timing the crossings of the centre (the
equilibrium) in the same direction, here upward (x rising through the centre):

    T_n = t_(n+1) − t_n           each cycle's period, s
    T   = mean of the T_n         over every cycle so far
    spread = their standard deviation (1 s.d., from n − 1), s

Each crossing time is found between the two samples on either side of the centre by a straight
line through them. At the centre x(t) is nearly straight (its curvature is x'' = −ω² x − γ v
= −γ v there, zero without damping), so the error of that line is small, and it shows in the
spread. A period needs at least MIN_CYCLES cycles (MIN_CYCLES + 1 crossings); with fewer the
motion does not repeat (over-damped, a mass that runs away or falls) or the run is too short,
and :func:`measured_period` says which in a sentence.

Formula. For the linear oscillator m x'' + b x' + k x = 0,

    ω_d = √(k/m − (b/2m)²),   T = 2π / ω_d

with k and b/m read from what the forces declare to the stability judgement
(physics.forces.Force.rates: "stiffness" and "damping"). It describes the motion only where a
closed form does (the caller says so: closed_form), where no force changes with time (a driving
force makes the motion settle at the drive's period) and where b² < 4mk (it swings at all).

Nothing here imports a front end: the page, --headless, --json and the offline page read these.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .forces import net_force
from .stability import rates

MIN_CYCLES = 2            # cycles a measured period needs: its spread needs two
SAMPLES_PER_PERIOD = 200  # samples per cycle a record needs for the crossings (record_spacing)
MAX_SAMPLES = 100_000     # samples a record for the period keeps at most: a long run is measured over its end


@dataclass(frozen=True)
class Period:
    """A period measured from the motion: the mean over `cycles` cycles, s, and their spread, s."""

    measured: float
    spread: float
    cycles: int


def upward_crossings(t, x, *, centre: float) -> np.ndarray:
    """The times, s, at which x rises through `centre` (from below it to at or above it), each
    on the straight line between the two samples around it. t (n,) s and x (n,) in any unit."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float) - centre
    below, after = x[:-1] < 0, x[1:] >= 0
    n = np.flatnonzero(below & after & np.isfinite(x[:-1]) & np.isfinite(x[1:]))
    # t* = t_n + (t_(n+1) − t_n) · (0 − x_n) / (x_(n+1) − x_n)
    return t[n] + (t[n + 1] - t[n]) * (-x[n]) / (x[n + 1] - x[n])


def period_from_crossings(times) -> Period | None:
    """The period from successive upward crossings of the centre, s: None with fewer than
    MIN_CYCLES cycles."""
    times = np.asarray(times, dtype=float)
    if len(times) < MIN_CYCLES + 1:
        return None
    cycles = np.diff(times)
    return Period(measured=float(np.mean(cycles)), spread=float(np.std(cycles, ddof=1)), cycles=len(cycles))


def measured_period(t, x, *, centre: float) -> Period | None:
    """The period of x(t) about `centre` (the equilibrium), from its upward crossings; None where
    it crosses fewer than MIN_CYCLES + 1 times (why_no_period says why)."""
    return period_from_crossings(upward_crossings(t, x, centre=centre))


def why_no_period(t, x, *, centre: float | None) -> str:
    """Why x(t) gives no measured period, in one sentence (for a report's note)."""
    if centre is None:
        return "the motion has no equilibrium to swing about (nothing pulls the mass back), so it does not repeat"
    crossings = len(upward_crossings(t, x, centre=centre))
    end = float(np.asarray(t)[-1]) if len(t) else 0.0
    return (f"the motion rises through its equilibrium only {crossings} time{'' if crossings == 1 else 's'} "
            f"by t = {end:.4g} s, and a period needs {MIN_CYCLES} whole cycles ({MIN_CYCLES + 1} crossings): "
            f"it does not repeat (damped too strongly to swing, or running away), or the run is too short")


class CrossingMeter:
    """Upward crossings of each mass's centre, gathered from samples that arrive a few at a time
    (the page's run): the same times upward_crossings gives for the whole record at once.

    centres  (N,) the centre of each mass, in the unit of the samples (nan: none, no crossings)
    """

    def __init__(self, centres):
        self.centres = np.asarray(centres, dtype=float)
        self.clear()

    def clear(self) -> None:
        self.times: list[list[float]] = [[] for _ in self.centres]
        self._last = None     # (t, x of each mass) of the latest sample: the bridge to the next ones

    def add(self, t, x) -> None:
        """Samples t (n,) s and x (n, N) of every mass, in time order after the ones before."""
        t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float).reshape(len(t), -1)
        if not len(t):
            return
        if self._last is not None:
            t, x = np.concatenate([[self._last[0]], t]), np.concatenate([[self._last[1]], x])
        for i, centre in enumerate(self.centres):
            if math.isfinite(centre):
                self.times[i] += upward_crossings(t, x[:, i], centre=centre).tolist()
        self._last = (t[-1], x[-1])

    def period(self, i: int) -> Period | None:
        """Mass i's period from its crossings so far."""
        return period_from_crossings(self.times[i])


def is_driven(forces, state) -> bool:
    """Whether a force changes with time at fixed positions and velocities (a driving force):
    the net force at the start, at a few times, compared."""
    v = state.v
    at = [net_force(forces, t, state.r, v, state.m) for t in (0.0, 0.37, 1.91, 7.3)]
    return any(not np.allclose(at[0], other, rtol=1e-12, atol=0.0) for other in at[1:])


def formula_period(forces, state, *, closed_form) -> tuple[np.ndarray | None, str]:
    """T = 2π/ω_d of each mass, (N,) s, with ω_d = √(k/m − (b/2m)²) from the rates the forces
    declare; and, where a mass has none, why, in one sentence ('' when every mass has one).

    closed_form  whether a closed form describes each mass's motion (True, False, or (N,) of
                 them: a Model's exact is not None, and finite for that mass): the formula is the
                 closed form's period, and means nothing for motion it does not cover.
    Returns (None, why) where no mass has one; nan for a mass without one.
    """
    covered = np.broadcast_to(np.asarray(closed_form, dtype=bool), (state.count,))
    if not covered.any():
        return None, "no closed form covers these forces, so there is no formula for the period"
    if is_driven(forces, state):
        return None, ("a force changes with time (a drive), and the motion settles at the drive's period, "
                      "not at 2π/ω_d")
    each = rates(forces, state.m)
    omega_squared = each.omega ** 2 - (each.damping / 2.0) ** 2      # ω_d² = k/m − (b/2m)², b/m = damping
    swings = covered & (omega_squared > 0)
    period = np.full(state.count, np.nan)
    period[swings] = 2.0 * np.pi / np.sqrt(omega_squared[swings])
    if not swings.any():
        return None, "b² ≥ 4mk: the damping is too strong for the motion to swing, so it has no period"
    why = []
    if not covered.all():
        why.append("no closed form covers the forces on some masses")
    if (covered & ~swings).any():
        why.append("on some masses the damping is too strong to swing (b² ≥ 4mk)")
    return period, "; ".join(why)


def record_spacing(forces, m, dt: float) -> float | None:
    """How often, s, a run must be recorded for its period to be measured: SAMPLES_PER_PERIOD
    samples per cycle of the fastest spring (√(k/m)), never more often than every step; None
    where no spring pulls a mass back (there is no period to measure)."""
    omega = rates(forces, m).omega
    fastest = float(np.max(omega)) if len(omega) else 0.0
    if not fastest > 0:
        return None
    return max(float(dt), 2.0 * math.pi / fastest / SAMPLES_PER_PERIOD)


def record_window(forces, m, dt: float, *, t0: float, until: float) -> tuple[float, float] | None:
    """(spacing, start), s: record every `spacing` seconds from `start` to `until` to measure the
    period (record_spacing), at most MAX_SAMPLES samples, so a very long run is measured over its
    last MAX_SAMPLES / SAMPLES_PER_PERIOD cycles; None where there is no period to measure."""
    spacing = record_spacing(forces, m, dt)
    if spacing is None:
        return None
    return spacing, max(float(t0), float(until) - MAX_SAMPLES * spacing)
