"""The data's own swing, before any model: its noise, its frequencies, whether it starts held still,
and the damped sinusoid that fits it best.

    noise       the scatter of the points about any smooth curve through them, from the n-th
                differences of neighbouring points (n = 2 to 6): a difference of order n takes a
                smooth swing down by (ω h)ⁿ but multiplies white noise of σ by √C(2n, n); the
                smallest estimate of σ over n is the one least spoilt by the swing
    frequencies the peaks of the spectrum, strongest first, of swings with 4 samples a period or more
    held        the stretch at the start where the mass sits still before it is let go
    damped      y = c + e^(−λ(t − t₁)) (A cos ω(t − t₁) + B sin ω(t − t₁)) by least squares: ω and λ
                by Gauss-Newton, A, B and c solved exactly for each (numpy only)

The fit (lab/fit.py) starts from this swing, and uses its noise to choose the model's Δt
(lab/settings.py). The swing is also an independent check on the fitted constants for a free spring.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from math import comb

import numpy as np

MOST_POINTS = 4000           # points the swing is fitted on at most (a longer record is thinned evenly)


@dataclass(frozen=True)
class Swing:
    """The damped sinusoid through the data: ω (rad/s), λ (1/s, the amplitude's decay rate), the RMS
    of what it leaves (m), the time its fit starts from (s), and its half swing there (m)."""

    omega: float
    decay: float
    rms: float
    start: float
    amplitude: float


def noise(y) -> float:
    """The data's point-to-point scatter, m: an estimate of the noise σ on each point (see the
    module's docstring), robust to a few outliers (the median absolute difference)."""
    y = np.asarray(y, dtype=float)
    found = math.inf
    for n in range(2, 7):
        if len(y) < n + 8:
            break
        difference = np.diff(y, n=n)
        sigma = 1.4826 * float(np.median(np.abs(difference - np.median(difference)))) / math.sqrt(comb(2 * n, n))
        found = min(found, sigma)
    return found if math.isfinite(found) else 0.0


def frequencies(t, y) -> list[float]:
    """Candidate angular frequencies of the data's swing, rad/s, strongest first: the two highest
    peaks of its spectrum, and of its spectrum times the frequency (the step at a release from rest
    leaks into the lowest frequencies, white noise into the highest, so neither alone is safe).
    The data are resampled evenly and padded four times; each peak is refined by a parabola."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    if len(t) < 8:
        return []
    interval = float(np.median(np.diff(t)))
    if not interval > 0:
        return []
    every = max(1, int(len(t) // 200_000))
    even = np.arange(t[0], t[-1], interval * every)
    centred = np.interp(even, t, y)
    centred = centred - np.mean(centred)
    size = 4 * len(even)
    plain = np.abs(np.fft.rfft(centred, n=size)) ** 2
    lowest = 4                                      # bins below one cycle over the record
    highest = len(plain) // 2                       # a swing with fewer than 4 samples a period is noise
    if highest <= lowest + 2:
        return []
    plain = plain[:highest + 1]
    found = []
    for power in (plain, plain * np.arange(len(plain))):
        inner = power[lowest:-1]
        peaks = np.flatnonzero((inner[1:-1] > inner[:-2]) & (inner[1:-1] >= inner[2:])) + 1
        for i in sorted(peaks, key=lambda i: -inner[i])[:2]:
            peak = lowest + int(i)
            a, b, c = np.log(power[peak - 1:peak + 2] + 1e-300)
            shift = 0.5 * (a - c) / (a - 2 * b + c) if a - 2 * b + c < 0 else 0.0
            omega = 2 * math.pi * (peak + shift) / (size * interval * every)
            if all(abs(omega - other) > 0.02 * other for other in found):
                found.append(omega)
    return found


def held(t, y, sigma: float) -> float:
    """The time the data leave the value they start at (the release, where the record begins with the
    mass held still), s; t[0] where they move from the first points on."""
    y = np.asarray(y, dtype=float)
    if len(y) < 12:
        return float(t[0])
    first = float(np.median(y[:4]))
    swing = float(np.ptp(y))
    moved = np.abs(y - first) > max(6 * sigma, 0.02 * swing)
    index = int(np.argmax(moved)) if moved.any() else 0
    if index < 5:
        return float(t[0])
    still = np.abs(y[:index] - first) <= max(2 * sigma, 0.005 * swing)
    last = int(np.flatnonzero(still)[-1]) if still.any() else 0
    return float(t[last])


def _design(t, omega, decay):
    envelope = np.exp(-decay * t)
    return np.column_stack([np.ones_like(t), envelope * np.cos(omega * t), envelope * np.sin(omega * t)])


def _cost(t, y, omega, decay) -> float:
    X = _design(t, omega, decay)
    coefficients, *_ = np.linalg.lstsq(X, y, rcond=None)
    residual = y - X @ coefficients
    return float(residual @ residual)


def _residual(t, y, omega, decay):
    X = _design(t, omega, decay)
    coefficients, *_ = np.linalg.lstsq(X, y, rcond=None)
    return y - X @ coefficients, coefficients


def damped(t, y, *, start: float | None = None) -> Swing | None:
    """The damped sinusoid that fits the data from `start` on (default: the first point), or None
    where the data have no swing to fit (fewer than 12 points, or no peak in their spectrum)."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    keep = t >= (t[0] if start is None else start)
    t, y = t[keep], y[keep]
    if len(t) < 12:
        return None
    every = max(1, len(t) // MOST_POINTS)
    t1 = float(t[0])
    u, y = t[::every] - t1, y[::every]
    span = float(u[-1])
    candidates = frequencies(u, y)
    if not candidates or not span > 0:
        return None
    # a coarse grid about each peak, then Gauss-Newton on (ω, λ) from the best
    best = (math.inf, 0.0, 0.0)
    for omega0 in candidates[:4]:
        for omega in omega0 * np.linspace(0.95, 1.05, 11):
            for ratio in (0.0, 0.003, 0.01, 0.03, 0.1, 0.3):
                cost = _cost(u, y, omega, ratio * omega)
                if cost < best[0]:
                    best = (cost, float(omega), float(ratio * omega))
    cost, omega, decay = best
    for _ in range(30):
        residual, _ = _residual(u, y, omega, decay)
        h_w, h_d = 1e-6 * omega, 1e-6 * max(omega, 1.0)
        J = np.column_stack([(_residual(u, y, omega + h_w, decay)[0] - residual) / h_w,
                             (_residual(u, y, omega, decay + h_d)[0] - residual) / h_d])
        step, *_ = np.linalg.lstsq(J, -residual, rcond=None)
        for scale in (1.0, 0.5, 0.25, 0.1):
            trial = (omega + scale * step[0], max(decay + scale * step[1], 0.0))
            trial_cost = _cost(u, y, *trial) if trial[0] > 0 else math.inf
            if trial_cost <= cost:
                break
        else:
            break
        done = abs(trial[0] - omega) <= 1e-10 * omega and abs(trial[1] - decay) <= 1e-10 * max(omega, 1.0)
        (omega, decay), cost = trial, trial_cost
        if done:
            break
    residual, coefficients = _residual(u, y, omega, decay)
    return Swing(omega=omega, decay=decay, rms=float(np.sqrt(np.mean(residual ** 2))), start=t1,
                 amplitude=float(math.hypot(coefficients[1], coefficients[2])))
