"""Where the fit starts (lab/compare.py): the data's own frequency and decay, the release point that
gives the data's swing, and the release time and position offset that match the data best on a
coarse grid.
"""
from __future__ import annotations

import math

import numpy as np

from . import LabError

START_POINTS = 2000              # points and release times the start's grid search uses at most
START_OFFSETS = 5000


def frequencies(t, y) -> list[float]:
    """Candidate angular frequencies of the data's swing, rad/s, strongest first: the two highest
    peaks of its spectrum, and of its spectrum times the frequency (the step at a release from rest
    leaks into the lowest frequencies, white noise into the highest, so neither alone is safe).
    The data are resampled evenly and padded four times; each peak is refined by a parabola."""
    interval = float(np.median(np.diff(t)))
    if not interval > 0 or len(t) < 8:
        return []
    even = np.arange(t[0], t[-1], interval)
    centred = np.interp(even, t, y)
    centred = centred - np.mean(centred)
    size = 4 * len(even)
    plain = np.abs(np.fft.rfft(centred, n=size)) ** 2
    lowest = 4                                      # bins below one cycle over the record
    if len(plain) <= lowest + 2:
        return []
    found = []
    for power in (plain, plain * np.arange(len(plain))):
        inner = power[lowest:-1]
        peaks = [i for i in range(1, len(inner) - 1) if inner[i - 1] < inner[i] >= inner[i + 1]]
        for i in sorted(peaks, key=lambda i: -inner[i])[:2]:
            peak = lowest + i
            a, b, c = np.log(power[peak - 1:peak + 2] + 1e-300)
            shift = 0.5 * (a - c) / (a - 2 * b + c) if a - 2 * b + c < 0 else 0.0
            omega = 2 * math.pi * (peak + shift) / (size * interval)
            if all(abs(omega - other) > 0.02 * other for other in found):
                found.append(omega)
    return found


def frequency(t, y) -> float | None:
    """The data's strongest angular frequency, rad/s (None if it has none)."""
    found = frequencies(t, y)
    return found[0] if found else None


def decay(t, y, m) -> float | None:
    """A damping constant from how the swing shrinks between the first and last quarter, kg/s."""
    quarter = max(len(t) // 4, 2)
    centred = y - np.median(y[len(y) // 2:])
    first, last = np.std(centred[:quarter]), np.std(centred[-quarter:])
    if first <= 0 or last <= 0 or first <= last:
        return None
    gap = np.mean(t[-quarter:]) - np.mean(t[:quarter])
    return 2.0 * m * math.log(first / last) / gap


def start_offsets(problem, theta_constants, t, y):
    """t_offset and position_offset to start from: the release time that matches the data best,
    searched over a grid of 1/50 period (linear interpolation, the position offset from the mean).
    A long record (200,000 rows) is searched on START_POINTS of its points and START_OFFSETS
    release times at most: it is only a start, and the full search took minutes."""
    span = t[-1] - t[0]
    omega = frequency(t, y) or 2 * math.pi / span
    period = 2 * math.pi / omega
    earliest, latest = t[0] - 0.5 * span - period, t[0] + 0.5 * span
    run = problem.run(theta_constants, t[-1] - earliest)
    grid = np.arange(0.0, run.end + run.dt / 2, run.dt)[: len(run.r)]
    every = max(1, len(t) // START_POINTS)
    t, y = t[::every], y[::every]
    best = (math.inf, t[0], 0.0)
    for t_offset in np.arange(earliest, latest, max(period / 50, (latest - earliest) / START_OFFSETS)):
        tau = t - t_offset
        model = np.where(tau < 0, run.r[0], np.interp(tau, grid, run.r))
        offset = float(np.mean(y - model))
        cost = float(np.sum((model + offset - y) ** 2))
        if cost < best[0]:
            best = (cost, float(t_offset), offset)
    return best[1], best[2], best[0]


def release(problem, start, j, t, y) -> float:
    """A start for r0 that gives the model the data's swing: the release point scaled about the
    middle of the model's swing (its equilibrium), by the data's half range over the model's. Where
    the mass starts from rest, the release point sets the amplitude, and the scene's own r0 may be
    far from the data's (a 0.3 m swing against the scene's 1.95 m left the fit in a false minimum)."""
    try:
        r = problem.run(start, float(t[-1] - t[0])).r
    except LabError:     # a start out of range: keep the scene's r0
        return start[j]
    middle, half = (np.max(r) + np.min(r)) / 2, np.ptp(r) / 2
    if not (half > 0 and np.isfinite(half)):
        return start[j]
    return float(middle + (start[j] - middle) * (np.ptp(y) / 2) / half)
