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
from typing import NamedTuple

import numpy as np

from .forces import net_force
from .stability import rates

MIN_CYCLES = 2            # cycles a measured period needs: its spread needs two
SAMPLES_PER_PERIOD = 200  # samples per cycle a record needs for the crossings (record_spacing)
MAX_SAMPLES = 100_000     # samples a record for the period keeps at most: a long run is measured over its end


class Period(NamedTuple):
    """A period measured from the motion: the mean over `cycles` cycles, s, and their spread, s.
    (A named tuple: a run of 10⁴ masses makes 10⁴ of them, at half a frozen dataclass's cost.)"""

    measured: float
    spread: float
    cycles: int


def upward_crossings(t, x, *, centre: float) -> np.ndarray:
    """The times, s, at which x rises through `centre` (from below it to at or above it), each
    on the straight line between the two samples around it. t (n,) s and x (n,) in any unit."""
    _, times = _crossings(np.asarray(t, dtype=float), np.asarray(x, dtype=float)[:, None], np.array([centre]))
    return times


def _crossings(t: np.ndarray, x: np.ndarray, centre: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where each column of x (n, N) rises through its centre (N,) between two samples: (column,
    time s) of each crossing, in time order within a column, with t (n,) the samples' times.

    With y = x − centre, a crossing is y_n < 0 ≤ y_(n+1), both finite. x < centre is y < 0 for
    every x and centre (IEEE subtraction keeps the sign, and its NaN and inf compare alike), so
    y is worked out at the crossings alone: one comparison of the samples, not a subtraction too.
    """
    below = x < centre
    # below, then not below (at or above, or NaN); flat indices, several times faster than nonzero's
    k = np.flatnonzero(below[:-1] > below[1:])
    n, i = np.divmod(k, x.shape[1])
    flat = x.reshape(-1)
    y_n, y_next = flat[k] - centre[i], flat[k + x.shape[1]] - centre[i]
    finite = np.isfinite(y_n) & np.isfinite(y_next)     # −inf < 0 ≤ y, or NaN after: no crossing time
    n, i, y_n, y_next = n[finite], i[finite], y_n[finite], y_next[finite]
    # t* = t_n + (t_(n+1) − t_n) · (0 − y_n) / (y_(n+1) − y_n)
    return i, t[n] + (t[n + 1] - t[n]) * (-y_n) / (y_next - y_n)


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
        return why_none(None, crossings=0, end=0.0)
    end = float(np.asarray(t)[-1]) if len(t) else 0.0
    return why_none(centre, crossings=len(upward_crossings(t, x, centre=centre)), end=end)


def why_none(centre: float | None, *, crossings: int, end: float) -> str:
    """Why a motion about `centre` that crossed it upward `crossings` times by t = `end` s gives no
    measured period, in one sentence."""
    if centre is None:
        return "the motion has no equilibrium to swing about (nothing pulls the mass back), so it does not repeat"
    return (f"the motion rises through its equilibrium only {crossings} time{'' if crossings == 1 else 's'} "
            f"by t = {end:.4g} s, and a period needs {MIN_CYCLES} whole cycles ({MIN_CYCLES + 1} crossings): "
            f"it does not repeat (damped too strongly to swing, or running away), or the run is too short")


class CrossingMeter:
    """Upward crossings of each mass's centre, gathered from samples that arrive a few at a time
    (the page's run, a headless run's recorder): the same times upward_crossings gives for the
    whole record at once, worked out for every mass together (10⁴ masses cost about what one does
    in numpy calls), and nothing of the samples kept but the last.

    centres  (N,) the centre of each mass, in the unit of the samples (nan: none, no crossings)
    """

    def __init__(self, centres):
        self.centres = np.array(centres, dtype=float).reshape(-1)     # its own contiguous copy
        self._mass_type = np.min_scalar_type(len(self.centres))        # 2 bytes a crossing for 10⁴ masses
        self.clear()

    def clear(self) -> None:
        self._found: list[tuple[np.ndarray, np.ndarray]] = []   # (mass, time) of each add's crossings
        self._sorted = None           # every crossing time by mass, and where each mass's begin
        self._last = None             # (t, x of each mass) of the latest sample: the bridge to the next ones

    @property
    def end(self) -> float:
        """The time of the latest sample, s (0 before any)."""
        return 0.0 if self._last is None else float(self._last[0])

    def add(self, t, x) -> None:
        """Samples t (n,) s and x (n, N) of every mass, in time order after the ones before."""
        t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float).reshape(len(t), -1)
        if not len(t):
            return
        if self._last is not None:                      # the bridge from the last sample to the first new one
            self._keep(*_crossings(np.array([self._last[0], t[0]]), np.stack([self._last[1], x[0]]), self.centres))
        if len(t) > 1:
            self._keep(*_crossings(t, x, self.centres))
        self._last = (t[-1], x[-1].copy())

    def _keep(self, masses: np.ndarray, times: np.ndarray) -> None:
        if len(masses):
            self._found.append((masses.astype(self._mass_type), times))
            self._sorted = None

    def _by_mass(self) -> tuple[np.ndarray, np.ndarray]:
        """Every crossing time so far, s, mass by mass and in time order within each; and where
        each mass's times begin in it, (N + 1,) (mass i's are times[starts[i]:starts[i + 1]])."""
        if self._sorted is None:
            masses = np.concatenate([found[0] for found in self._found] or [np.zeros(0, dtype=self._mass_type)])
            times = np.concatenate([found[1] for found in self._found] or [np.zeros(0)])
            # by mass, in time order within each (a radix sort where the mass numbers fit 16 bits)
            order = np.argsort(masses, kind="stable")
            starts = np.concatenate([[0], np.cumsum(np.bincount(masses, minlength=len(self.centres)))])
            self._sorted = (times[order], starts)
        return self._sorted

    @property
    def times(self) -> list[np.ndarray]:
        """Each mass's upward crossing times so far, s, in order: a list of N arrays."""
        times, starts = self._by_mass()
        return np.split(times, starts[1:-1])

    def counts(self) -> np.ndarray:
        """How many times each mass has crossed its centre upward so far, (N,)."""
        return np.diff(self._by_mass()[1])

    def period(self, i: int) -> Period | None:
        """Mass i's period from its crossings so far."""
        times, starts = self._by_mass()
        return period_from_crossings(times[starts[i]:starts[i + 1]])

    def periods(self) -> list[Period | None]:
        """Every mass's period from its crossings so far: period(i) of each i, the same numbers,
        worked out for the masses with the same number of crossings together."""
        times, starts = self._by_mass()
        counts = np.diff(starts)
        found: list[Period | None] = [None] * len(counts)
        tally = np.bincount(counts)
        for count in np.flatnonzero(tally)[np.flatnonzero(tally) >= MIN_CYCLES + 1].tolist():
            masses = np.flatnonzero(counts == count)
            cycles = np.diff(times[starts[masses][:, None] + np.arange(count)], axis=1)
            # row by row these are np.mean and np.std of each mass's own cycles, bit for bit
            means, spreads = np.mean(cycles, axis=1), np.std(cycles, axis=1, ddof=1)
            for i, mean, spread in zip(masses.tolist(), means.tolist(), spreads.tolist()):
                found[i] = Period(mean, spread, count - 1)
        return found


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
